// A run into an output folder (folder_run.h).
#include "run/folder_run.h"

#include <chrono>
#include <ctime>
#include <iostream>
#include <memory>
#include <optional>
#include <vector>

#include "io/results.h"
#include "io/run_lock.h"
#include "run/period.h"
#include "run/progress.h"
#include "run/stop.h"

namespace evas::run {

namespace {

// The rows to the results file, stopping on request, flushing rows that wait
// too long, drawing the progress line.
class ResultsSink : public RowSink {
 public:
  ResultsSink(const std::string& path, ResultsWriter::Options opt, const Stop& stop,
              Progress& progress, CycleTracker& cycles, double until_settled)
      : path_(path),
        opt_(std::move(opt)),
        stop_(stop),
        progress_(progress),
        cycles_(cycles),
        until_settled_(until_settled) {}

  void begin(const std::vector<Channel>& channels, const Integrator& integ) override {
    integ_ = &integ;
    writer_ = std::make_unique<ResultsWriter>(path_, channels, opt_);
    cycles_.begin(channels);
  }
  void between_steps(double t, double h) override {
    if (stop_.due()) stop_.stop(t, h);
    writer_->flush_if_due();
    if (progress_.due()) progress_.draw(t, integ_->stats().steps, h);
  }
  void row(double t, const double* values) override {
    writer_->append(t, values);
    cycles_.row(values);
    if (progress_.due()) {
      const IntegratorStats st = integ_->stats();
      progress_.draw(t, st.steps, st.last_step);
    }
    if (until_settled_ > 0.0 && cycles_.at_cycle_end() &&
        cycles_.measure().max_difference <= until_settled_)
      throw EndRun();
  }
  ResultsWriter* writer() { return writer_.get(); }

