// `evas study`: compare integrators on a scene (docs/study.md).
//
//   work_precision  a grid of cases, each run against one reference: error,
//                   wall time and every integrator statistic per case;
//   convergence     one family sweeping `step` or `rtol`: the observed order
//                   (least-squares slope of log error against log step/rtol);
//   stability       the largest step at which a fixed-step case stays stable,
//                   found by bisection in log h, optionally over a parameter sweep.
//
// The logic lives here (the CLI in apps/cmd_study.cpp is a thin layer), so
// tests and other front ends call the same functions. Errors: InputError for
// bad input, ReferenceFailed when the reference run fails; a failed case is a
// result (status "failed" and its message), never an exception.
#pragma once

#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "study/case_grid.h"
#include "study/measure.h"
#include "study/run_case.h"
#include "study/scene_edit.h"
#include "study/steady_start.h"
#include "study/task_runner.h"

namespace evas::study {

/// The reference run failed (or a reference file does not fit the scene's output).
class ReferenceFailed : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

constexpr const char* kDefaultReference = "ida rtol=1e-9 atol=1e-12";

/// Options every sub-command shares.
struct Options {
  std::string scene;                ///< scene file
  std::vector<std::string> params;  ///< "ITEM.KEY=VALUE" scene overrides
  std::optional<double> t_end;      ///< end time override [s]
  std::string channels;             ///< comma-separated globs; "" = all but crank_angle
  std::string window;               ///< "" = last-cycles=1 on a crank-angle grid, else all
  std::string norm = kDefaultNorm;  ///< --norm (measure.h: group, channel, rms, floor=F, l2, final)
  std::string reference = kDefaultReference;  ///< case spec of the reference run
  std::string reference_file;                 ///< or a results file (evas run) to compare against
  /// or analytic: "CHANNEL=EXPR" of t (study/expression.h), one per channel
  /// compared (they select the channels)
  std::vector<std::string> reference_exprs;
  int repeats = 1;                 ///< wall time = minimum over this many runs
  std::string work = "residuals";  ///< work-precision's second work axis (plot/study_figures.h)
  std::string out_dir;             ///< "" = out/study-<scene name>
  bool plot = true;                ///< run gnuplot when present
  std::ostream* log = nullptr;     ///< progress lines (nullptr: silent)
  std::function<bool()> stop;      ///< true once an interrupt was requested
  /// Runs the cases (nullptr: one after another in this process); --jobs, MPI.
  std::shared_ptr<TaskRunner> runner;
  double max_wall = 0.0;  ///< wall-clock limit of one run [s] (--max-wall); 0 = none
  /// Every run from one state (--initial FILE), or one period from the
  /// periodic state (--steady): steady_start.h
  SteadyStart start;
};

/// A case spec with where it came from ("" = --case, else "FILE:LINE").
struct CaseInput {
  std::string spec;
  std::string where;
};

/// The reference every case is compared with.
struct Reference {
  std::string description;  ///< label of the reference case, or the results file
  std::vector<double> time, crank;
  Mat y;  ///< rows x selected channels
  std::vector<std::string> names, units;
  IntegratorStats stats;
  double wall = std::numeric_limits<double>::quiet_NaN();
};

/// One row of a study table.
struct CaseResult {
  Case c;
  CaseStatus status = CaseStatus::not_run;
  std::string message;
  double error = std::numeric_limits<double>::quiet_NaN();
  /// Every selected channel's error (NaN: no scale) and the one that sets `error`.
  std::vector<double> channel_error;
  std::string error_channel;
  double wall = std::numeric_limits<double>::quiet_NaN();
  long rows = 0;  ///< output rows reached
  IntegratorStats stats;
};

/// What a study measured and where it wrote it.
struct StudyInfo {
  std::string scene_name, scene_path, scene_text, grid;
  std::vector<std::string> channels;  ///< selected channel names
  std::string window, norm, error_definition;
  std::string start;  ///< what every run starts from ("" = the scene's initial state)
  std::string out_dir;
  bool interrupted = false;
  std::vector<std::string> files;  ///< written files
};

struct WorkPrecisionResult {
  StudyInfo info;
  Reference reference;
  std::vector<CaseResult> cases;
};

/// Default cases of work_precision when none are given.
std::vector<std::string> default_work_precision_cases();

/// Runs every case of every spec against the reference; writes study.csv,
/// study.md, study.h5 (after every case) and study.png (gnuplot, at the end).
WorkPrecisionResult work_precision(const Options& opt, const std::vector<CaseInput>& specs);

struct ConvergenceResult {
  StudyInfo info;
  Reference reference;
  std::string key;                 ///< the swept key: step or rtol
  std::string family;              ///< the case's label without the swept key
  std::vector<CaseResult> cases;   ///< sorted by the swept value, largest first
  std::vector<double> x;           ///< swept value per case
  std::vector<double> pair_order;  ///< order between case i-1 and i (NaN for i = 0 or a gap)
  double slope = std::numeric_limits<double>::quiet_NaN();  ///< least-squares observed order
  int points = 0;                                           ///< cases in the fit
};

/// One family sweeping `step` or `rtol`; writes convergence.csv/.md/.png.
ConvergenceResult convergence(const Options& opt, const CaseInput& spec);

struct StabilityOptions {
  double h_min = 0.0, h_max = 0.0;
  std::string sweep;  ///< "ITEM.KEY=V1,V2,..." or ""
  double growth = 10.0;
  int bisections = 12;
};

/// Outcome of the stability search at one sweep value: bracketed (limit
/// between h_stable and h_unstable), stable up to HMAX, unstable at HMIN,
/// reference failed, interrupted, timed out (a trial ran past --max-wall: it
/// says nothing of stability, so the search ends there with its bracket so
/// far) or not run.
enum class StabilityStatus {
  not_run,
  bracketed,
  stable_to_hmax,
  unstable_at_hmin,
  reference_failed,
  interrupted,
  timed_out
};

/// "not run", "bracketed", "stable up to HMAX", "unstable at HMIN",
/// "reference failed", "interrupted" or "timed out": the text written to
/// every file.
const char* to_text(StabilityStatus s);

/// Result of the search at one sweep value.
struct StabilityPoint {
  std::string value;  ///< sweep value ("" without sweep)
  StabilityStatus status = StabilityStatus::not_run;
  double h_stable = std::numeric_limits<double>::quiet_NaN();    ///< largest stable step found
  double h_unstable = std::numeric_limits<double>::quiet_NaN();  ///< smallest unstable step found
  std::string message;  ///< why h_unstable is unstable (or the reference failure)
  /// The largest stable step's interpolation excursion: with a step longer
  /// than two output intervals stability is judged at the step points, and
  /// the outputs between them may swing far beyond (empty when they did not
  /// exceed the bound)
  std::string interpolation;
  int runs = 0;
  double reference_max =
      std::numeric_limits<double>::quiet_NaN();  ///< largest |y_ref| (all channels)
};

struct StabilityResult {
  StudyInfo info;
  Case c;
  std::string sweep_key;  ///< "ITEM.KEY" or ""
  std::vector<StabilityPoint> points;
};

/// Largest stable step of one case (its `step` ignored) in [h_min, h_max]: a
/// step is stable when the run completes and no selected channel's max |y|
/// (after the first output) exceeds growth times the reference run's. Writes
/// stability.csv/.md and, with a sweep, stability.png. A failed reference run
/// at a sweep value is recorded there (status "reference failed") unless there
/// is no sweep, when it throws ReferenceFailed.
StabilityResult stability(const Options& opt, const CaseInput& spec, const StabilityOptions& so);

/// Least-squares slope of log(e) against log(x) over the points with x, e > 0
/// finite; NaN with fewer than two.
double log_log_slope(const std::vector<double>& x, const std::vector<double>& e,
                     int* used = nullptr);

}  // namespace evas::study
