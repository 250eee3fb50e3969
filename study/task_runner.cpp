// Running a study's tasks in this process or in forked workers (task_runner.h).
#include "study/task_runner.h"

#include <fcntl.h>
#include <poll.h>
#include <sched.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <deque>

#include "study/report.h"

namespace evas::study {

namespace {

class SerialRunner : public TaskRunner {
 public:
  void run(const std::vector<TaskSpec>& tasks, const std::vector<int>& todo,
           const std::function<void(const TaskEnd&)>& done,
           const std::function<bool()>& stop) override {
    for (int i : todo) {
      if (stop && stop()) return;
      TaskEnd e;
      e.index = i;
      // through the byte form, as every other runner: the same digits
      e.run = unpack_run(pack_run(run_task(tasks[static_cast<std::size_t>(i)], stop)));
      if (stop && stop()) return;  // cut short by the interrupt: not run
      e.ran = true;
      e.worker = "this process";
      done(e);
    }
  }
  int width() const override { return 1; }
  std::string describe() const override { return "serial"; }
};

RunData failed_run(const std::string& why) {
  RunData d;
  d.status = CaseStatus::failed;
  d.message = why;
  return d;
}

// Writes all of `bytes` to fd (a worker's end of its pipe).
bool write_all(int fd, const std::string& bytes) {
  std::size_t off = 0;
  while (off < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + off, bytes.size() - off);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    off += static_cast<std::size_t>(n);
  }
  return true;
}

std::string signal_name(int sig) {
  const char* d = ::strsignal(sig);
  return std::to_string(sig) + (d ? std::string(" (") + d + ")" : "");
}

double now_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

class ProcessRunner : public TaskRunner {
 public:
  ProcessRunner(int jobs, double hard_wall) : jobs_(jobs), hard_wall_(hard_wall) {}

  void run(const std::vector<TaskSpec>& tasks, const std::vector<int>& todo,
           const std::function<void(const TaskEnd&)>& done,
           const std::function<bool()>& stop) override {
    std::vector<std::unique_ptr<LocalWorker>> active;
    std::deque<int> queue(todo.begin(), todo.end());
    auto stopped = [&] { return stop && stop(); };
    while (!queue.empty() || !active.empty()) {
      if (stopped()) return;  // the workers' destructors kill them: not run
      while (static_cast<int>(active.size()) < jobs_ && !queue.empty()) {
        const int i = queue.front();
        queue.pop_front();
        active.push_back(
            std::make_unique<LocalWorker>(i, tasks[static_cast<std::size_t>(i)], stop));
      }
      // wait for output of any worker (or 100 ms, to look at stop and the clock)
      std::vector<pollfd> pfd;
      for (const auto& w : active) pfd.push_back({w->fd(), POLLIN, 0});
      const int n = ::poll(pfd.data(), pfd.size(), 100);
      if (n < 0 && errno != EINTR)
        throw std::runtime_error("study: poll(): " + std::string(std::strerror(errno)));
      std::vector<std::unique_ptr<LocalWorker>> still;
      std::vector<TaskEnd> ended;
      for (std::size_t k = 0; k < active.size(); ++k) {
        if (n > 0 && (pfd[k].revents & (POLLIN | POLLHUP | POLLERR)) && !active[k]->read_some()) {
          ended.push_back(active[k]->finish());
          continue;
        }
        if (hard_wall_ > 0.0 && active[k]->seconds() > hard_wall_)
          active[k]->kill_now("timed out: the worker was killed after " +
                              gnum(active[k]->seconds(), 4) + " s (limit " + gnum(hard_wall_, 4) +
                              " s)");
        still.push_back(std::move(active[k]));
      }
      active = std::move(still);
      if (ended.empty()) continue;
      if (stopped()) return;  // their runs were cut short by the interrupt: not run
      // the free slots get their next tasks before the coordinator's bookkeeping
      while (static_cast<int>(active.size()) < jobs_ && !queue.empty()) {
        const int i = queue.front();
        queue.pop_front();
        active.push_back(
            std::make_unique<LocalWorker>(i, tasks[static_cast<std::size_t>(i)], stop));
      }
      for (const TaskEnd& e : ended) done(e);
    }
  }
  int width() const override { return jobs_; }
  std::string describe() const override {
    return std::to_string(jobs_) + " local worker process" + (jobs_ == 1 ? "" : "es");
  }

