// Running a study's tasks in this process or in forked workers (task_runner.h).
#include "study/task_runner.h"

#include <fcntl.h>
#include <poll.h>
#include <pthread.h>
#include <sched.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstring>
#include <deque>
#include <map>

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

// Reads exactly n bytes (false at the end of input or on an error).
bool read_exact(int fd, char* out, std::size_t n) {
  std::size_t off = 0;
  while (off < n) {
    const ssize_t got = ::read(fd, out + off, n - off);
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) return false;
    off += static_cast<std::size_t>(got);
  }
  return true;
}

// A message: its length (8 bytes) and its bytes.
std::string framed(const std::string& bytes) {
  const std::uint64_t n = bytes.size();
  std::string out(sizeof n, '\0');
  std::memcpy(out.data(), &n, sizeof n);
  return out + bytes;
}

// The worker process: runs the tasks that come in until its input ends.
[[noreturn]] void serve(int in, int out, const std::function<bool()>& stop) {
  for (;;) {
    std::uint64_t n = 0;
    if (!read_exact(in, reinterpret_cast<char*>(&n), sizeof n)) ::_exit(0);
    std::string task(n, '\0');
    if (!read_exact(in, task.data(), n)) ::_exit(0);
    std::string result;
    try {
      result = pack_run(run_task(unpack_task(task), stop));
    } catch (const std::exception& e) {
      result = pack_run(failed_run(std::string("the worker could not run the task: ") + e.what()));
    }
    if (!write_all(out, framed(result))) ::_exit(3);
    // an interrupted worker serves no further task (each would only be cut short)
    if (stop && stop()) ::_exit(0);
  }
}

// Up to `jobs` workers, each kept for the whole list; a worker that dies or is
// killed is replaced by a new one when there is more to run.
class ProcessRunner : public TaskRunner {
 public:
  ProcessRunner(int jobs, double hard_wall) : jobs_(jobs), hard_wall_(hard_wall) {}

