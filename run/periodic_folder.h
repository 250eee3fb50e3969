// `evas periodic`: the periodic cycle of a scene (run/periodic.h) into an
// output folder: DIR/results.h5 holds one converged cycle on the scene's own
// grid, at the times a run from the scene's start has them modulo the period
// (crank angle 0 .. 719 deg for the engine at 1 deg), and DIR/summary.json the
// method, its iterations with their periodicity defect, the cycle
// integrations, the Floquet multipliers and the wall time; DIR/state.yaml the
// periodic state (io/initial_state.h: `--initial` starts a run from it). A method that does
// not converge writes no results file (nothing that looks like a converged
// cycle), only the summary with its defect history, and exits 2.
#pragma once

#include "run/folder_run.h"
#include "run/period.h"
#include "run/periodic.h"

namespace evas::run {

struct PeriodicFolderResult {
  PeriodicResult periodic;
  ScenePeriod period;
  int exit_code = 0;   ///< 0 converged; 2 not converged, failed or a write failed; 128 + N signal
  std::string status;  ///< "completed" or "failed: ..."
  std::string results, summary, csv;  ///< files written ("" when not)
  std::string state;                  ///< DIR/state.yaml: the periodic state (initial_state.h)
  long rows = 0;
};

/// The periodic cycle of `scene` with `settings` as the cycle map. `period`:
/// "" for the scene's own, else as --period gives it. Throws InputError
/// (nothing written) for bad input.
PeriodicFolderResult periodic_into_folder(const Scene& scene, const IntegratorSettings& settings,
                                          const PeriodicOptions& popt, const std::string& period,
                                          const FolderOptions& opt);

/// summary.json's "periodic" member (the value alone).
std::string periodic_json(const PeriodicResult& r, const ScenePeriod& per,
                          const PeriodicOptions& opt, const std::string& indent);

}  // namespace evas::run
