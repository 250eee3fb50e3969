// `evas periodic` into an output folder (periodic_folder.h).
#include "run/periodic_folder.h"

#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>

#include "io/initial_state.h"
#include "io/results.h"
#include "io/text_escape.h"
#include "run/stop.h"

namespace evas::run {

namespace {

// Stops the search on a signal or the wall-time limit.
class StopWatch : public CycleObserver {
 public:
  explicit StopWatch(const Stop& stop) : stop_(stop) {}
  void state(double t, const Vec&, const Vec&) override {
    if (stop_.due()) stop_.stop(t, 0.0);
  }
  void between_steps(double t, double h) override {
    if (stop_.due()) stop_.stop(t, h);
  }

 private:
  const Stop& stop_;
};

// The channel rows of the converged cycle, from its sampled states (the
// channels of the cycles before it are never evaluated).
void write_rows(const PeriodicResult& p, OutputSet& out, const System& sys, ResultsWriter& w) {
  std::vector<double> row(static_cast<std::size_t>(out.size()));
  for (std::size_t k = 0; k < p.sample_t.size(); ++k) {
    const double t = p.sample_t[k];
    const Vec &q = p.sample_q[k], &v = p.sample_v[k];
    out.values(t, q.data(), v.data(), row.data());
    for (std::size_t c = 0; c < row.size(); ++c)
      if (!std::isfinite(row[c]))
        throw RunError("channel '" + out.channels()[c].name + "' is not finite at " +
                       sys.describe_state(t, q.data(), v.data()));
    w.append(t, row.data());
  }
}

}  // namespace

std::string periodic_json(const PeriodicResult& r, const ScenePeriod& per,
                          const PeriodicOptions& opt, const std::string& indent) {
  std::ostringstream o;
  const std::string in = indent + "  ", in2 = in + "  ";
  o << "{\n";
  o << in << "\"method\": " << json_string(to_text(opt.method)) << ",\n";
  o << in << "\"converged\": " << (r.converged ? "true" : "false") << ",\n";
  if (!r.converged) o << in << "\"reason\": " << json_string(r.message) << ",\n";
  o << in << "\"period_s\": " << json_number(per.seconds) << ",\n";
  o << in << "\"period_deg\": " << json_number(per.degrees) << ",\n";
  o << in << "\"period_basis\": " << json_string(per.basis) << ",\n";
  o << in << "\"tolerance\": " << json_number(opt.tol) << ",\n";
  o << in << "\"defect_measure\": "
    << json_string(
           "max over the state (q, v) of |G(x)_i - x_i| / s_i, s_i the coordinate's "
           "largest |value| over the cycle, at least 1e-4 of the largest of its kind")
    << ",\n";
  o << in << "\"cycle_integrations\": " << r.cycles << ",\n";
  if (opt.method == PeriodicMethod::projected)
    o << in << "\"slow_dimension\": " << r.slow_dimension << ",\n";
  o << in << "\"wall_seconds\": " << json_number(r.wall) << ",\n";
  o << in << "\"iterations\": [";
  for (std::size_t k = 0; k < r.iterations.size(); ++k) {
    const PeriodicIteration& it = r.iterations[k];
    o << (k ? ",\n" : "\n") << in2 << "{\"cycles\": " << it.cycles
      << ", \"step\": " << json_string(it.step) << ", \"defect\": " << json_number(it.defect)
      << ", \"worst\": " << json_string(it.worst) << ", \"wall_seconds\": " << json_number(it.wall)
      << "}";
  }
  o << "\n" << in << "],\n";
  o << in << "\"floquet_source\": " << json_string(r.multiplier_source) << ",\n";
  o << in << "\"floquet_multipliers\": [";
  for (std::size_t k = 0; k < r.multipliers.size(); ++k) {
    const FloquetMultiplier& f = r.multipliers[k];
    o << (k ? ",\n" : "\n") << in2 << "{\"re\": " << json_number(f.mu.real())
      << ", \"im\": " << json_number(f.mu.imag())
      << ", \"modulus\": " << json_number(std::abs(f.mu)) << ", \"lives_in\": [";
    for (std::size_t j = 0; j < f.lives_in.size(); ++j)
      o << (j ? ", " : "") << json_string(f.lives_in[j]);
    o << "]}";
  }
  o << (r.multipliers.empty() ? "]" : "\n" + in + "]");
  o << ",\n" << in << "\"stable\": ";
  if (r.multipliers.empty())
    o << "null";
  else
    o << (std::abs(r.multipliers.front().mu) < 1.0 ? "true" : "false");
  o << "\n" << indent << "}";
  return o.str();
}

PeriodicFolderResult periodic_into_folder(const Scene& scene, const IntegratorSettings& settings,
                                          const PeriodicOptions& popt, const std::string& period,
                                          const FolderOptions& opt) {
  PeriodicFolderResult r;
  r.period = scene_period(scene, period);
  const double t0 = scene.t_start, T = r.period.seconds;
  make_integrator(settings.name);  // an unknown name is refused before the folder is touched
  SceneRun run(scene, t0 + T);
  std::vector<double> samples;
  for (double t : run.outputs().times())
    if (t < t0 + T * (1.0 - 1e-9)) samples.push_back(t);
  const std::unique_ptr<RunLock> lock = open_run_folder(opt);
  const Stop stop(opt.max_wall);
  System& sys = run.system();
  StopWatch watch(stop);
  Vec q0, v0;
  sys.initial_state(q0, v0);
  if (!opt.quiet)
    std::cerr << opt.log_prefix << ": scene '" << scene.name << "', " << sys.size()
              << " modal coordinates, integrator " << settings.name << ", method "
              << to_text(popt.method) << ", period " << format_number(T) << " s (" << r.period.basis
              << ")\n";
  std::string failure;
  try {
    r.periodic = find_periodic(sys, t0, T, q0, v0, settings, popt, samples, &watch);
    if (!r.periodic.converged) {
      failure = r.periodic.message;
      r.exit_code = 2;
    }
  } catch (const InputError&) {
    throw;
  } catch (const Stopped& e) {
    failure = e.what();
    r.exit_code = e.exit_code();
  } catch (const std::exception& e) {
    failure = e.what();
    r.exit_code = 2;
  }
  r.status = failure.empty() ? "completed" : "failed: " + failure;
  if (!opt.quiet || r.exit_code)
    for (const PeriodicIteration& it : r.periodic.iterations)
      std::cerr << opt.log_prefix << ": cycle " << it.cycles << " (" << it.step << "): defect "
                << format_number(it.defect) << " in " << it.worst << "\n";

  RunSummary sum = summary_of(scene, settings);
  sum.t_end = t0 + T;
  sum.stats = r.periodic.stats;
  if (r.exit_code == 0) {
    // the converged cycle: the rows of the cycle integrated last
    r.results = (opt.dir / "results.h5").string();
    try {
      ResultsWriter::Options wopt;
      wopt.scene_text = scene.text;
      wopt.integrator = settings.name;
      wopt.grid = scene.output.grid;
      ResultsWriter w(r.results, run.outputs().channels(), wopt);
      write_rows(r.periodic, run.outputs(), sys, w);
      w.finish(r.periodic.stats, "completed");
      r.rows = w.rows_written();
      sum.channels = w.channels();
      sum.channel_summary = w.summary();
      sum.t_reached = w.last_time_written();
    } catch (const std::exception& e) {
      r.exit_code = 2;
      r.status = std::string("failed: ") + e.what();
      std::cerr << opt.log_prefix << ": FAILED: " << e.what() << "\n";
    }
  } else {
    std::cerr << opt.log_prefix << ": FAILED: " << failure
              << " (no results file written; the iterations are in summary.json)\n";
  }
  sum.status = r.status;
  sum.rows = r.rows;
  sum.extra.emplace_back("periodic", periodic_json(r.periodic, r.period, popt, "  "));
  r.summary = (opt.dir / "summary.json").string();
  try {
    write_summary_json(r.summary, sum);
  } catch (const std::exception& e) {
    std::cerr << opt.log_prefix << ": FAILED: " << e.what() << "\n";
    if (r.exit_code == 0) r.exit_code = 2;
  }
  if (r.exit_code == 0) {
    // the periodic state, for `--initial FILE` (a run-up from it, a neighbour's start)
    r.state = (opt.dir / "state.yaml").string();
    try {
      std::ofstream f(r.state);
      f << initial_state_text(
          *scene.model, r.periodic.q, r.periodic.v, scene.name, t0,
          "The periodic state of scene '" + scene.name + "' at t = " + format_number(t0) +
              " s (evas periodic, " + to_text(popt.method) + ", defect " +
              format_number(r.periodic.iterations.back().defect) +
              "): each body's modal coordinates q and velocities v.\nStart a run from it with "
              "`evas run SCENE --initial THIS_FILE`.");
      if (!f) throw RunError(r.state + ": cannot be written");
    } catch (const std::exception& e) {
      std::cerr << opt.log_prefix << ": FAILED: " << e.what() << "\n";
      r.exit_code = 2;
      r.state.clear();
    }
  }
  if (opt.csv && !r.results.empty() && r.exit_code == 0) {
    r.csv = (opt.dir / "results.csv").string();
    try {
      export_csv(r.results, r.csv);
    } catch (const std::exception& e) {
      std::cerr << opt.log_prefix << ": FAILED: " << e.what() << "\n";
      r.exit_code = 2;
    }
  }
  return r;
}

}  // namespace evas::run
