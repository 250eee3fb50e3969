// evas run SCENE: read the scene, integrate, record results as the run goes.
#include <boost/program_options.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <iostream>
#include <memory>

#include "apps/commands.h"
#include "apps/run_stop.h"
#include "apps/step_advice.h"
#include "dae/consistent.h"
#include "integrators/common.h"
#include "integrators/integrator.h"
#include "integrators/settings.h"
#include "io/outputs.h"
#include "io/results.h"
#include "io/run_lock.h"
#include "io/scene.h"
#include "solver/system.h"

namespace evas::cli {

namespace {

// Progress line on stderr, redrawn at most twice a second.
class Progress {
 public:
  Progress(bool quiet, double t0, double t1) : quiet_(quiet), t0_(t0), t1_(t1) {}
  bool due() const {
    return !quiet_ &&
           std::chrono::duration<double>(std::chrono::steady_clock::now() - last_).count() >= 0.5;
  }
  /// h: the last step [s] (0: unknown); a collapsing step shows here first.
  void draw(double t, long steps, double h) {
    if (quiet_) return;
    last_ = std::chrono::steady_clock::now();
    const double pct = 100.0 * (t - t0_) / (t1_ - t0_);
    std::fprintf(stderr, "\r  t = %.6g s  %5.1f %%  %ld steps  step %.2g s   ", t, pct, steps,
                 std::abs(h));
    std::fflush(stderr);
    drawn_ = true;
  }
  void end() {
    if (drawn_) std::fputc('\n', stderr);
    drawn_ = false;
  }

