// A run into an output folder, as `evas run` makes it (and a sweep worker
// will): the folder locked for the run (io/run_lock.h), signals and the
// wall-time limit stopping it in order (run/stop.h), the rows written to
// DIR/results.h5 as they come, then DIR/summary.json and, when asked,
// DIR/results.csv, each written as far as it can be whatever the run's end.
#pragma once

#include <filesystem>
#include <string>

#include "io/scene.h"
#include "run/run.h"

namespace evas::run {

struct FolderOptions {
  std::filesystem::path dir;  ///< created when missing
  bool csv = false;           ///< also DIR/results.csv
  double max_wall = 0.0;      ///< wall-time limit [s]; 0: none
  bool quiet = false;         ///< no progress line, no start and end lines
  /// Replace an earlier run's results in `dir`; without it such a folder is refused.
  bool overwrite = false;
  std::string log_prefix = "evas run";  ///< of the lines on stderr
};

struct FolderResult {
  Outcome outcome;                    ///< exit_code covers the writes too (2 when one failed)
  std::string results, summary, csv;  ///< the files written ("" for csv when not asked)
  double t_reached = 0.0;             ///< last output time written
  long rows = 0;
};

/// Runs `scene` to `t_end` with `settings` into `opt.dir`. Throws InputError
/// (nothing written) for bad input: an empty output grid, a folder that
/// cannot be made or that another run holds, or (without `opt.overwrite`) a
/// folder that holds an earlier run's results. With `opt.overwrite` the earlier
/// results.h5, summary.json and results.csv are removed before the run starts,
/// so that nothing of the earlier run is left beside the new one.
FolderResult run_into_folder(const Scene& scene, double t_end, const IntegratorSettings& settings,
                             const FolderOptions& opt);

}  // namespace evas::run
