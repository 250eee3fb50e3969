// A study's unit of work, as data: one run of a scene with one integrator
// setting, keeping chosen channels (run_case.h). A task and its result pack
// into bytes exactly (every double bit for bit), so that a run made in this
// process, in a forked worker (--jobs) or on another MPI rank gives the same
// result files.
#pragma once

#include <functional>
#include <string>

#include "study/run_case.h"

namespace evas::study {

struct TaskSpec {
  SceneSource src;
  IntegratorSettings settings;
  std::vector<int> channels;  ///< indices into the scene's channels
  int repeats = 1;            ///< wall time = minimum over the repeats
  double max_wall = 0.0;      ///< wall-clock limit of the run [s]; 0 = none
  /// Growth limit of a stability trial (none when empty): after the first
  /// output row (that row only when its t <= limit_after), a kept channel c
  /// with limit[c] > 0 and |y_c| > limit[c] ends the run as failed, "|NAME| =
  /// V > GROWTH x reference max M at t = T s" (NAME from limit_names).
  std::vector<double> limit;
  std::vector<std::string> limit_names;
  double limit_after = 0.0, growth = 0.0;
  /// "" a transient run to the scene's end; else the periodic cycle by this
  /// method of evas periodic (run/periodic.h), its defect tolerance
  /// periodic_tol: the rows are one converged cycle (run_periodic_case).
  std::string periodic;
  double periodic_tol = 3e-4;
  /// A periodic task's first guess of the cycle's start state, every body's q
  /// then v (a neighbour point's RunData::state: a warm start); empty = the
  /// scene's own initial state. Left out of the fingerprint: it changes where
  /// the search starts, not the cycle it converges to.
  std::vector<double> initial;
};

/// Runs the task (run_case_repeated; with a limit, one run_case with that
/// check). A run longer than max_wall fails with "timed out: ..."; `stop` (may
/// be empty) as in run_case.
RunData run_task(const TaskSpec& task, const std::function<bool()>& stop = nullptr);

/// Exact byte forms. unpack_* throw std::runtime_error on a malformed buffer.
std::string pack_task(const TaskSpec& t);
TaskSpec unpack_task(const std::string& bytes);

/// What a task computes, as 16 hex digits: a 64-bit FNV-1a hash of its bytes
/// with max_wall left out (a time limit does not change what a completed run
/// computes). A resumed or merged sweep keeps an earlier task file only when
/// its fingerprint is this one: an edited scene, --t-end, --param or case
/// runs again. The bodies' files are named by path in the scene; their
/// contents are not in it.
std::string task_fingerprint(const TaskSpec& t);
std::string pack_run(const RunData& d);
RunData unpack_run(const std::string& bytes);

}  // namespace evas::study