 private:
  bool quiet_;
  double t0_, t1_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point last_{};
};

// Without --out the scene name becomes the folder out/<name>: it must be one
// plain path component, so that no scene writes outside out/.
void check_folder_name(const Scene& scene) {
  const std::string& n = scene.name;
  std::string why;
  if (n.empty()) why = "is empty";
  if (n == "." || n == "..") why = "is a relative folder";
  if (n.find('/') != std::string::npos || n.find('\\') != std::string::npos)
    why = "contains a path separator";
  std::string shown;
  for (char ch : n) {
    const unsigned char c = static_cast<unsigned char>(ch);
    if (c < 0x20 || c == 0x7F) {
      why = "contains a control character";
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", c);
      shown += buf;
    } else {
      shown += ch;
    }
  }
  if (!why.empty())
    throw InputError(scene.path + ": name: '" + shown + "' " + why +
                     " and cannot name the output folder out/<name>; use a plain name (no '/', "
                     "'..' or control characters), or choose the folder with --out");
}

}  // namespace

// A non-finite output ends the run naming the channel and the state it came from.
void check_finite(const OutputSet& outputs, const std::vector<double>& row, double t,
                  const System& sys, const Vec& q, const Vec& v) {
  for (std::size_t c = 0; c < row.size(); ++c)
    if (!std::isfinite(row[c]))
      throw RunError("channel '" + outputs.channels()[c].name + "' is " +
                     (std::isnan(row[c]) ? "NaN" : "infinite") + " at " +
                     sys.describe_state(t, q.data(), v.data()));
}

int cmd_run(const std::vector<std::string>& args) {
  po::options_description opts(
      "usage: evas run SCENE.yaml [options]\n\n"
      "Simulates a scene and writes DIR/results.h5 and DIR/summary.json.\n"
      "Exit codes: 0 completed; 1 bad input, or DIR is in use by another run (nothing\n"
      "written); 2 the run failed: integrator error, non-finite value, results file not\n"
      "writable (disk full), --max-wall reached; 128+N stopped by signal N: 130 SIGINT\n"
      "(Ctrl-C), 143 SIGTERM, 129 SIGHUP (after the current step; a second signal\n"
      "ends the process at once). A failed or stopped run keeps its rows, writes the status "
      "'failed: ...',\n"
      "its statistics and DIR/summary.json.\n\n"
      "options");
  opts.add_options()("help,h", "show this help")(
      "integrator", po::value<std::string>(),
      "integrator: ida, cvode, generalized-alpha, linear-acceleration, radau")(
      "rtol", po::value<std::string>(), "relative tolerance (adaptive integrators)")(
      "atol", po::value<std::string>(), "absolute tolerance (adaptive integrators)")(
      "step", po::value<std::string>(),
      "fixed step [s] (generalized-alpha, linear-acceleration, radau)")(
      "set,s", po::value<std::vector<std::string>>()->composing(),
      "KEY=VALUE: any integrator setting, repeatable (see --help-settings); applied after "
      "the scene's integrator block and the options above")(
      "help-settings", "list every integrator setting with its default and meaning")(
      "t-end", po::value<double>(), "end time [s] (overrides the scene)")(
      "out", po::value<std::string>(), "output directory (default out/<scene name>)")(
      "csv", "also write DIR/results.csv")(
      "max-wall", po::value<double>(),
      "wall-time limit [s]: the run stops with status 'failed: wall-time limit ...' "
      "(exit 2, rows kept) when it runs longer")("quiet,q", "no progress line");
  po::variables_map vm;
  if (parse_args(args, opts, {"scene"}, vm)) return 0;
  if (vm.count("help-settings")) {
    std::cout << settings_reference();
    return 0;
  }
  if (!vm.count("scene")) {
    std::cerr << "evas run: missing SCENE file\n" << opts << "\n";
    return 1;
  }
  const bool quiet = vm.count("quiet") > 0;

  // --- input: everything here exits 1 on InputError (caught in main) ---
  Scene scene = read_scene(vm["scene"].as<std::string>());
  IntegratorSettings& set = scene.integrator;
  if (vm.count("integrator"))
    set_integrator_setting(set, "name", vm["integrator"].as<std::string>());
  for (const char* key : {"rtol", "atol", "step"})
    if (vm.count(key)) {
      try {
        set_integrator_setting(set, key, vm[key].as<std::string>());
      } catch (const InputError& e) {
        throw InputError(std::string("--") + e.what());
      }
    }
  if (vm.count("set"))
    for (const auto& a : vm["set"].as<std::vector<std::string>>()) apply_setting_assignment(set, a);
  warn_unread_settings("run", vm, set);
  if (vm.count("t-end")) {
    scene.t_end = vm["t-end"].as<double>();
    if (!std::isfinite(scene.t_end))
      throw InputError("--t-end: " + std::to_string(scene.t_end) + " is not a finite time");
    if (!(scene.t_end > scene.t_start))
      throw InputError("--t-end must be after the start time " + std::to_string(scene.t_start));
  }
  double max_wall = 0.0;
  if (vm.count("max-wall")) {
    max_wall = vm["max-wall"].as<double>();
    if (!(max_wall > 0.0)) throw InputError("--max-wall must be a positive number of seconds");
  }
  std::unique_ptr<Integrator> integ = make_integrator(set.name);
  System sys(*scene.model);
  OutputSet outputs(scene.output, sys, scene.t_start, scene.t_end);
  if (outputs.times().empty())
    throw InputError(scene.path + ": output: the grid has no output time in [" +
                     std::to_string(scene.t_start) + ", " + std::to_string(scene.t_end) + "] s" +
                     (outputs.has_crank_angle()
                          ? " (on the crank-angle grid: the crank turns from " +
                                format_number(outputs.crank_angle(scene.t_start)) + " to " +
                                format_number(outputs.crank_angle(scene.t_end)) +
                                " deg in that time)"
                          : std::string()));
  if (!vm.count("out")) check_folder_name(scene);
  const std::filesystem::path dir = vm.count("out")
                                        ? std::filesystem::path(vm["out"].as<std::string>())
                                        : std::filesystem::path("out") / scene.name;
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw InputError(dir.string() + ": cannot create the output directory: " + ec.message());
  // One run per folder: refuse before anything in it is touched.
  const RunLock lock(dir);
  if (!lock.note().empty()) std::cerr << "evas run: warning: " << lock.note() << "\n";
  if (const std::string w = coarse_step_warning(*scene.model, set); !w.empty())
    std::cerr << "evas run: warning: " << w << "\n";
  const RunStop stop(max_wall);  // signals from here on end the run in order
  const std::string h5path = (dir / "results.h5").string();

  // The start: a constrained system from consistent values (dae/consistent.h),
  // and the integrator prepared before the results file is made, so that its
  // multipliers, if it has them, get channels. A failure here is reported by
  // the run below, with the results file and summary written as for any failure.
  Vec q0, v0, lambda0;
  std::exception_ptr init_error;
  try {
    sys.initial_state(q0, v0);
    if (sys.constraint_count() > 0) {
      const dae::ConsistentState cs = dae::consistent_state(sys, scene.t_start, q0, v0);
      q0 = cs.q;
      v0 = cs.v;
      lambda0 = cs.lambda;
    }
    integ->init(sys, scene.t_start, q0, v0, set);
    if (Vec lam; sys.constraint_count() > 0 && integ->multipliers(lam)) {
      outputs.add_multiplier_channels();
      lambda0 = lam;
    }
  } catch (...) {
    init_error = std::current_exception();
  }

  ResultsWriter::Options wopt;
  wopt.scene_text = scene.text;
  wopt.integrator = set.name;
  wopt.grid = scene.output.grid;
  ResultsWriter writer(h5path, outputs.channels(), wopt);

  if (!quiet)
    std::cerr << "evas run: scene '" << scene.name << "', " << scene.model->bodies().size()
              << " bodies, " << sys.size() << " modal coordinates, "
              << scene.model->elements().size() << " elements, integrator " << set.name << ", "
              << outputs.times().size() << " output points, t = " << scene.t_start << " .. "
              << scene.t_end << " s\n";

  // --- the run ---
  Progress progress(quiet, scene.t_start, scene.t_end);
  std::vector<double> row(outputs.size());
  std::string status = "completed";
  int code = 0;
  // Between steps (every accepted step of every integrator): stop on
  // request, flush rows that wait too long, show the step size.
  integ->set_step_monitor([&](double t, double h) {
    if (stop.due()) stop.stop(t, h);
    writer.flush_if_due();
    if (progress.due()) progress.draw(t, integ->stats().steps, h);
  });
  try {
    if (init_error && q0.size() != sys.size()) std::rethrow_exception(init_error);
    if (stop.due()) stop.stop(scene.t_start, 0.0);
    std::vector<double> times = outputs.times();
    const double eps = 1e-12 * std::max(1.0, std::abs(scene.t_start));
    if (times.front() <= scene.t_start + eps) {
      outputs.values(scene.t_start, q0.data(), v0.data(), row.data(), lambda0.data());
      writer.append(scene.t_start, row);
      times.erase(times.begin());
    }
    if (init_error) std::rethrow_exception(init_error);
    integrate(*integ, sys, scene.t_start, times, [&](double t, const Vec& q, const Vec& v) {
      if (stop.due()) stop.stop(t, integ->stats().last_step);
      Vec lam;
      const bool with_lam = outputs.has_multiplier_channels() && integ->multipliers(lam);
      try {
        outputs.values(t, q.data(), v.data(), row.data(), with_lam ? lam.data() : nullptr);
      } catch (const RangeError& e) {
        // the integrator took the steps, but the state at this output (a step's
        // or the interpolant between two) is outside an element's range
        throw RunError(std::string("the output channels at t = ") + format_number(t) +
                       " s cannot be evaluated: " + e.what() +
                       "; state: " + sys.describe_state(t, q.data(), v.data()) +
                       ". The steps around this time passed the integrator's own tests; with a "
                       "fixed step (generalized-alpha, linear-acceleration) a smaller 'step' or "
                       "step_control=adaptive follows the motion more closely");
      }
      check_finite(outputs, row, t, sys, q, v);
      writer.append(t, row);
      if (progress.due()) {
        const IntegratorStats st = integ->stats();
        progress.draw(t, st.steps, st.last_step);
      }
    });
    const IntegratorStats st = integ->stats();
    progress.draw(writer.last_time(), st.steps, st.last_step);
  } catch (const RunStopped& e) {
    progress.end();
    status = std::string("failed: ") + e.what();
    code = e.exit_code();
    std::cerr << "evas run: FAILED: " << e.what() << "\n";
  } catch (const std::exception& e) {
    progress.end();
    status = std::string("failed: ") + e.what();
    code = 2;
    std::cerr << "evas run: FAILED: " << e.what() << "\n";
  }
  integ->set_step_monitor(nullptr);
  progress.end();

  const IntegratorStats stats = integ->stats();
  // The results, the summary and the CSV are each written as far as they can be.
  try {
    writer.finish(stats, status);
  } catch (const std::exception& e) {
    std::cerr << "evas run: FAILED: " << e.what() << "\n";
    if (code == 0) {
      status = std::string("failed: ") + e.what();
      code = 2;
    }
  }
  RunSummary sum;
  sum.scene = scene.name;
  sum.scene_path = scene.path;
  sum.integrator = set.name;
  sum.settings = set;
  sum.grid = scene.output.grid;
  sum.status = status;
  sum.t_start = scene.t_start;
  sum.t_end = scene.t_end;
  sum.t_reached = writer.rows_written() > 0 ? writer.last_time_written() : scene.t_start;
  sum.rows = writer.rows_written();
  sum.peak_memory_mb = process_peak_memory_mb();
  sum.stats = stats;
  sum.channels = writer.channels();
  sum.channel_summary = writer.summary();
  const std::string json = (dir / "summary.json").string();
  try {
    write_summary_json(json, sum);
  } catch (const std::exception& e) {
    std::cerr << "evas run: FAILED: " << e.what() << "\n";
    if (code == 0) code = 2;
  }
  std::string csv;
  if (vm.count("csv")) {
    csv = (dir / "results.csv").string();
    try {
      export_csv(h5path, csv);
    } catch (const std::exception& e) {
      std::cerr << "evas run: FAILED: " << e.what() << "\n";
      if (code == 0) code = 2;
    }
  }
  if (!quiet || code != 0) {
    std::cerr << "evas run: " << (code ? "failed, last output" : "completed")
              << " at t = " << sum.t_reached << " s: " << sum.rows << " output rows, "
              << stats.steps << " steps, " << stats.residual_evals << " residual and "
              << stats.jacobian_evals << " Jacobian evaluations, " << stats.wall_seconds
              << " s wall\n";
    std::cerr << "  results: " << h5path << "\n  summary: " << json << "\n";
    if (!csv.empty()) std::cerr << "  csv:     " << csv << "\n";
  }
  return code;
}

}  // namespace evas::cli
