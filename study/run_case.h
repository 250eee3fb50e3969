// One run of a study case: parse the scene (its own model), build System and
// OutputSet, make the integrator, init and integrate, collecting the selected
// channels at the output times. Any std::exception from the run is caught and
// recorded (status "failed" with the message); the rows before it are kept.
#pragma once

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "integrators/integrator.h"
#include "model/element.h"
#include "study/scene_edit.h"

namespace evas::study {

/// The output grid and channels of a scene (from a probe build).
struct SceneInfo {
  std::string name;
  std::string grid;  ///< "time" or "crank-angle"
  std::vector<Channel> channels;
  std::vector<double> times;
  std::vector<double> crank;      ///< crank angle at every output time [deg] (crank-angle grid)
  int crank_channel = -1;         ///< index of crank_angle, -1 on the time grid
  IntegratorSettings integrator;  ///< the scene's integrator block
  double t_start = 0.0, t_end = 0.0;
  std::vector<std::string> warnings;  ///< the scene's plausibility warnings (Scene::warnings)
};

/// Parses the scene and builds its outputs once. Throws InputError.
SceneInfo probe_scene(const SceneSource& src);

/// Status of a study case (or of one run of it).
enum class CaseStatus { not_run, completed, failed };

/// "not run", "completed" or "failed": the text written to every file.
const char* to_text(CaseStatus s);

/// Collected output of one run.
struct RunData {
  CaseStatus status = CaseStatus::not_run;
  std::string message;
  std::vector<double> time;
  std::vector<double> crank;  ///< crank angle per row (crank-angle grid)
  Mat y;                      ///< rows x selected channels
  IntegratorStats stats;
  double wall = std::numeric_limits<double>::quiet_NaN();  ///< init + integrate [s]
  /// A converged periodic cycle's start state (every body's q, then v); empty
  /// for a transient run
  std::vector<double> state;
  /// A converged periodic cycle's states spread over it (about 36, on the
  /// output samples): cycle_t their times, cycle_states their q then v, one
  /// state after the other (post/assembled_modes.h linearizes about them);
  /// empty for a transient run
  std::vector<double> cycle_t, cycle_states;
  long rows() const { return static_cast<long>(time.size()); }
};

/// Called with (t, selected values) at every output row; may throw to stop the
/// run (the run is then "failed" with the exception's message).
using RowCheck = std::function<void(double t, const double* values)>;

/// Runs `settings` on the scene, keeping the `channels` (indices into the
/// scene's channels). Never throws for a failure of the run itself. `stop` (may
/// be empty) is asked after every step: true ends the run as failed, message
/// "interrupted at t = ...".
RunData run_case(const SceneSource& src, const IntegratorSettings& settings,
                 const std::vector<int>& channels, const RowCheck& check = nullptr,
                 const std::function<bool()>& stop = nullptr);

/// The periodic cycle of the scene (run/periodic.h, `method` by its name,
/// defect tolerance `tol`, the scene's own period) with `settings` as the cycle
/// map: the rows of the converged cycle (crank angle 0 .. 719 deg on the
/// engine's grid), its statistics summed over every cycle integrated and the
/// wall time of the whole search, and the cycle's start state (RunData::state).
/// `initial` (every body's q then v; empty = the scene's initial state) is the
/// search's first guess. Not converged: failed, with the defect and the
/// slowest multiplier in the message, and no rows. Never throws for a failure
/// of the run itself.
RunData run_periodic_case(const SceneSource& src, const IntegratorSettings& settings,
                          const std::vector<int>& channels, const std::string& method, double tol,
                          const std::function<bool()>& stop = nullptr,
                          const std::vector<double>& initial = {});

/// run_case `repeats` times (stopping at the first failure); the wall time is
/// the minimum over the runs, data and statistics are those of the last run.
/// `stop` (may be empty) is asked after every step and before each repeat.
RunData run_case_repeated(const SceneSource& src, const IntegratorSettings& settings,
                          const std::vector<int>& channels, int repeats,
                          const std::function<bool()>& stop = nullptr);

}  // namespace evas::study
