// evas plot KIND RESULTS.h5 --out FIGURE.png|svg: the figures of a run's
// results (plot/figures.h).
#include <iostream>

#include "apps/commands.h"
#include "model/types.h"
#include "plot/figures.h"

namespace evas::cli {

int cmd_plot(const std::vector<std::string>& args) {
  PlotOptions o;
  std::string kinds;
  for (const auto& [k, what] : plot_kinds())
    kinds += "  " + k + std::string(k.size() < 15 ? 15 - k.size() : 1, ' ') + what + "\n";
  po::options_description opts(
      "usage: evas plot KIND RESULTS.h5 [--channel NAME]... [--element NAME] --out "
      "FIGURE.png|svg\n"
      "       evas plot waterfall|campbell|order-cuts SWEEP.h5 [--channel NAME]... "
      "[--order O]... --out FIGURE.png|svg\n\n"
      "Draws a figure of a run's results with gnuplot, PNG or SVG by the extension of\n"
      "--out, and leaves its gnuplot script and data beside it (FIGURE.gp, FIGURE.dat).\n"
      "Kinds:\n" +
      kinds + "\noptions");
  opts.add_options()("help,h", "show this help")(
      "channel", po::value<std::vector<std::string>>(&o.channels),
      "channel name or glob (channels, order-track: repeatable; order, spectrum: one; erp: "
      "the surface output's name)")("element", po::value<std::string>(&o.element),
                                    "journal bearing (polar, orbit, film)")(
      "out", po::value<std::string>(), "the figure: a file name ending in .png or .svg")(
      "cycles", po::value<int>(&o.cycles),
      "the last N whole cycles of a crank-angle grid (default 1, as evas spectrum and evas "
      "report; channels: 0, the whole record; 0: every whole cycle)")(
      "cycle", po::value<double>(&o.cycle)->default_value(720.0), "cycle length [deg]")(
      "x", po::value<std::string>(&o.x)->default_value("auto"),
      "channels, film: auto, time or crank-angle")(
      "max-order", po::value<double>(&o.max_order)->default_value(12.0), "order: highest order")(
      "window", po::value<std::string>(&o.spectrum.window)->default_value("hann"),
      "spectrum: rectangular, hann or flattop")("from", po::value<double>(&o.spectrum.t0),
                                                "spectrum: first time used [s]")(
      "to", po::value<double>(&o.spectrum.t1), "spectrum: last time used [s]")(
      "max-frequency", po::value<double>(&o.max_frequency), "spectrum: highest frequency [Hz]")(
      "order", po::value<std::vector<double>>(&o.orders),
      "order-cuts, order-track: an engine order to draw (repeatable; default 1, 2 and 4; "
      "order-track 1, 2, 4 and 6)")("title", po::value<std::string>(&o.title),
                                    "the figure's title (default: the kind's own)");
  po::variables_map vm;
  if (parse_args(args, opts, {"kind", "results"}, vm)) return 0;
  if (!vm.count("kind") || !vm.count("results") || !vm.count("out")) {
    std::cerr << "evas plot: need KIND, RESULTS.h5 and --out FIGURE.png|svg\n" << opts << "\n";
    return 1;
  }
  o.kind = vm["kind"].as<std::string>();
  if (!vm.count("cycles")) o.cycles = o.kind == "channels" ? 0 : 1;
  if (o.cycles < 0) throw InputError("--cycles must be >= 0");
  if (!(o.cycle > 0.0 && o.cycle <= 1e6)) throw InputError("--cycle must be > 0 and <= 1e6 deg");
  if (vm.count("max-frequency") && !(o.max_frequency > 0.0))
    throw InputError("--max-frequency must be > 0 Hz");
  for (const auto& f :
       plot_results(vm["results"].as<std::string>(), o, vm["out"].as<std::string>()))
    std::cout << f << "\n";
  return 0;
}

}  // namespace evas::cli
