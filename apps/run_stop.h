// Stopping `evas run` on request: SIGINT (Ctrl-C), SIGTERM and SIGHUP, and the
// wall-time limit of --max-wall. The signal handler only sets a flag; the run
// polls it through check(), which the integrators reach once per step (their
// step monitor) and the output sink once per output row, and which throws
// RunStopped. The run then ends like any failed run: status "failed: ...",
// statistics and summary written, the rows computed so far kept.
#pragma once

#include <chrono>
#include <csignal>
#include <string>

#include "solver/types.h"

namespace evas::cli {

/// A run stopped on request; what() is the reason ("interrupted (SIGTERM) at t = ...").
class RunStopped : public RunError {
 public:
  RunStopped(const std::string& what, int exit_code) : RunError(what), exit_code_(exit_code) {}
  /// 128 + the signal number for a signal, 2 for the wall-time limit.
  int exit_code() const { return exit_code_; }

 private:
  int exit_code_;
};

class RunStop {
 public:
  /// Installs the handlers for its lifetime; a second signal ends the process at
  /// once (default action). max_wall_seconds <= 0: no wall-time limit.
  explicit RunStop(double max_wall_seconds);
  ~RunStop();
  RunStop(const RunStop&) = delete;
  RunStop& operator=(const RunStop&) = delete;

  /// True once a signal has arrived or the wall-time limit is passed (cheap).
  bool due() const;
  /// Throws RunStopped for the reason due() saw; `t` (and `h`, the last step,
  /// when > 0) say where the run was.
  [[noreturn]] void stop(double t, double h) const;

 private:
  double max_wall_;
  std::chrono::steady_clock::time_point start_;
  struct sigaction old_int_ {
  }, old_term_{}, old_hup_{};
};

}  // namespace evas::cli
