// A run into an output folder, as `evas run` makes it (and a sweep worker
// will): the folder locked for the run (io/run_lock.h), signals and the
// wall-time limit stopping it in order (run/stop.h), the rows written to
// DIR/results.h5 as they come, then DIR/summary.json and, when asked,
// DIR/results.csv, each written as far as it can be whatever the run's end.
#pragma once

#include <filesystem>
#include <memory>
#include <string>

#include "io/results.h"
#include "io/run_lock.h"
#include "io/scene.h"
#include "run/run.h"
#include "run/settledness.h"

namespace evas::run {

struct FolderOptions {
  std::filesystem::path dir;  ///< created when missing
  bool csv = false;           ///< also DIR/results.csv
  double max_wall = 0.0;      ///< wall-time limit [s]; 0: none
  bool quiet = false;         ///< no progress line, no start and end lines
  /// Replace an earlier run's results in `dir`; without it such a folder is refused.
  bool overwrite = false;
  std::string log_prefix = "evas run";  ///< of the lines on stderr
  /// The period whose last two cycles are compared (run/period.h): "" the
  /// scene's own, else as --period gives it ("720deg", "0.04s").
  std::string period;
  /// Settled when the last two cycles differ by at most this (run/settledness.h);
  /// a run that has not settled is warned of.
  double settle_tol = 1e-3;
  /// > 0: end the run, completed, at the first cycle end where the last two
  /// cycles differ by at most this (--until-settled); t_end is then the limit.
  double until_settled = 0.0;
};

struct FolderResult {
  Outcome outcome;                    ///< exit_code covers the writes too (2 when one failed)
  std::string results, summary, csv;  ///< the files written ("" for csv when not asked)
  double t_reached = 0.0;             ///< last output time written
  long rows = 0;
  Settledness settledness;  ///< the last two cycles compared (measured = false: why_not)
};

/// Makes `opt.dir` ready for a run's files: created, locked for this run
/// (the lock is returned; held until it is destroyed) and, with
/// `opt.overwrite`, emptied of an earlier run's results.h5, summary.json and
/// results.csv. Throws InputError (nothing touched) when the folder cannot be
/// made, another run holds it, or it holds earlier results without
/// `opt.overwrite`.
std::unique_ptr<RunLock> open_run_folder(const FolderOptions& opt);

/// The summary's fields of a run of `scene` with `settings` that do not
/// depend on how it ended: scene name and path, integrator, settings, grid,
/// start time and the peak memory so far.
RunSummary summary_of(const Scene& scene, const IntegratorSettings& settings);

/// Runs `scene` to `t_end` with `settings` into `opt.dir`. Throws InputError
/// (nothing written) for bad input: an empty output grid, a folder that
/// cannot be made or that another run holds, or (without `opt.overwrite`) a
/// folder that holds an earlier run's results. With `opt.overwrite` the earlier
/// results.h5, summary.json and results.csv are removed before the run starts,
/// so that nothing of the earlier run is left beside the new one.
FolderResult run_into_folder(const Scene& scene, double t_end, const IntegratorSettings& settings,
                             const FolderOptions& opt);

}  // namespace evas::run