 private:
  std::string path_;
  ResultsWriter::Options opt_;
  const Stop& stop_;
  Progress& progress_;
  CycleTracker& cycles_;
  double until_settled_;
  const Integrator* integ_ = nullptr;
  std::unique_ptr<ResultsWriter> writer_;
};

// A write after the run: its failure is reported and fails a run that had
// completed (exit 2), never hides the run's own failure.
template <class Write>
void write_after(FolderResult& r, const std::string& prefix, Write&& write) {
  try {
    write();
  } catch (const std::exception& e) {
    std::cerr << prefix << ": FAILED: " << e.what() << "\n";
    if (r.outcome.exit_code == 0) {
      r.outcome.status = Status::failed;
      r.outcome.message = e.what();
      r.outcome.exit_code = 2;
    }
  }
}

// The files a run writes into its folder.
const char* const kRunFiles[] = {"results.h5", "summary.json", "results.csv", "state.yaml"};

// "results.h5 and summary.json, written 2026-11-28 17:40 UTC": the earlier
// run's files in `dir`, or "" when there are none.
std::string earlier_results(const std::filesystem::path& dir) {
  std::vector<std::string> found;
  // (not file_time_type{}: libstdc++'s file clock counts from 2174, so every
  // real time is before its zero and the message said "2173-12-31")
  auto newest = std::filesystem::file_time_type::min();
  for (const char* f : kRunFiles) {
    std::error_code ec;
    if (!std::filesystem::exists(dir / f, ec)) continue;
    found.emplace_back(f);
    const auto t = std::filesystem::last_write_time(dir / f, ec);
    if (!ec && t > newest) newest = t;
  }
  if (found.empty()) return "";
  std::string s;
  for (std::size_t i = 0; i < found.size(); ++i)
    s += (i == 0 ? "" : i + 1 == found.size() ? " and " : ", ") + found[i];
  const auto sys = std::chrono::time_point_cast<std::chrono::system_clock::duration>(
      newest - std::filesystem::file_time_type::clock::now() + std::chrono::system_clock::now());
  const std::time_t tt = std::chrono::system_clock::to_time_t(sys);
  std::tm tm{};
  char buf[32];
  if (gmtime_r(&tt, &tm) && std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M:%S UTC", &tm))
    s += std::string(", written ") + buf;
  return s;
}

// The period and rows per period of a run's settledness (no rows: why not).
Settledness settledness_plan(const Scene& scene, const FolderOptions& opt) {
  Settledness s;
  std::optional<ScenePeriod> per;
  if (!opt.period.empty())
    per = scene_period(scene, opt.period);
  else
    per = natural_period(scene, s.why_not);
  if (!per) return s;
  s.period_s = per->seconds;
  s.period_deg = per->degrees;
  s.rows_per_period = rows_per_period(scene.output.grid == "crank-angle", scene.output.step,
                                      per->seconds, per->degrees, s.why_not);
  return s;
}

// The warning of a run whose last two cycles differ by more than the tolerance,
// or that holds too few cycles to tell (a run with no period says nothing).
void warn_unsettled(const Settledness& s, const FolderOptions& opt) {
  if (s.measured && !s.settled()) {
    std::cerr << opt.log_prefix << ": warning: not settled: the last cycle ("
              << format_number(s.period_s) << " s) differs from the one before by "
              << format_number(s.max_difference) << " in '" << s.worst_channel << "' (tolerance "
              << format_number(s.tolerance)
              << "); run longer (--until-settled TOL) or find the steady cycle with evas "
                 "periodic\n";
  } else if (!s.measured && s.rows_per_period > 0 && !opt.quiet) {
    std::cerr << opt.log_prefix << ": note: whether the run settled is not known: " << s.why_not
              << " (summary.json, settledness)\n";
  }
}

}  // namespace

std::unique_ptr<RunLock> open_run_folder(const FolderOptions& opt) {
  std::error_code ec;
  std::filesystem::create_directories(opt.dir, ec);
  if (ec)
    throw InputError(opt.dir.string() + ": cannot create the output directory: " + ec.message());
  // One run per folder: refuse before anything in it is touched.
  auto lock = std::make_unique<RunLock>(opt.dir);
  if (!lock->note().empty()) std::cerr << opt.log_prefix << ": warning: " << lock->note() << "\n";
  // An earlier run's results are never replaced silently (docs/errors.md).
  if (const std::string earlier = earlier_results(opt.dir); !earlier.empty()) {
    if (!opt.overwrite)
      throw InputError(opt.dir.string() + ": the folder holds an earlier run's results (" +
                       earlier +
                       "): give --overwrite to replace them, or choose another folder with "
                       "--out DIR");
    for (const char* f : kRunFiles) {
      std::error_code ec;
      std::filesystem::remove(opt.dir / f, ec);
      if (ec)
        throw InputError((opt.dir / f).string() +
                         ": cannot remove the earlier run's file (--overwrite): " + ec.message());
    }
    if (!opt.quiet)
      std::cerr << opt.log_prefix << ": replacing the earlier results in " << opt.dir.string()
                << " (" << earlier << ", --overwrite)\n";
  }
  return lock;
}

RunSummary summary_of(const Scene& scene, const IntegratorSettings& settings) {
  RunSummary sum;
  sum.scene = scene.name;
  sum.scene_path = scene.path;
  sum.integrator = settings.name;
  sum.settings = settings;
  sum.grid = scene.output.grid;
  sum.t_start = scene.t_start;
  sum.peak_memory_mb = process_peak_memory_mb();
  return sum;
}

FolderResult run_into_folder(const Scene& scene, double t_end, const IntegratorSettings& settings,
                             const FolderOptions& opt) {
  const std::unique_ptr<Integrator> integ = make_integrator(settings.name);
  SceneRun run(scene, t_end);
  const Settledness plan = settledness_plan(scene, opt);  // may refuse --period
  const std::unique_ptr<RunLock> lock = open_run_folder(opt);
  const Stop stop(opt.max_wall);  // signals from here on end the run in order

  FolderResult r;
  r.results = (opt.dir / "results.h5").string();
  ResultsWriter::Options wopt;
  wopt.scene_text = scene.text;
  wopt.integrator = settings.name;
  wopt.grid = scene.output.grid;
  Progress progress(opt.quiet, scene.t_start, t_end);
  CycleTracker cycles(plan.rows_per_period, plan.why_not);
  ResultsSink sink(r.results, wopt, stop, progress, cycles, opt.until_settled);
  if (!opt.quiet)
    std::cerr << opt.log_prefix << ": scene '" << scene.name << "', "
              << scene.model->bodies().size() << " bodies, " << run.system().size()
              << " modal coordinates, " << scene.model->elements().size()
              << " elements, integrator " << settings.name << ", " << run.outputs().times().size()
              << " output points, t = " << scene.t_start << " .. " << t_end << " s\n";

  r.outcome = run.perform(*integ, settings, sink);
  if (r.outcome.completed()) {
    const IntegratorStats& st = r.outcome.stats;
    progress.draw(sink.writer()->last_time(), st.steps, st.last_step);
  } else {
    progress.end();
    std::cerr << opt.log_prefix << ": FAILED: " << r.outcome.message << "\n";
  }
  progress.end();

  // The results, the summary and the CSV are each written as far as they can be.
  ResultsWriter* writer = sink.writer();
  if (writer)
    write_after(r, opt.log_prefix,
                [&] { writer->finish(r.outcome.stats, r.outcome.status_text()); });
  RunSummary sum = summary_of(scene, settings);
  sum.status = r.outcome.status_text();
  sum.t_end = t_end;
  r.rows = writer ? writer->rows_written() : 0;
  r.t_reached = r.rows > 0 ? writer->last_time_written() : scene.t_start;
  sum.t_reached = r.t_reached;
  sum.rows = r.rows;
  sum.stats = r.outcome.stats;
  if (writer) {
    sum.channels = writer->channels();
    sum.channel_summary = writer->summary();
  }
  r.settledness = cycles.measure();
  r.settledness.period_s = plan.period_s;
  r.settledness.period_deg = plan.period_deg;
  r.settledness.tolerance = opt.until_settled > 0.0 ? opt.until_settled : opt.settle_tol;
  if (r.settledness.why_not.empty()) r.settledness.why_not = plan.why_not;
  sum.extra.emplace_back("settledness", settledness_json(r.settledness, "  "));
  warn_unsettled(r.settledness, opt);
  r.summary = (opt.dir / "summary.json").string();
  write_after(r, opt.log_prefix, [&] { write_summary_json(r.summary, sum); });
  if (opt.csv) {
    r.csv = (opt.dir / "results.csv").string();
    write_after(r, opt.log_prefix, [&] { export_csv(r.results, r.csv); });
  }
  return r;
}

}  // namespace evas::run
