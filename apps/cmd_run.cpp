// evas run SCENE: read the scene, integrate, record results as the run goes.
#include <boost/program_options.hpp>
#include <cmath>
#include <iostream>

#include "apps/commands.h"
#include "apps/scene_options.h"
#include "integrators/integrator.h"
#include "integrators/settings.h"
#include "run/folder_run.h"
#include "run/period.h"
#include "run/stability_note.h"
#include "run/step_advice.h"

namespace evas::cli {

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
  opts.add_options()("help,h", "show this help");
  add_scene_run_options(opts);
  opts.add_options()("t-end", po::value<double>(), "end time [s] (overrides the scene)")(
      "period", po::value<std::string>(),
      "the period whose last two cycles are compared, with its unit (720deg, 0.04s); default: "
      "the scene's own (720 deg of the crank with pistons, 360 without)")(
      "settle-tol", po::value<double>(),
      "a run whose last two cycles differ by more than this (per channel, relative) is warned "
      "of as not settled; summary.json, settledness (default 1e-3)")(
      "until-settled", po::value<double>(),
      "TOL: run whole cycles until the last two differ by at most TOL (then stop, completed), "
      "at most --max-cycles of them; replaces --t-end")(
      "max-cycles", po::value<int>(), "with --until-settled: the most cycles run (default 100)");
  po::variables_map vm;
  if (const int code = parse_scene_command("run", args, opts, vm); code >= 0) return code;
  const bool quiet = vm.count("quiet") > 0;
  Scene scene = scene_from_options("run", vm);
  IntegratorSettings& set = scene.integrator;
  if (vm.count("t-end")) {
    scene.t_end = vm["t-end"].as<double>();
    if (!std::isfinite(scene.t_end))
      throw InputError("--t-end: " + std::to_string(scene.t_end) + " is not a finite time");
    if (!(scene.t_end > scene.t_start))
      throw InputError("--t-end must be after the start time " + std::to_string(scene.t_start));
  }
  if (vm.count("settle-tol")) {
    const double tol = vm["settle-tol"].as<double>();
    if (!(tol > 0.0) || !std::isfinite(tol))
      throw InputError("--settle-tol must be a positive number (a relative difference)");
  }
  double until = 0.0;
  if (vm.count("until-settled")) {
    until = vm["until-settled"].as<double>();
    if (!(until > 0.0) || !std::isfinite(until))
      throw InputError("--until-settled must be a positive number (a relative difference)");
    if (vm.count("t-end"))
      throw InputError(
          "--until-settled runs until the run settles: give --max-cycles, not --t-end");
    const int cycles = vm.count("max-cycles") ? vm["max-cycles"].as<int>() : 100;
    if (cycles < 2) throw InputError("--max-cycles must be at least 2 (two cycles to compare)");
    const run::ScenePeriod per =
        run::scene_period(scene, vm.count("period") ? vm["period"].as<std::string>() : "");
    scene.t_end = scene.t_start + cycles * per.seconds;
  } else if (vm.count("max-cycles")) {
    throw InputError("--max-cycles goes with --until-settled");
  }
  run::FolderOptions fo = folder_from_options("run", vm, scene);
  if (vm.count("period")) fo.period = vm["period"].as<std::string>();
  if (vm.count("settle-tol")) fo.settle_tol = vm["settle-tol"].as<double>();
  fo.until_settled = until;
  for (const std::string& w : scene.warnings) std::cerr << "evas run: warning: " << w << "\n";
  if (const std::string w = coarse_step_warning(*scene.model, set); !w.empty())
    std::cerr << "evas run: warning: " << w << "\n";
  if (const std::string w = stability_limit_warning(*scene.model, set, scene.t_start); !w.empty())
    std::cerr << "evas run: warning: " << w << "\n";
  if (const std::string w = step_count_warning(set, scene.t_start, scene.t_end); !w.empty())
    std::cerr << "evas run: warning: " << w << "\n";
  const run::FolderResult r = run::run_into_folder(scene, scene.t_end, set, fo);
  const IntegratorStats& stats = r.outcome.stats;
  const int code = r.outcome.exit_code;
  if (!quiet || code != 0) {
    std::cerr << "evas run: " << (code ? "failed, last output" : "completed")
              << " at t = " << r.t_reached << " s: " << r.rows << " output rows, " << stats.steps
              << " steps, " << stats.residual_evals << " residual and " << stats.jacobian_evals
              << " Jacobian evaluations, " << stats.wall_seconds << " s wall\n";
    std::cerr << "  results: " << r.results << "\n  summary: " << r.summary << "\n";
    if (!r.csv.empty()) std::cerr << "  csv:     " << r.csv << "\n";
    if (r.settledness.measured)
      std::cerr << "  settled: " << (r.settledness.settled() ? "yes" : "no")
                << ", the last two cycles differ by " << r.settledness.max_difference << " ("
                << r.settledness.worst_channel << ")\n";
  }
  return code;
}

}  // namespace evas::cli
