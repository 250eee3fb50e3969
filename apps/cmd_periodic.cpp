// evas periodic SCENE: the periodic cycle of a scene whose forcing repeats
// (run/periodic_folder.h, docs/periodic.md).
#include <cmath>
#include <iostream>

#include "apps/commands.h"
#include "apps/scene_options.h"
#include "integrators/settings.h"
#include "run/periodic_folder.h"

namespace evas::cli {

int cmd_periodic(const std::vector<std::string>& args) {
  po::options_description opts(
      "usage: evas periodic SCENE.yaml [options]\n\n"
      "The periodic solution of a scene whose forcing repeats (the engine cycle: 720 deg of\n"
      "the crank with four-stroke pistons, 360 deg of a spinning body without): the state\n"
      "at the scene's start that one period of the integrator returns. Writes one cycle in\n"
      "DIR/results.h5 (the scene's channels and grid, crank angle 0 .. 719 deg at 1 deg) and\n"
      "the method, its iterations, the cycles integrated and the Floquet multipliers in\n"
      "DIR/summary.json (docs/periodic.md).\n"
      "Exit codes: 0 converged; 1 bad input (a scene with no period, a period that is not a\n"
      "whole multiple of the forcing's; nothing written); 2 not converged within --max-cycles\n"
      "(no results file; the defect history in summary.json) or an integration failed;\n"
      "128+N stopped by signal N.\n\n"
      "options");
  opts.add_options()("help,h", "show this help");
  add_scene_run_options(opts);
  opts.add_options()(
      "period", po::value<std::string>(),
      "the period with its unit (720deg, 0.04s); default: the scene's own, and a given one must "
      "be a whole multiple of it")(
      "method", po::value<std::string>()->default_value("projected"),
      "projected (Newton on the slow multipliers' subspace, fixed point on the rest), newton "
      "(shooting, monodromy by differences: 2n cycles per iteration), anderson, fixed-point")(
      "tol", po::value<double>()->default_value(3e-4, "3e-4"),
      "periodicity defect at which the cycle is accepted (max over the state of |G(x) - x| / "
      "the coordinate's amplitude)")("max-cycles", po::value<int>()->default_value(40),
                                     "cycle integrations at most")(
      "slow", po::value<double>()->default_value(0.02, "0.02"),
      "projected: multipliers of modulus >= this are solved by Newton")(
      "depth", po::value<int>()->default_value(5), "anderson: earlier iterates mixed")(
      "coarse", po::value<double>()->default_value(10.0, "10"),
      "the first cycles at rtol and atol times this, until the defect is below 30 x --tol (1: "
      "none); the cycle accepted is at the integrator's own tolerances")(
      "no-secant", "projected: keep the first Jacobian (no Broyden updates)")(
      "floquet", po::value<std::string>()->default_value("estimate"),
      "estimate: the Floquet multipliers the method has at hand (newton's monodromy; the "
      "projected Jacobian and the linearization); differences: the monodromy matrix by "
      "differences at the periodic state (2n more cycles)")(
      "linearization", po::value<std::string>()->default_value("stepped"),
      "projected: the slow subspace from the linearized equations stepped over the first cycle "
      "(stepped) or from K and C averaged over it (averaged)")(
      "steps", po::value<int>()->default_value(180),
      "projected, stepped: implicit Euler steps of the linearized equations over the cycle (at "
      "most one per output time)")(
      "difference-jacobian",
      "projected: the slow subspace's Jacobian by differences of the cycle map along its p "
      "directions (p more cycles), not from the linearization");
  po::variables_map vm;
  if (const int code = parse_scene_command("periodic", args, opts, vm); code >= 0) return code;
  run::PeriodicOptions popt;
  popt.method = run::periodic_method(vm["method"].as<std::string>());
  popt.tol = vm["tol"].as<double>();
  if (!(popt.tol > 0.0) || !std::isfinite(popt.tol))
    throw InputError("--tol must be a positive number");
  popt.max_cycles = vm["max-cycles"].as<int>();
  if (popt.max_cycles < 2) throw InputError("--max-cycles must be at least 2");
  popt.slow = vm["slow"].as<double>();
  if (!(popt.slow > 0.0 && popt.slow < 1.0))
    throw InputError("--slow must be between 0 and 1 (a multiplier's modulus)");
  popt.coarse = vm["coarse"].as<double>();
  if (!(popt.coarse >= 1.0) || !std::isfinite(popt.coarse))
    throw InputError("--coarse must be 1 or more (a factor on rtol and atol)");
  popt.depth = vm["depth"].as<int>();
  if (popt.depth < 1) throw InputError("--depth must be at least 1");
  popt.secant = vm.count("no-secant") == 0;
  popt.difference_jacobian = vm.count("difference-jacobian") > 0;
  const std::string floquet = vm["floquet"].as<std::string>();
  if (floquet != "estimate" && floquet != "differences")
    throw InputError("--floquet: '" + floquet + "' is neither estimate nor differences");
  popt.difference_floquet = floquet == "differences";
  popt.linearization = vm["linearization"].as<std::string>();
  if (popt.linearization != "stepped" && popt.linearization != "averaged")
    throw InputError("--linearization: '" + popt.linearization +
                     "' is neither stepped nor averaged");
  popt.steps = vm["steps"].as<int>();
  if (popt.steps < 1) throw InputError("--steps must be at least 1");
  Scene scene = scene_from_options("periodic", vm);
  const run::FolderOptions fo = folder_from_options("periodic", vm, scene);
  for (const std::string& w : scene.warnings) std::cerr << "evas periodic: warning: " << w << "\n";
  const run::PeriodicFolderResult r = run::periodic_into_folder(
      scene, scene.integrator, popt, vm.count("period") ? vm["period"].as<std::string>() : "", fo);
  if (!fo.quiet || r.exit_code != 0) {
    const run::PeriodicResult& p = r.periodic;
    std::cerr << "evas periodic: " << (r.exit_code ? "failed" : "converged") << " after "
              << p.cycles << " cycle integrations, " << p.stats.steps << " steps, " << p.wall
              << " s wall";
    if (!p.iterations.empty()) std::cerr << "; periodicity defect " << p.iterations.back().defect;
    if (!p.multipliers.empty())
      std::cerr << "; largest Floquet multiplier |mu| = " << std::abs(p.multipliers.front().mu);
    std::cerr << "\n";
    if (!r.results.empty()) std::cerr << "  results: " << r.results << "\n";
    std::cerr << "  summary: " << r.summary << "\n";
    if (!r.csv.empty()) std::cerr << "  csv:     " << r.csv << "\n";
    if (!r.state.empty()) std::cerr << "  state:   " << r.state << " (evas run --initial)\n";
  }
  return r.exit_code;
}

}  // namespace evas::cli
