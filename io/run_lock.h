// One run at a time per output folder.
//
// `evas run` holds DIR/.evas-run.lock for the whole run with flock(2) and
// writes its pid, host and start time into it. A second run into the same
// folder finds the lock held and refuses before it touches any file there. The
// kernel releases the lock when the holder ends, however it ends, so a lock file
// left behind by a killed run is simply taken over. The file is removed when
// the run ends.
#pragma once

#include <filesystem>
#include <string>

namespace evas {

class RunLock {
 public:
  /// Takes the lock of the existing folder `dir`. Throws InputError naming the
  /// folder and the run that holds it (pid, host, start time), or naming the
  /// lock file when it cannot be created. On a file system without flock the run
  /// goes on unlocked and note() says so.
  explicit RunLock(const std::filesystem::path& dir);
  ~RunLock();
  RunLock(const RunLock&) = delete;
  RunLock& operator=(const RunLock&) = delete;

  const std::string& path() const { return path_; }
  /// Empty, or why the folder could not be locked (the run goes on).
  const std::string& note() const { return note_; }

 private:
  std::string path_;
  std::string note_;
  int fd_ = -1;
};

}  // namespace evas
