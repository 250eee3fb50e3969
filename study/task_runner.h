// How a study's tasks (task.h) are run: in this process, in N forked worker
// processes on this machine (--jobs N), or on the ranks of an MPI job (the
// evas program's MPI runner, apps/mpi_runner.h). Whatever runs them, the
// coordinator gets every task's result as the same exact bytes (pack_run), so
// a study's files do not depend on how it was run (wall times aside).
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "study/task.h"

namespace evas::study {

/// What the coordinator learns of one task.
struct TaskEnd {
  int index = -1;      ///< position in the task list
  bool ran = false;    ///< true: `run` holds the task's result
  RunData run;         ///< the result (status failed for a failed run)
  std::string worker;  ///< where it ran ("this process", "worker pid 123", "rank 1")
};

class TaskRunner {
 public:
  virtual ~TaskRunner() = default;
  /// Runs tasks[i] for every i in `todo` and calls done() on the coordinator
  /// after each, in the order they finish. A worker that dies or is killed
  /// ends its task as failed with the reason (signal, exit code). When stop()
  /// turns true no new task starts, running ones are stopped and left out of
  /// done() (they were not run), and run() returns.
  virtual void run(const std::vector<TaskSpec>& tasks, const std::vector<int>& todo,
                   const std::function<void(const TaskEnd&)>& done,
                   const std::function<bool()>& stop) = 0;
  /// Tasks that run at once.
  virtual int width() const = 0;
  /// "serial", "2 local processes", "MPI, 3 ranks".
  virtual std::string describe() const = 0;
};

/// Every task in this process, one after another.
std::unique_ptr<TaskRunner> serial_runner();

/// Up to `jobs` forked worker processes at once (one thread each), each kept
/// for the whole task list. A worker still running its task `hard_wall`
/// seconds after the start (0: hard_wall_of the task's own max_wall) is
/// killed: tasks limit themselves through TaskSpec::max_wall, this catches a
/// worker stuck inside one step.
std::unique_ptr<TaskRunner> process_runner(int jobs, double hard_wall = 0.0);

/// The hard limit after which a worker still busy with a task of `max_wall`
/// seconds is killed (0 = never): the task limits itself cooperatively at
/// max_wall; this catches a run stuck inside one step.
double hard_wall_of(double max_wall);

/// One forked worker process that runs tasks one after another: each task
/// goes to it as pack_task bytes, each result comes back as pack_run bytes.
/// A worker keeps its memory between tasks (the allocator's pages, the body
/// cache), so the second and later tasks start as warm as in one process.
/// Used by the process runner and by the MPI runner on every rank.
class LocalWorker {
 public:
  /// Forks the worker; it waits for tasks and runs them with `stop` (checked
  /// in the worker). Throws std::runtime_error when fork, pipe or socket fail.
  explicit LocalWorker(const std::function<bool()>& stop);
  ~LocalWorker();  ///< kills and reaps the worker
  LocalWorker(const LocalWorker&) = delete;
  LocalWorker& operator=(const LocalWorker&) = delete;

  /// Hands task `index` (its pack_task bytes) to an idle, live worker. False
  /// when the worker is gone (it then is not alive; the task did not start).
  bool start(int index, const std::string& task_bytes);
  bool alive() const { return pid_ > 0; }
  bool busy() const { return index_ >= 0; }
  int fd() const { return from_; }  ///< readable when a result (or the end) comes
  int index() const { return index_; }
  long pid() const { return pid_; }
  double seconds() const;  ///< since the current task started
  /// Reads what the worker sent. True when the current task ended: `end`
  /// holds its result, or a failure with the reason when the worker died, was
  /// killed or sent something unreadable (the worker is then not alive).
  bool read_some(TaskEnd& end);
  void kill_now(const std::string& why);  ///< SIGKILL; read_some reports `why`

 private:
  void reap();
  int index_ = -1, to_ = -1, from_ = -1;
  long pid_ = -1;
  std::string bytes_, killed_;
  double start_ = 0.0;
};

/// The number of processors this process may use (at least 1).
int available_cores();

}  // namespace evas::study
