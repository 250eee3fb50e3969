#include "io/run_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <ctime>

#include "model/types.h"

namespace evas {

namespace {

std::string holder_text(int fd) {
  char buf[512];
  const ssize_t n = pread(fd, buf, sizeof buf - 1, 0);
  if (n <= 0) return "a run that has not written its pid yet";
  std::string s(buf, static_cast<std::size_t>(n));
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  std::string out;
  for (char c : s) {
    if (c == '\n')
      out += ", ";
    else  // the file is ours, but print no control bytes from it
      out += static_cast<unsigned char>(c) < 0x20 ? '?' : c;
  }
  return out;
}

std::string own_text() {
  char host[256] = "unknown";
  gethostname(host, sizeof host - 1);
  host[sizeof host - 1] = '\0';
  const std::time_t now = std::time(nullptr);
  char when[64] = "unknown";
  std::tm tm{};
  if (localtime_r(&now, &tm)) std::strftime(when, sizeof when, "%Y-%m-%d %H:%M:%S %z", &tm);
  return "pid " + std::to_string(getpid()) + "\nhost " + host + "\nstarted " + when + "\n";
}

}  // namespace

RunLock::RunLock(const std::filesystem::path& dir) : path_((dir / ".evas-run.lock").string()) {
  // A holder that ends unlinks the file it locked: whoever locked that unlinked
  // file (it opened it just before) must try again on the new one.
  for (int attempt = 0; attempt < 100; ++attempt) {
    const int fd = open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0)
      throw InputError(
          path_ + ": cannot create the lock file of the output folder: " + std::strerror(errno));
    if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int e = errno;
      if (e == EWOULDBLOCK) {
        const std::string holder = holder_text(fd);
        close(fd);
        throw InputError(dir.string() + ": the output folder is in use by another evas run (" +
                         holder + "; lock file " + path_ +
                         "); wait for that run to end or choose another folder with --out");
      }
      close(fd);
      note_ = path_ + ": cannot lock the output folder (" + std::strerror(e) +
              "); two runs into it would overwrite each other";
      return;
    }
    struct stat by_fd {
    }, by_path{};
    if (fstat(fd, &by_fd) != 0 || stat(path_.c_str(), &by_path) != 0 ||
        by_fd.st_ino != by_path.st_ino || by_fd.st_dev != by_path.st_dev) {
      close(fd);
      continue;
    }
    const std::string text = own_text();
    if (ftruncate(fd, 0) != 0 ||
        pwrite(fd, text.data(), text.size(), 0) != static_cast<ssize_t>(text.size())) {
      // Still locked: the run is protected, only the message of a second run is poorer.
    }
    fd_ = fd;
    return;
  }
  throw InputError(path_ + ": cannot take the lock of the output folder (it keeps changing)");
}

RunLock::~RunLock() {
  if (fd_ < 0) return;
  unlink(path_.c_str());  // while still holding the lock (see the constructor)
  close(fd_);
}

}  // namespace evas
