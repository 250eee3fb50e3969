// The diagrams of `evas study`: work-precision (error against wall time and
// against residual evaluations, one curve per family of cases) and
// convergence (error against step or tolerance with the fitted slope), as
// gnuplot scripts. The study draws them as it runs; `evas plot work-precision
// STUDY.h5` draws the first again from the study's file.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace evas {

/// A case of a work-precision study: its family (its settings without the
/// precision knobs: one curve joins the cases that differ only in those),
/// wall time [s], error and residual evaluations.
struct WorkPrecisionPoint {
  std::string family;
  double wall = 0.0, error = 0.0, residuals = 0.0;
};

struct WorkPrecisionData {
  std::string scene_name, window, norm;
  std::vector<WorkPrecisionPoint> points;  ///< completed cases only
};

/// Reads a work-precision study's study.h5 (its completed cases). Throws
/// InputError naming the file when it is another file or cannot be read.
WorkPrecisionData read_work_precision(const std::string& path);

/// The work-precision figure `out` (.png or .svg); "" when no point has a
/// positive finite error. Settings every curve shares go to the title.
std::string work_precision_script(const WorkPrecisionData& d, const std::filesystem::path& out);

/// The convergence figure: error against `key` (x > 0), with the least-squares
/// line of slope `slope` through the points' centroid in log-log (none when
/// slope is NaN); "" when no point has a positive finite error.
std::string convergence_script(const std::string& scene_name, const std::string& family,
                               const std::string& key, const std::vector<double>& x,
                               const std::vector<double>& error, double slope,
                               const std::filesystem::path& out);

}  // namespace evas
