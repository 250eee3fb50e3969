// A read run in a forked child (see isolated_read.h).
#include "io/isolated_read.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <exception>

#include "io/hdf5_util.h"

// Present when a sanitizer runtime is linked (ASan, UBSan): the child sends its
// reports, which are libhdf5's faults on the file, to its silenced stderr.
extern "C" void __sanitizer_set_report_path(const char* path) __attribute__((weak));
// Present with a sanitizer runtime: libFuzzer's hook that saves the input when a
// sanitizer stops the process, which the child must not run.
extern "C" void __sanitizer_set_death_callback(void (*callback)()) __attribute__((weak));

namespace evas::h5 {

namespace {

bool g_in_child = false;  // reads nested in an isolated one run directly
bool g_isolate = true;    // set_read_isolation

bool write_all(int fd, const void* data, std::size_t n) {
  const char* p = static_cast<const char*>(data);
  while (n > 0) {
    const ssize_t w = ::write(fd, p, n);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) return false;
    p += w;
    n -= static_cast<std::size_t>(w);
  }
  return true;
}

bool write_string(int fd, const std::string& s) {
  const std::uint64_t n = s.size();
  return write_all(fd, &n, sizeof n) && write_all(fd, s.data(), s.size());
}

// The child: status 'O' + count + strings, or 'E' + message; never returns.
[[noreturn]] void child(int fd, const std::function<std::vector<std::string>()>& read) {
  g_in_child = true;
  const int null = ::open("/dev/null", O_WRONLY);
  if (null >= 0) ::dup2(null, STDERR_FILENO);  // HDF5's error stack, sanitizer reports
  if (__sanitizer_set_report_path) __sanitizer_set_report_path("stderr");
  if (__sanitizer_set_death_callback) __sanitizer_set_death_callback(nullptr);
  bool ok = false;
  try {
    const std::vector<std::string> v = read();
    const std::uint64_t count = v.size();
    ok = write_all(fd, "O", 1) && write_all(fd, &count, sizeof count);
    for (std::size_t i = 0; ok && i < v.size(); ++i) ok = write_string(fd, v[i]);
  } catch (const std::exception& e) {
    ok = write_all(fd, "E", 1) && write_string(fd, e.what());
  } catch (...) {
    ok = write_all(fd, "E", 1) && write_string(fd, "unknown error");
  }
  ::_exit(ok ? 0 : 1);  // no atexit handlers: HDF5 and the caller's state stay the parent's
}

// Reads the child's bytes until it closes the pipe; false on time-out.
bool drain(int fd, std::string& out, double timeout_s) {
  using Clock = std::chrono::steady_clock;
  const auto end = Clock::now() + std::chrono::duration<double>(timeout_s);
  char buf[65536];
  for (;;) {
    const double left = std::chrono::duration<double>(end - Clock::now()).count();
    if (left <= 0.0) return false;
    pollfd p{fd, POLLIN, 0};
    const int r = ::poll(&p, 1, static_cast<int>(left * 1000.0) + 1);
    if (r < 0 && errno == EINTR) continue;
    if (r == 0) return false;  // time-out
    if (r < 0) return true;    // poll failed: what arrived is parsed (and found short)
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return true;  // end of the child's output (or an error: parsed as short)
    out.append(buf, static_cast<std::size_t>(n));
  }
}

struct Parser {
  const std::string& s;
  std::size_t pos = 0;
  bool u64(std::uint64_t& v) {
    if (s.size() - pos < sizeof v) return false;
    std::memcpy(&v, s.data() + pos, sizeof v);
    pos += sizeof v;
    return true;
  }
  bool str(std::string& v) {
    std::uint64_t n = 0;
    if (!u64(n) || s.size() - pos < n) return false;
    v.assign(s, pos, static_cast<std::size_t>(n));
    pos += static_cast<std::size_t>(n);
    return true;
  }
};

}  // namespace

std::vector<std::string> read_isolated(const std::function<std::vector<std::string>()>& read,
                                       const std::string& what, double timeout_s) {
  if (g_in_child || !g_isolate) return read();
  int fds[2];
  if (::pipe(fds) != 0) return read();
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    return read();
  }
  if (pid == 0) {
    ::close(fds[0]);
    child(fds[1], read);
  }
  ::close(fds[1]);
  std::string bytes;
  const bool done = drain(fds[0], bytes, timeout_s);
  ::close(fds[0]);
  if (!done) ::kill(pid, SIGKILL);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  const std::string head = what + " cannot be read: ";
  if (!done)
    throw Failure(head + "the HDF5 library did not return within " +
                  std::to_string(static_cast<int>(timeout_s)) + " s (corrupt file?)");
  if (WIFSIGNALED(status))
    throw Failure(head + "the HDF5 library crashed on it (signal " +
                  std::to_string(WTERMSIG(status)) + "; corrupt file?)");
  Parser p{bytes};
  std::string message;
  if (!bytes.empty() && bytes[0] == 'E') {
    p.pos = 1;
    throw Failure(p.str(message) ? message : head + "the read failed");
  }
  std::uint64_t count = 0;
  p.pos = 1;
  std::vector<std::string> out;
  bool ok = !bytes.empty() && bytes[0] == 'O' && p.u64(count) && WIFEXITED(status) &&
            WEXITSTATUS(status) == 0;
  for (std::uint64_t i = 0; ok && i < count; ++i) {
    out.emplace_back();
    ok = p.str(out.back());
  }
  if (!ok || p.pos != bytes.size())
    throw Failure(head + "the HDF5 library failed on it (the reading process ended with status " +
                  std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) +
                  " without its result; corrupt file?)");
  return out;
}

void set_read_isolation(bool on) { g_isolate = on; }

}  // namespace evas::h5
