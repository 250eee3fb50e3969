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
/// precision knobs its spec sweeps: one curve joins the cases that differ only
/// in those), wall time [s], error and its count of the work axis.
struct WorkPrecisionPoint {
  std::string family;
  double wall = 0.0, error = 0.0, work = 0.0;
};

/// The work axes beside wall time: `--work` name -> statistic (IntegratorStats field).
struct WorkAxis {
  const char* name;   ///< --work value
  const char* field;  ///< statistic (a /cases/stats dataset)
  const char* label;  ///< axis label
};
const std::vector<WorkAxis>& work_axes();
/// The axis of a --work value; throws InputError listing the names.
const WorkAxis& work_axis(const std::string& name);

struct WorkPrecisionData {
  std::string scene_name, window, norm;
  std::string reference;                   ///< the reference's description
  std::string work = "residuals";          ///< the second panel's axis (work_axes())
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
/// slope is NaN); "" when no point has a positive finite error. `measure`
/// (the --norm and the reference) is named in the title.
std::string convergence_script(const std::string& scene_name, const std::string& family,
                               const std::string& measure, const std::string& key,
                               const std::vector<double>& x, const std::vector<double>& error,
                               double slope, const std::filesystem::path& out);

}  // namespace evas