 private:
  int jobs_;
  double hard_wall_;
};

}  // namespace

std::unique_ptr<TaskRunner> serial_runner() { return std::make_unique<SerialRunner>(); }

std::unique_ptr<TaskRunner> process_runner(int jobs, double hard_wall) {
  return std::make_unique<ProcessRunner>(jobs < 1 ? 1 : jobs, hard_wall);
}

LocalWorker::LocalWorker(int index, const TaskSpec& task, const std::function<bool()>& stop)
    : index_(index), start_(now_seconds()) {
  int fds[2];
  if (::pipe(fds) != 0)
    throw std::runtime_error("study: pipe(): " + std::string(std::strerror(errno)));
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    throw std::runtime_error("study: fork(): " + std::string(std::strerror(errno)));
  }
  if (pid == 0) {  // the worker: run, send the bytes, leave without any cleanup
    ::close(fds[0]);
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);  // never outlive the coordinator
    int code = 0;
    try {
      code = write_all(fds[1], pack_run(run_task(task, stop))) ? 0 : 3;
    } catch (...) {
      code = 4;
    }
    ::_exit(code);
  }
  ::close(fds[1]);
  ::fcntl(fds[0], F_SETFD, FD_CLOEXEC);
  // a wide pipe: a result of megabytes then passes in a few reads, not in
  // hundreds of 64 kB turns between a worker and a coordinator that share
  // cores with the other workers (best effort: the default is kept on refusal)
  ::fcntl(fds[0], F_SETPIPE_SZ, 1 << 20);
  fd_ = fds[0];
  pid_ = pid;
}

LocalWorker::~LocalWorker() {
  if (pid_ > 0) {
    ::kill(static_cast<pid_t>(pid_), SIGKILL);
    int st = 0;
    while (::waitpid(static_cast<pid_t>(pid_), &st, 0) < 0 && errno == EINTR) {
    }
  }
  if (fd_ >= 0) ::close(fd_);
}

double LocalWorker::seconds() const { return now_seconds() - start_; }

bool LocalWorker::read_some() {
  static thread_local std::vector<char> buf(1 << 20);
  for (;;) {
    const ssize_t got = ::read(fd_, buf.data(), buf.size());
    if (got > 0) {
      bytes_.append(buf.data(), static_cast<std::size_t>(got));
      return true;
    }
    if (got < 0 && errno == EINTR) continue;
    return false;
  }
}

void LocalWorker::kill_now(const std::string& why) {
  if (pid_ > 0 && killed_.empty()) {
    ::kill(static_cast<pid_t>(pid_), SIGKILL);
    killed_ = why;
  }
}

TaskEnd LocalWorker::finish() {
  ::close(fd_);
  fd_ = -1;
  int st = 0;
  while (::waitpid(static_cast<pid_t>(pid_), &st, 0) < 0 && errno == EINTR) {
  }
  TaskEnd e;
  e.index = index_;
  e.ran = true;
  e.worker = "worker pid " + std::to_string(pid_);
  pid_ = -1;
  const double secs = seconds();
  if (!killed_.empty()) {
    e.run = failed_run(killed_);
  } else if (WIFEXITED(st) && WEXITSTATUS(st) == 0) {
    try {
      e.run = unpack_run(bytes_);
    } catch (const std::exception& ex) {
      e.run = failed_run(e.worker + " sent a malformed result: " + ex.what());
    }
  } else if (WIFSIGNALED(st)) {
    e.run = failed_run(e.worker + " died of signal " + signal_name(WTERMSIG(st)) + " after " +
                       gnum(secs, 4) + " s");
  } else {
    e.run = failed_run(e.worker + " exited with code " +
                       std::to_string(WIFEXITED(st) ? WEXITSTATUS(st) : -1));
  }
  return e;
}

int available_cores() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (::sched_getaffinity(0, sizeof set, &set) == 0) return std::max(1, CPU_COUNT(&set));
  const long n = ::sysconf(_SC_NPROCESSORS_ONLN);
  return n > 0 ? static_cast<int>(n) : 1;
}

}  // namespace evas::study
