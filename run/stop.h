// Stopping a run on request: SIGINT (Ctrl-C), SIGTERM and SIGHUP, and the
// wall-time limit of --max-wall. The signal handler only sets a flag; the run's
// sink polls it through due() between steps and before every output row
// (run/sink.h), and stop() throws Stopped. The run then ends like any failed run: status "failed:
// ...", statistics and summary written, the rows computed so far kept.
#pragma once

#include <chrono>
#include <csignal>
#include <string>

#include "model/types.h"

namespace evas::run {

/// A run stopped on request; what() is the reason ("interrupted (SIGTERM) at t = ...").
class Stopped : public RunError {
 public:
  Stopped(const std::string& what, int exit_code) : RunError(what), exit_code_(exit_code) {}
  /// 128 + the signal number for a signal, 2 for the wall-time limit.
  int exit_code() const { return exit_code_; }

 private:
  int exit_code_;
};

class Stop {
 public:
  /// Installs the handlers for its lifetime; a second signal ends the process at
  /// once (default action). max_wall_seconds <= 0: no wall-time limit.
  explicit Stop(double max_wall_seconds);
  ~Stop();
  Stop(const Stop&) = delete;
  Stop& operator=(const Stop&) = delete;

  /// True once a signal has arrived or the wall-time limit is passed (cheap).
  bool due() const;
  /// Throws Stopped for the reason due() saw; `t` (and `h`, the last step,
  /// when > 0) say where the run was.
  [[noreturn]] void stop(double t, double h) const;

 private:
  double max_wall_;
  std::chrono::steady_clock::time_point start_;
  struct sigaction old_int_ {
  }, old_term_{}, old_hup_{};
};

}  // namespace evas::run
