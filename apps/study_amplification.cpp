// `evas study amplification` (apps/study_amplification.h).
#include "apps/study_amplification.h"

#include <cmath>
#include <fstream>
#include <iostream>

#include "apps/commands.h"
#include "study/amplification.h"

namespace evas::cli {

int study_amplification(const std::vector<std::string>& args) {
  po::options_description opts(
      "usage: evas study amplification --case SPEC [--case SPEC]... [--h-over-t LIST]\n"
      "                                [--damping ZETA] [--out DIR]\n\n"
      "The one-step amplification of each integrator setting, measured from the integrator\n"
      "itself: it runs the linear oscillator q'' + 2 zeta omega q' + omega^2 q = 0 (T = 1 s)\n"
      "with a fixed step h from the unit states (1, 0) and (0, 1) for 10 steps, fits the\n"
      "recurrence the displacements obey and takes its roots: the spectral radius rho, the\n"
      "algorithmic damping ratio and the relative period error (T_bar - T)/T against h/T\n"
      "(Hilber, Hughes & Taylor 1977; Chung & Hulbert 1993). Built-ins and plug-ins alike;\n"
      "ida and cvode (their own step and order) are refused with that reason. The Newmark\n"
      "family iterates by Newton unless the case names an iteration.\n"
      "Writes DIR/case<k>/amplification.csv (h_over_T, spectral_radius, damping_ratio,\n"
      "period_error, order, note), DIR/amplification.md and DIR/amplification.png.\n\n"
      "Example: evas study amplification --case \"generalized-alpha rho_inf=0,0.5,1\" \\\n"
      "  --case linear-acceleration --h-over-t 1e-3..1e3/61\n\noptions");
  opts.add_options()("help,h", "show this help")(
      "case,c", po::value<std::vector<std::string>>()->composing(),
      "case spec \"NAME KEY=V1,V2 ...\" (an integrator and its settings), repeatable")(
      "h-over-t", po::value<std::string>()->default_value("1e-3..1e3/61"),
      "step over period: values (0.1,1) or a log range A..B/N")(
      "damping", po::value<double>()->default_value(0.0), "the oscillator's damping ratio zeta")(
      "region", po::value<double>(),
      "also the stability region: |R(z)| over Re z in [-E, E], Im z in [-E, E] (E this value), "
      "into case<k>/region.csv and region.png")(
      "region-points", po::value<int>()->default_value(60), "Re z values - 1 of the region grid")(
      "out", po::value<std::string>(), "output directory (default out/study-amplification)")(
      "no-plot", "do not run gnuplot (the .gp script is still written)");
  po::variables_map vm;
  if (parse_args(args, opts, {}, vm)) return 0;
  study::AmplificationOptions o;
  o.h_over_T = study::parse_h_over_t(vm["h-over-t"].as<std::string>());
  o.damping_ratio = vm["damping"].as<double>();
  if (vm.count("region")) {
    o.region = vm["region"].as<double>();
    if (!(o.region > 0.0 && std::isfinite(o.region)))
      throw InputError("--region must be a number > 0 (the half width of the z plane shown)");
  }
  o.region_points = vm["region-points"].as<int>();
  if (o.region_points < 4 || o.region_points > 1000)
    throw InputError("--region-points must be in [4, 1000]");
  if (vm.count("out")) o.out_dir = vm["out"].as<std::string>();
  o.plot = !vm.count("no-plot");
  const std::vector<std::string> specs =
      vm.count("case") ? vm["case"].as<std::vector<std::string>>() : std::vector<std::string>{};
  const auto cases = study::amplification_study(specs, o);
  const std::string dir = o.out_dir.empty() ? "out/study-amplification" : o.out_dir;
  std::ifstream md(dir + "/amplification.md");
  std::cout << md.rdbuf();
  int refused = 0;
  for (const auto& c : cases) refused += !c.refused.empty();
  return refused == static_cast<int>(cases.size()) ? 1 : 0;
}

}  // namespace evas::cli
