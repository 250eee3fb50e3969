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

/// Up to `jobs` forked worker processes at once (one thread each). A worker
/// still running `hard_wall` seconds after its start (0 = never) is killed:
/// tasks limit themselves through TaskSpec::max_wall, this catches a worker
/// stuck inside one step.
std::unique_ptr<TaskRunner> process_runner(int jobs, double hard_wall = 0.0);

/// One forked worker process running one task; its result comes back through
/// a pipe. Used by the process runner and the MPI runner's own local worker.
class LocalWorker {
 public:
  /// Forks; the child runs tasks[index] (run_task with `stop`), writes the
  /// result bytes to the pipe and leaves with _exit. Throws std::runtime_error
  /// when fork or pipe fails.
  LocalWorker(int index, const TaskSpec& task, const std::function<bool()>& stop);
  ~LocalWorker();  ///< kills and reaps a worker still running
  LocalWorker(const LocalWorker&) = delete;
  LocalWorker& operator=(const LocalWorker&) = delete;

  int fd() const { return fd_; }
  int index() const { return index_; }
  double seconds() const;  ///< since the start
  /// Reads what the pipe holds; false at the end of the output (then finish()).
  bool read_some();
  /// Reaps the process and returns its task's end (failed with the reason when
  /// it died, was killed or sent nothing readable).
  TaskEnd finish();
  void kill_now(const std::string& why);  ///< SIGKILL; finish() reports `why`

 private:
  int index_, fd_ = -1;
  long pid_ = -1;
  std::string bytes_, killed_;
  double start_;
};

/// The number of processors this process may use (at least 1).
int available_cores();

}  // namespace evas::study
