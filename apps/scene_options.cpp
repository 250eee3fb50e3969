// The options evas run and evas periodic share (scene_options.h).
#include "apps/scene_options.h"

#include <cmath>
#include <cstdio>
#include <iostream>

#include "integrators/integrator.h"
#include "integrators/settings.h"
#include "io/initial_state.h"
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

int parse_scene_command(const std::string& command, const std::vector<std::string>& args,
                        const po::options_description& opts, po::variables_map& vm) {
  if (parse_args(args, opts, {"scene"}, vm)) return 0;
  if (vm.count("help-settings")) {
    std::cout << settings_reference();
    return 0;
  }
  if (!vm.count("scene")) {
    std::cerr << "evas " << command << ": missing SCENE file\n" << opts << "\n";
    return 1;
  }
  return -1;
}

void add_scene_run_options(po::options_description& opts) {
  opts.add_options()("integrator", po::value<std::string>(),
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
      "out", po::value<std::string>(), "output directory (default out/<scene name>)")(
      "overwrite",
      "replace the results of an earlier run in the output directory (without it such a "
      "directory is refused, exit 1)")("csv", "also write DIR/results.csv")(
      "max-wall", po::value<double>(),
      "wall-time limit [s]: the run stops with status 'failed: wall-time limit ...' "
      "(exit 2, rows kept) when it runs longer")("quiet,q", "no progress line")(
      "initial", po::value<std::string>(),
      "FILE: start from the bodies' states in FILE (the state.yaml evas periodic writes: a "
      "run-up from the steady cycle at its first speed) in place of the scene's initial state");
}

Scene scene_from_options(const std::string& command, const po::variables_map& vm) {
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
  warn_unread_settings(command, vm, set);
  if (vm.count("initial")) apply_initial_state(*scene.model, vm["initial"].as<std::string>());
  return scene;
}

run::FolderOptions folder_from_options(const std::string& command, const po::variables_map& vm,
                                       const Scene& scene) {
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
  fo.quiet = vm.count("quiet") > 0;
  fo.overwrite = vm.count("overwrite") > 0;
  fo.log_prefix = "evas " + command;
  return fo;
}

}  // namespace evas::cli