  void run(const std::vector<TaskSpec>& tasks, const std::vector<int>& todo,
           const std::function<void(const TaskEnd&)>& done,
           const std::function<bool()>& stop) override {
    std::vector<std::unique_ptr<LocalWorker>> pool;  // destroyed (killed) on return
    std::deque<int> queue(todo.begin(), todo.end());
    std::map<const LocalWorker*, double> limit;  // the hard wall of each worker's task
    auto stopped = [&] { return stop && stop(); };
    auto busy = [&] {
      return std::any_of(pool.begin(), pool.end(), [](const auto& w) { return w->busy(); });
    };
    // idle workers take the next tasks; the pool grows to `jobs` while there are more
    auto dispatch = [&] {
      for (;;) {
        pool.erase(
            std::remove_if(pool.begin(), pool.end(), [](const auto& w) { return !w->alive(); }),
            pool.end());
        if (queue.empty()) return;
        LocalWorker* idle = nullptr;
        for (auto& w : pool)
          if (!w->busy()) idle = w.get();
        if (!idle) {
          if (static_cast<int>(pool.size()) >= jobs_) return;
          pool.push_back(std::make_unique<LocalWorker>(stop));
          idle = pool.back().get();
        }
        const int i = queue.front();
        const TaskSpec& t = tasks[static_cast<std::size_t>(i)];
        if (idle->start(i, pack_task(t))) {
          queue.pop_front();
          limit[idle] = hard_wall_ > 0.0 ? hard_wall_ : hard_wall_of(t.max_wall);
        }
      }
    };
    while (!queue.empty() || busy()) {
      if (stopped()) return;  // the workers' destructors kill them: not run
      dispatch();
      // wait for output of any busy worker (or 100 ms, to look at stop and the clock)
      std::vector<pollfd> pfd;
      std::vector<LocalWorker*> at;
      for (auto& w : pool)
        if (w->busy()) {
          pfd.push_back({w->fd(), POLLIN, 0});
          at.push_back(w.get());
        }
      const int n = ::poll(pfd.data(), pfd.size(), 100);
      if (n < 0 && errno != EINTR)
        throw std::runtime_error("study: poll(): " + std::string(std::strerror(errno)));
      std::vector<TaskEnd> ended;
      for (std::size_t k = 0; k < at.size(); ++k) {
        TaskEnd e;
        if (n > 0 && (pfd[k].revents & (POLLIN | POLLHUP | POLLERR)) && at[k]->read_some(e)) {
          ended.push_back(std::move(e));
          continue;
        }
        const double hard = limit[at[k]];
        if (hard > 0.0 && at[k]->seconds() > hard)
          at[k]->kill_now("timed out: the worker was killed after " + gnum(at[k]->seconds(), 4) +
                          " s (limit " + gnum(hard, 4) + " s)");
      }
      if (ended.empty()) continue;
      if (stopped()) return;  // their runs were cut short by the interrupt: not run
      dispatch();  // the free workers get their next tasks before the coordinator's bookkeeping
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

double hard_wall_of(double max_wall) { return max_wall > 0.0 ? 1.5 * max_wall + 10.0 : 0.0; }

LocalWorker::LocalWorker(const std::function<bool()>& stop) {
  int down[2], up[2];  // tasks to the worker, results from it
  if (::pipe(down) != 0)
    throw std::runtime_error("study: pipe(): " + std::string(std::strerror(errno)));
  if (::pipe(up) != 0) {
    ::close(down[0]);
    ::close(down[1]);
    throw std::runtime_error("study: pipe(): " + std::string(std::strerror(errno)));
  }
  // wide pipes: a result of megabytes then passes in a few reads, not in
  // hundreds of 64 kB turns between a worker and a coordinator that share
  // cores with the other workers (best effort: the default is kept on refusal)
  ::fcntl(up[0], F_SETPIPE_SZ, 1 << 20);
  const pid_t pid = ::fork();
  if (pid < 0) {
    for (int fd : {down[0], down[1], up[0], up[1]}) ::close(fd);
    throw std::runtime_error("study: fork(): " + std::string(std::strerror(errno)));
  }
  if (pid == 0) {  // the worker: serve tasks, leave without any cleanup
    ::close(down[1]);
    ::close(up[0]);
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);  // never outlive the coordinator
    serve(down[0], up[1], stop);
  }
  ::close(down[0]);
  ::close(up[1]);
  for (int fd : {down[1], up[0]}) ::fcntl(fd, F_SETFD, FD_CLOEXEC);
  to_ = down[1];
  from_ = up[0];
  pid_ = pid;
}

LocalWorker::~LocalWorker() {
  if (pid_ > 0) ::kill(static_cast<pid_t>(pid_), SIGKILL);
  reap();
}

void LocalWorker::reap() {
  if (pid_ > 0) {
    int st = 0;
    while (::waitpid(static_cast<pid_t>(pid_), &st, 0) < 0 && errno == EINTR) {
    }
    pid_ = -1;
  }
  for (int* fd : {&to_, &from_})
    if (*fd >= 0) {
      ::close(*fd);
      *fd = -1;
    }
}

bool LocalWorker::start(int index, const std::string& task_bytes) {
  if (pid_ <= 0 || busy()) return false;
  // a worker that has died has closed its end: the write fails with EPIPE
  // (SIGPIPE blocked for the write, a pending one discarded)
  sigset_t pipe_set, old;
  sigemptyset(&pipe_set);
  sigaddset(&pipe_set, SIGPIPE);
  ::pthread_sigmask(SIG_BLOCK, &pipe_set, &old);
  const bool sent = write_all(to_, framed(task_bytes));
  if (!sent) {
    const timespec zero{0, 0};
    while (::sigtimedwait(&pipe_set, nullptr, &zero) == SIGPIPE) {
    }
  }
  ::pthread_sigmask(SIG_SETMASK, &old, nullptr);
  if (!sent) {
    ::kill(static_cast<pid_t>(pid_), SIGKILL);
    reap();
    return false;
  }
  index_ = index;
  start_ = now_seconds();
  bytes_.clear();
  killed_.clear();
  return true;
}

double LocalWorker::seconds() const { return now_seconds() - start_; }

bool LocalWorker::read_some(TaskEnd& end) {
  static thread_local std::vector<char> buf(1 << 20);
  ssize_t got = 0;
  do got = ::read(from_, buf.data(), buf.size());
  while (got < 0 && errno == EINTR);
  if (got > 0) {
    bytes_.append(buf.data(), static_cast<std::size_t>(got));
    std::uint64_t n = 0;
    if (bytes_.size() < sizeof n) return false;
    std::memcpy(&n, bytes_.data(), sizeof n);
    if (bytes_.size() - sizeof n < n) return false;
    end = TaskEnd{};
    end.index = index_;
    end.ran = true;
    end.worker = "worker pid " + std::to_string(pid_);
    try {
      if (bytes_.size() - sizeof n > n) throw std::runtime_error("bytes after the result");
      end.run = unpack_run(bytes_.substr(sizeof n));
    } catch (const std::exception& ex) {
      end.run = failed_run(end.worker + " sent a malformed result: " + ex.what());
    }
    index_ = -1;
    bytes_.clear();
    return true;
  }
  // the end of the worker's output: it has left (or was killed)
  const int task = index_;
  const std::string who = "worker pid " + std::to_string(pid_);
  const double secs = seconds();
  int st = 0;
  if (pid_ > 0)
    while (::waitpid(static_cast<pid_t>(pid_), &st, 0) < 0 && errno == EINTR) {
    }
  pid_ = -1;
  reap();
  index_ = -1;
  if (task < 0) return false;  // it left between tasks: nothing was lost
  end = TaskEnd{};
  end.index = task;
  end.ran = true;
  end.worker = who;
  if (!killed_.empty())
    end.run = failed_run(killed_);
  else if (WIFSIGNALED(st))
    end.run = failed_run(who + " died of signal " + signal_name(WTERMSIG(st)) + " after " +
                         gnum(secs, 4) + " s");
  else
    end.run = failed_run(who + " ended without a result (exit code " +
                         std::to_string(WIFEXITED(st) ? WEXITSTATUS(st) : -1) + ")");
  return true;
}

void LocalWorker::kill_now(const std::string& why) {
  if (pid_ > 0 && killed_.empty()) {
    ::kill(static_cast<pid_t>(pid_), SIGKILL);
    killed_ = why;
  }
}

int available_cores() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (::sched_getaffinity(0, sizeof set, &set) == 0) return std::max(1, CPU_COUNT(&set));
  const long n = ::sysconf(_SC_NPROCESSORS_ONLN);
  return n > 0 ? static_cast<int>(n) : 1;
}

}  // namespace evas::study
