// Private to study/: what the `evas study` drivers (work_precision.cpp,
// convergence.cpp, stability.cpp) share. The scene setup, the reference (run,
// read from a results file, window rows), the loop over the cases of
// work_precision and convergence, the case table (CSV, Markdown, HDF5) and the
// gnuplot helpers. Not part of the public API (study/study.h).
#pragma once

#include <filesystem>
#include <functional>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "io/hdf5_util.h"
#include "study/study.h"

namespace evas {
class GnuplotProcess;
}

namespace evas::study::detail {

namespace fs = std::filesystem;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// True once an interrupt was requested.
bool stopped(const Options& o);
/// A progress line to opt.log (nothing without one).
void say(const Options& o, const std::string& line);

/// A settings label without the tokens "KEY=..." of the given keys.
std::string strip_keys(const std::string& label, const std::set<std::string>& keys);
/// The strings joined with `sep`.
std::string join(const std::vector<std::string>& v, const std::string& sep = ", ");

// Everything a study shares once the scene is read.
struct Setup {
  SceneSource src;
  SceneInfo info;
  std::vector<int> channels;
  std::vector<std::string> names, units;
  Window window;
  bool window_default = false;
  ErrorMeasure measure;
  fs::path out;
  StartedFrom started;       ///< --initial / --steady (steady_start.h)
  bool created_out = false;  ///< prepare() made the output folder (it was not there)
  std::size_t params = 0;    ///< how many --param overrides edit the scene
};

/// Removes the output folder when prepare() made it and it is still empty as
/// this goes out of scope (a study refused after prepare() leaves no empty
/// folder behind).
class EmptyOutGuard {
 public:
  explicit EmptyOutGuard(const Setup& s) : s_(s) {}
  ~EmptyOutGuard();
  EmptyOutGuard(const EmptyOutGuard&) = delete;
  EmptyOutGuard& operator=(const EmptyOutGuard&) = delete;

 private:
  const Setup& s_;
};

/// Reads the scene, selects the channels, window and norm, creates the output folder.
Setup prepare(const Options& opt);
StudyInfo make_info(const Setup& s);

// --- reference --------------------------------------------------------------------

/// The reference case of a spec on a scene (exactly one case).
Case reference_case(const std::string& spec, const IntegratorSettings& base);
/// Runs opt.reference on the scene; ReferenceFailed when it fails.
Reference run_reference(const Options& opt, const SceneSource& src, const SceneInfo& info,
                        const std::vector<int>& channels, const std::vector<std::string>& names,
                        const std::vector<std::string>& units);
/// The reference from its run: ReferenceFailed when the run failed or gave
/// fewer rows than the scene's output times.
Reference reference_of(const Case& c, const RunData& d, const SceneInfo& info,
                       const std::vector<std::string>& names,
                       const std::vector<std::string>& units);
/// Reads opt.reference_file at the scene's output times.
Reference read_reference(const Options& opt, const SceneInfo& info,
                         const std::vector<std::string>& names,
                         const std::vector<std::string>& units);
/// read_reference with --reference-file, else run_reference.
Reference make_reference(const Options& opt, const Setup& s);
/// Window rows on the reference (falls back to all for a default window that does not fit).
std::vector<int> reference_rows(const Options& opt, Setup& s, const Reference& ref);

// --- cases ------------------------------------------------------------------------

/// The balance tolerance of linear-acceleration's iteration (its default
/// 1e-3, 0.1 % of the balance, is an error of its own that stays when h
/// shrinks): a case that reads balance_tol and whose spec (and the scene's
/// integrator block) does not set it gets kStudyBalanceTol, so that the study
/// measures the method's truncation error. Says so on opt.log once.
constexpr double kStudyBalanceTol = 1e-9;
void tie_iteration_tolerance(const Options& opt, std::vector<Case>& cases,
                             const IntegratorSettings& base);

/// One task per case: the scene with the case's settings, the study's channels,
/// repeats and --max-wall.
std::vector<TaskSpec> case_tasks(const Options& opt, const Setup& s,
                                 const std::vector<Case>& cases);
/// opt.runner, or the serial runner.
TaskRunner& runner_of(const Options& opt);

/// The loop of work_precision and convergence: runs every case through the
/// study's runner (in the order they finish with several workers), stores each
/// evaluated against the reference in results[k], prints its line and calls
/// on_case_done (the driver writes its tables there). A case cut short by the
/// interrupt stays "not run"; a stop request sets info.interrupted.
void run_cases(const Options& opt, const Setup& s, const std::vector<Case>& cases,
               const Reference& ref, const std::vector<int>& rows, std::vector<CaseResult>& results,
               StudyInfo& info, const std::function<void()>& on_case_done);

// --- tables -----------------------------------------------------------------------

struct Column {
  enum class Kind { Text, Real, Integer };
  std::string csv;  // CSV header
  std::string h5;   // dataset path below /cases
  Kind kind = Kind::Text;
  std::vector<std::string> text;
  std::vector<double> num;
};

/// The case table: label, integrator, every setting, status, message, error,
/// wall, rows and every statistic.
std::vector<Column> case_columns(const std::vector<CaseResult>& rows);
std::string columns_csv(const std::vector<Column>& cols, std::size_t nrows);
void write_columns_h5(hid_t group, const std::vector<Column>& cols);

/// The Markdown title and the list above a case table.
std::string md_header(const std::string& title, const StudyInfo& info, const Options& opt,
                      const Reference& ref);
std::string status_cell(const CaseResult& r);

/// errors.csv: one row per case and selected channel (case index, label,
/// channel, unit, scale, error, and 1 on the channel that sets the case's
/// error), under the study's measure (info.norm).
std::string errors_csv(const std::vector<CaseResult>& cases, const Reference& ref,
                       const std::vector<int>& rows, const StudyInfo& info);
/// The same as a (cases x channels) dataset "channel_error" of group g.
void write_channel_errors_h5(hid_t g, const std::vector<CaseResult>& cases, std::size_t channels);

void write_reference_h5(hid_t file, const Reference& ref, const std::vector<int>& rows);
/// Writes an HDF5 file through body at path.tmp and renames it onto path.
void write_h5_atomic(const fs::path& path, const std::function<void(hid_t)>& body);
void write_info_attributes(hid_t f, const std::string& kind, const StudyInfo& info,
                           const Options& opt);

// --- gnuplot ----------------------------------------------------------------------

/// Writes the gnuplot script and, with --plot and gnuplot present, runs it;
/// adds the files written to info.files. True when the figure was made.
bool plot(const Options& opt, const fs::path& script, const std::string& text, StudyInfo& info,
          const fs::path& png);
/// A figure: its gnuplot script's path and text and the PNG it draws.
struct Figure {
  fs::path script;
  std::string text;
  fs::path png;
};
/// plot() of figures of one folder with one gnuplot process (`started`, when
/// given and ready, else a new one); a figure that process did not draw is
/// tried alone (and reported as plot() does).
void plot_all(const Options& opt, const std::vector<Figure>& figures, StudyInfo& info,
              GnuplotProcess* started = nullptr);

}  // namespace evas::study::detail
