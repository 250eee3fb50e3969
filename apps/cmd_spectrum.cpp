// evas spectrum RESULTS.h5 --channel NAME: order spectrum of a channel of a run
// on the crank-angle grid (post/order_spectrum.h).
#include <fstream>
#include <iomanip>
#include <iostream>

#include "apps/commands.h"
#include "io/results.h"
#include "model/types.h"
#include "post/order_spectrum.h"

namespace evas::cli {

int cmd_spectrum(const std::vector<std::string>& args) {
  int cycles = 0;
  double cycle = 720.0, max_order = 12.0;
  po::options_description opts(
      "usage: evas spectrum RESULTS.h5 --channel NAME [--cycles N] [--csv FILE]\n\n"
      "Order spectrum of one output channel over whole engine cycles taken from the end\n"
      "of the record: by default every whole cycle, the start-up transient included; give\n"
      "--cycles N for the last N only. The run must use the crank-angle output grid\n"
      "(its results carry the channel crank_angle). Orders are harmonics of the crank\n"
      "rotation in steps of 360/cycle (0.5 for a four-stroke cycle).\n\n"
      "options");
  opts.add_options()("help,h", "show this help")("channel", po::value<std::string>(),
                                                 "channel name, e.g. main1.fy")(
      "cycles", po::value<int>(&cycles),
      "cycles analysed, >= 1 (default: every whole cycle of the record)")(
      "cycle", po::value<double>(&cycle)->default_value(720.0), "cycle length [deg]")(
      "max-order", po::value<double>(&max_order)->default_value(12.0), "highest order listed")(
      "csv", po::value<std::string>(), "write order,amplitude,phase to this file");
  po::variables_map vm;
  if (parse_args(args, opts, {"results"}, vm)) return 0;
  if (!vm.count("results") || !vm.count("channel")) {
    std::cerr << "evas spectrum: need RESULTS.h5 and --channel NAME\n" << opts << "\n";
    return 1;
  }
  if (vm.count("cycles") && cycles < 1)
    throw InputError("--cycles " + std::to_string(cycles) +
                     ": give a number of cycles >= 1 (leave it out for every whole cycle)");
  if (!(cycle > 0.0 && cycle <= 1e6))
    throw InputError("--cycle must be > 0 and <= 1e6 deg (720 for a four-stroke engine)");
  if (!(max_order >= 0.0 && max_order <= 1e6))
    throw InputError("--max-order must be >= 0 and <= 1e6");
  const std::string path = vm["results"].as<std::string>();
  const std::string name = vm["channel"].as<std::string>();
  const ResultsData d = read_results(path);
  int ia = -1, ic = -1;
  for (std::size_t i = 0; i < d.names.size(); ++i) {
    if (d.names[i] == "crank_angle") ia = static_cast<int>(i);
    if (d.names[i] == name) ic = static_cast<int>(i);
  }
  if (ia < 0)
    throw InputError(path +
                     ": no crank_angle channel (run the scene with output grid crank-angle)");
  if (ic < 0) throw InputError(path + ": no channel '" + name + "'");
  std::vector<double> th(d.values.rows()), y(d.values.rows());
  for (Eigen::Index r = 0; r < d.values.rows(); ++r) {
    th[r] = d.values(r, ia);
    y[r] = d.values(r, ic);
  }
  const OrderSpectrum s = order_spectrum(th, y, cycles, cycle, max_order);
  std::cout << "order spectrum of " << name << " [" << d.units[ic] << "], " << s.cycles
            << " cycles of " << cycle << " deg\n  order     amplitude     phase [rad]\n";
  for (std::size_t k = 0; k < s.order.size(); ++k)
    std::cout << std::setw(7) << s.order[k] << std::setw(14) << std::setprecision(6)
              << s.amplitude[k] << std::setw(14) << s.phase[k] << "\n";
  if (vm.count("csv")) {
    std::ofstream f(vm["csv"].as<std::string>());
    if (!f) throw InputError(vm["csv"].as<std::string>() + ": cannot write");
    f << "order,amplitude[" << d.units[ic] << "],phase[rad]\n" << std::setprecision(12);
    for (std::size_t k = 0; k < s.order.size(); ++k)
      f << s.order[k] << "," << s.amplitude[k] << "," << s.phase[k] << "\n";
  }
  return 0;
}

}  // namespace evas::cli
