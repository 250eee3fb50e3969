// Keeps a results file valid when the disk fills up, and the program alive when
// a write of it fails.
//
// HDF5 1.10 does not survive a failed write: after a failed H5Fflush every
// later flush and the close fail too ("slist already enabled"), and the library
// crashes at exit closing the file again; the file on disk is half written
// (its superblock may promise bytes that never arrived, and then it cannot be
// opened). So HDF5 must never see a write fail:
//   preallocation  after every complete flush the guard allocates `bytes` on
//                  the file system beyond the end of the file (fallocate,
//                  FALLOC_FL_KEEP_SIZE), so the next flush writes into space
//                  the file already owns. When that allocation fails (ENOSPC,
//                  EDQUOT) the disk is full: after_flush() says so, the writer
//                  stops taking rows while the file is still complete, and its
//                  last writes (statistics, status "failed: ...") go into the
//                  space allocated before. The space left over is given back
//                  when the guard ends, for the summary.
//   guarded driver the file is written through the POSIX ("sec2") driver
//                  with its write and truncate wrapped: the first write that
//                  fails all the same (I/O error, a file system without
//                  fallocate) moves the open file onto an in-memory copy and
//                  is repeated there, so HDF5 goes on and closes normally;
//                  failed() then tells the writer, and the file on disk keeps
//                  what reached it before.
//
// Test hook (tests/test_run_faults.cpp; not meant for users), read here only:
//   EVAS_FAULT_WRITE_AFTER_ROWS=N  once N rows are on disk the disk is full:
//                                  allocating fails with ENOSPC, and so does
//                                  every write beyond the space the file owns
//   EVAS_FAULT_WRITE_EIO=1         instead, every later write fails with EIO
#pragma once

#include <hdf5.h>

#include <functional>
#include <string>

#include "io/hdf5_util.h"

namespace evas {

class WriteGuard {
 public:
  /// `bytes`: space kept allocated beyond the end of the file (<= 0: none).
  WriteGuard(const std::string& results_path, long long bytes);
  /// Gives back the allocated space beyond the end of the (closed) file.
  ~WriteGuard();
  WriteGuard(const WriteGuard&) = delete;
  WriteGuard& operator=(const WriteGuard&) = delete;

  /// Creates (truncates) the results file, written through the guard.
  h5::Handle create_file();
  /// After every complete flush (`rows_on_disk` rows written): 0, or the errno
  /// (ENOSPC, EDQUOT) that says the next rows may not fit.
  int after_flush(long rows_on_disk);
  /// A write failed (errno error()): the file now lives in memory.
  bool failed() const { return detached_; }
  /// The space kept allocated beyond the end of the file [bytes].
  long long bytes() const { return bytes_; }
  int error() const { return error_; }

  /// The guarded driver's write and truncate (for its C callbacks).
  int io(const std::function<herr_t()>& op, long long end);

 private:
  bool detach();

  std::string path_;
  long long bytes_ = 0;
  int fd_ = -1;             // the file's descriptor while it is open
  long long limit_ = -1;    // end of the space the file owns (-1: unknown)
  long fault_rows_ = -1;    // test hook
  bool fault_eio_ = false;  // test hook
  bool fault_on_ = false;
  bool detached_ = false;
  int error_ = 0;
};

}  // namespace evas
