#include "io/write_guard.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <map>
#include <vector>

namespace evas {

namespace {

constexpr long long kMaxDetachCopy = 1LL << 30;  // larger files are detached without a copy

// --- the guarded driver: sec2 with write and truncate going through WriteGuard::io

const H5FD_class_t* g_sec2 = nullptr;
H5FD_class_t g_class;
hid_t g_driver = -1;
std::map<int, WriteGuard*> g_guards;  // by file descriptor
WriteGuard* g_creating = nullptr;     // the guard whose file H5Fcreate is creating

int descriptor(H5FD_t* file) {
  void* handle = nullptr;
  if (g_sec2->get_handle(file, H5P_DEFAULT, &handle) < 0 || !handle) return -1;
  return *static_cast<int*>(handle);
}

WriteGuard* guard_of(H5FD_t* file) {
  const int fd = descriptor(file);
  const auto it = g_guards.find(fd);
  if (it != g_guards.end()) return it->second;
  if (g_creating && fd >= 0) return g_guards[fd] = g_creating;
  return nullptr;
}

herr_t guarded_write(H5FD_t* file, H5FD_mem_t type, hid_t dxpl, haddr_t addr, size_t size,
                     const void* buf) {
  const auto op = [&] { return g_sec2->write(file, type, dxpl, addr, size, buf); };
  WriteGuard* g = guard_of(file);
  return g ? g->io(op, static_cast<long long>(addr + size)) : op();
}

herr_t guarded_truncate(H5FD_t* file, hid_t dxpl, hbool_t closing) {
  const auto op = [&] { return g_sec2->truncate(file, dxpl, closing); };
  WriteGuard* g = guard_of(file);
  return g ? g->io(op, -1) : op();
}

hid_t guarded_driver() {
  if (g_driver >= 0 && H5Iis_valid(g_driver) > 0) return g_driver;
  g_driver = -1;
  // The sec2 class is not public: borrow it from a file it opens.
  H5FD_t* probe = H5FDopen("/dev/null", H5F_ACC_RDONLY, H5P_DEFAULT, haddr_t{1} << 40);
  if (!probe) return -1;
  g_sec2 = probe->cls;
  H5FDclose(probe);
  if (!g_sec2 || !g_sec2->write || !g_sec2->truncate || !g_sec2->get_handle) return -1;
  g_class = *g_sec2;
  g_class.name = "evas_guarded_sec2";
  g_class.terminate = nullptr;  // sec2's own would reset sec2's registration
  g_class.write = guarded_write;
  g_class.truncate = guarded_truncate;
  g_driver = H5FDregister(&g_class);
  h5::set_open_driver(g_driver);  // a results file read while written is the same file
  return g_driver;
}

long env_long(const char* name, long fallback) {
  const char* s = std::getenv(name);
  if (!s || !*s) return fallback;
  char* end = nullptr;
  const long v = std::strtol(s, &end, 10);
  return end && *end == '\0' ? v : fallback;
}

// Copies the file at `path` into `fd` (from offset 0). False on any error.
bool copy_into(const std::string& path, int fd) {
  const int src = open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (src < 0) return false;
  struct stat st {};
  bool ok = fstat(src, &st) == 0;
  if (ok && st.st_size > kMaxDetachCopy) {
    ok = ftruncate(fd, st.st_size) == 0;  // sparse: HDF5 rarely reads back what it wrote
  } else if (ok) {
    std::vector<char> buf(1 << 20);
    for (off_t off = 0; ok;) {
      const ssize_t n = pread(src, buf.data(), buf.size(), off);
      if (n == 0) break;
      ok = n > 0 && pwrite(fd, buf.data(), static_cast<std::size_t>(n), off) == n;
      off += n;
    }
  }
  close(src);
  return ok;
}

}  // namespace

WriteGuard::WriteGuard(const std::string& results_path, long long bytes)
    : path_(results_path), bytes_(bytes) {
  fault_rows_ = env_long("EVAS_FAULT_WRITE_AFTER_ROWS", -1);
  fault_eio_ = env_long("EVAS_FAULT_WRITE_EIO", 0) != 0;
}

WriteGuard::~WriteGuard() {
  for (auto it = g_guards.begin(); it != g_guards.end();)
    it = it->second == this ? g_guards.erase(it) : std::next(it);
  if (bytes_ > 0 && limit_ >= 0 && !detached_) {  // give back what was allocated beyond the end
    const int fd = open(path_.c_str(), O_WRONLY | O_CLOEXEC);
    struct stat st {};
    if (fd >= 0 && fstat(fd, &st) == 0 && ftruncate(fd, st.st_size) != 0) {
      // nothing to do: the space stays with the file
    }
    if (fd >= 0) close(fd);
  }
}

h5::Handle WriteGuard::create_file() {
  const hid_t driver = guarded_driver();
  h5::Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  if (driver >= 0 && fapl.valid() && H5Pset_driver(fapl, driver, nullptr) < 0) fapl.reset();
  g_creating = this;
  h5::Handle f(
      H5Fcreate(path_.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.valid() ? fapl.get() : H5P_DEFAULT),
      H5Fclose);
  g_creating = nullptr;
  if (!f.valid()) throw h5::Failure("cannot create the file (directory missing or not writable?)");
  void* handle = nullptr;
  if (H5Fget_vfd_handle(f, H5P_DEFAULT, &handle) >= 0 && handle) {
    fd_ = *static_cast<int*>(handle);
    if (driver >= 0) g_guards[fd_] = this;
  }
  return f;
}

int WriteGuard::after_flush(long rows_on_disk) {
  if (detached_) return error_;
  if (fault_rows_ >= 0 && rows_on_disk >= fault_rows_) fault_on_ = true;
  if (bytes_ <= 0 || fd_ < 0) return 0;
  struct stat st {};
  if (fstat(fd_, &st) != 0) return 0;
  int err = fault_on_ && !fault_eio_ ? ENOSPC : 0;
  if (!err && fallocate(fd_, FALLOC_FL_KEEP_SIZE, st.st_size, bytes_) != 0) err = errno;
  if (err == 0) {
    limit_ = st.st_size + bytes_;
    return 0;
  }
  if (err == ENOSPC || err == EDQUOT) return err;
  bytes_ = 0;  // a file system without fallocate: go on without
  return 0;
}

int WriteGuard::io(const std::function<herr_t()>& op, long long end) {
  if (!detached_) {
    int err = 0;
    if (fault_on_ && fault_eio_) err = EIO;
    if (fault_on_ && !fault_eio_ && end > limit_) err = ENOSPC;
    if (err == 0) {
      errno = 0;
      if (op() >= 0) return 0;
      err = errno ? errno : EIO;
    }
    error_ = err;
    if (!detach()) return -1;  // HDF5 sees the failure after all
  }
  return op();  // into the in-memory copy
}

bool WriteGuard::detach() {
  if (fd_ < 0) return false;
  int scratch = memfd_create("evas-detached-results", MFD_CLOEXEC);
  if (scratch < 0) scratch = open("/tmp", O_TMPFILE | O_RDWR | O_CLOEXEC, 0600);
  if (scratch < 0) return false;
  // A copy, so that whatever HDF5 reads back is what it wrote.
  const bool ok = copy_into(path_, scratch) && dup2(scratch, fd_) >= 0;
  close(scratch);
  if (ok) detached_ = true;
  return ok;
}

}  // namespace evas
