// One run, performed in one place for every front end (`evas run`, `evas
// study`, `evas problem`, Python, sweep workers): the start (initial state,
// consistent with the constraints, element internal states, integrator
// init), the first output, the integration with its stops, every row checked
// finite and handed to a sink, and the run's status, statistics and wall time.
// docs/architecture.md follows one run through the layers.
#pragma once

#include <limits>
#include <string>

#include "integrators/integrator.h"
#include "io/outputs.h"
#include "io/scene.h"
#include "run/sink.h"
#include "solver/system.h"

namespace evas::run {

enum class Status { completed, failed };

/// How a run ended.
struct Outcome {
  Status status = Status::completed;
  std::string message;  ///< why it failed ("" when completed)
  int exit_code = 0;    ///< 0 completed, 2 failed, 128 + N stopped by signal N
  IntegratorStats stats;
  /// The start and the integration [s] (NaN when the start was not reached).
  double wall = std::numeric_limits<double>::quiet_NaN();
  bool completed() const { return status == Status::completed; }
  /// "completed" or "failed: <message>", as results files and summaries write it.
  std::string status_text() const;
};

/// A scene made ready to run: its System and output grid for [t_start, t_end].
class SceneRun {
 public:
  /// Throws InputError (naming the scene file) when the grid has no output time.
  SceneRun(const Scene& scene, double t_end);
  SceneRun(const SceneRun&) = delete;
  SceneRun& operator=(const SceneRun&) = delete;

  System& system() { return *sys_; }
  OutputSet& outputs() { return *out_; }
  double t_start() const { return t_start_; }
  double t_end() const { return t_end_; }

  /// Runs `integ` (fresh from make_integrator) with `settings`, rows to `sink`.
  /// Never throws for a failure of the run: the outcome says it, and the rows
  /// before it are in the sink. A SceneRun runs once.
  Outcome perform(Integrator& integ, const IntegratorSettings& settings, RowSink& sink);
  /// The same with the integrator made by name (built in or plug-in); throws
  /// InputError when the name is unknown.
  Outcome perform(const IntegratorSettings& settings, RowSink& sink);

 private:
  double t_start_, t_end_;
  std::unique_ptr<System> sys_;
  std::unique_ptr<OutputSet> out_;
};

/// The end state of a problem run from t0 to t_end (landing on it).
struct EndState {
  Vec q, v, lambda;  ///< lambda empty when the integrator has no multipliers
  Outcome outcome;
};

/// Runs `p` from its initial state (made consistent with its constraints) at t0
/// to t_end with `settings`. Throws InputError for bad settings; a failure of
/// the integration is in the outcome.
EndState run_to_end(Problem& p, const IntegratorSettings& settings, double t0, double t_end);

}  // namespace evas::run
