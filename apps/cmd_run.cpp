// evas run SCENE: read the scene, integrate, record results as the run goes.
#include <boost/program_options.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "apps/commands.h"
#include "integrators/integrator.h"
#include "integrators/settings.h"
#include "io/scene.h"
#include "run/folder_run.h"
#include "run/step_advice.h"
#include "study/scene_edit.h"

namespace evas::cli {

namespace {

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
      ("integrator: " + builtin_integrator_list() + " or a loaded plug-in").c_str())(
      "rtol", po::value<std::string>(), "relative tolerance (adaptive integrators)")(
      "atol", po::value<std::string>(), "absolute tolerance (adaptive integrators)")(
      "step", po::value<std::string>(),
      ("fixed step [s] (" + builtin_integrator_list(true) + ")").c_str())(
      "set,s", po::value<std::vector<std::string>>()->composing(),
      "KEY=VALUE: any integrator setting, repeatable (see --help-settings); applied after "
      "the scene's integrator block and the options above")(
      "help-settings", "list every integrator setting with its default and meaning")(
      "param,p", po::value<std::vector<std::string>>()->composing(),
      "ITEM.KEY=VALUE: change a scene parameter before the run, repeatable, as in evas study "
      "(e.g. crank.lof.speed=418.879); the results file keeps the changed scene")(
      "t-end", po::value<double>(), "end time [s] (overrides the scene)")(
      "out", po::value<std::string>(), "output directory (default out/<scene name>)")(
      "overwrite",
      "replace the results of an earlier run in the output directory (without it such a "
      "directory is refused, exit 1)")("csv", "also write DIR/results.csv")(
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
  Scene scene = vm.count("param")
                    ? study::load_scene_source(vm["scene"].as<std::string>(),
                                               vm["param"].as<std::vector<std::string>>())
                          .parse()
                    : read_scene(vm["scene"].as<std::string>());
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
  if (!vm.count("out")) check_folder_name(scene);
  run::FolderOptions fo;
  fo.dir = vm.count("out") ? std::filesystem::path(vm["out"].as<std::string>())
                           : std::filesystem::path("out") / scene.name;
  fo.csv = vm.count("csv") > 0;
  fo.max_wall = max_wall;
  fo.quiet = quiet;
  fo.overwrite = vm.count("overwrite") > 0;
  for (const std::string& w : scene.warnings) std::cerr << "evas run: warning: " << w << "\n";
  if (const std::string w = coarse_step_warning(*scene.model, set); !w.empty())
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
  }
  return code;
}

}  // namespace evas::cli
