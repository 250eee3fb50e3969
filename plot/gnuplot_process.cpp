// A gnuplot process started before its figures exist (gnuplot_process.h).
#include "plot/gnuplot_process.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <string>

#include "plot/gnuplot.h"

extern char** environ;

namespace evas {

GnuplotProcess::GnuplotProcess() {
  if (!have_gnuplot()) return;
  int sv[2];
  // a socket, not a pipe: send() with MSG_NOSIGNAL cannot raise SIGPIPE in
  // evas when gnuplot has gone; close-on-exec keeps our end out of the child
  if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sv) != 0) return;
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_adddup2(&fa, sv[1], 0);
  posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&fa, 2, "/dev/null", O_WRONLY, 0);
  char prog[] = "gnuplot";
  char* argv[] = {prog, nullptr};
  pid_t pid = -1;
  const int rc = ::posix_spawnp(&pid, "gnuplot", &fa, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&fa);
  ::close(sv[1]);
  if (rc != 0) {
    ::close(sv[0]);
    return;
  }
  pid_ = pid;
  fd_ = sv[0];
  if (!send("set terminal pngcairo size 64,64\nset output '/dev/null'\nplot 0 notitle\n"
            "unset output\nreset\n"))
    finish();
}

GnuplotProcess::~GnuplotProcess() {
  if (pid_ > 0) finish();
}

bool GnuplotProcess::send(const std::string& text) {
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::send(fd_, text.data() + done, text.size() - done, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<std::size_t>(n);
  }
  return true;
}

int GnuplotProcess::finish() {
  // "exit", not only the end of input: a process forked from this one after
  // the start (a sweep's worker) holds a copy of our end of the socket
  if (fd_ >= 0) send("exit\n");
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  int status = 0;
  pid_t r;
  do r = ::waitpid(pid_, &status, 0);
  while (r < 0 && errno == EINTR);
  pid_ = -1;
  return r > 0 && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

bool GnuplotProcess::draw(const std::vector<std::filesystem::path>& scripts) {
  if (pid_ <= 0) return false;
  std::string cmd;
  if (!scripts.empty()) {
    const std::filesystem::path& first = scripts.front();
    cmd = "cd " + gp_quote(first.has_parent_path() ? first.parent_path().string() : ".") + "\n";
  }
  for (const auto& s : scripts) cmd += "load " + gp_quote(s.filename().string()) + "\n";
  const bool sent = send(cmd);
  return finish() == 0 && sent;
}

}  // namespace evas
