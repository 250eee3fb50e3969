// evas report RESULTS.h5 --out DIR: the page of an engine run's figures
// (plot/report_page.h).
#include <chrono>
#include <iostream>

#include "apps/commands.h"
#include "model/types.h"
#include "plot/report_page.h"

namespace evas::cli {

int cmd_report(const std::vector<std::string>& args) {
  ReportOptions o;
  po::options_description opts(
      "usage: evas report RESULTS.h5 --out DIR [--title T] [--cycles N] [--overwrite]\n\n"
      "Writes DIR/index.html, the page an NVH engineer opens first for a run of an\n"
      "engine scene on the crank-angle grid, and its figures (PNG, drawn by gnuplot as\n"
      "`evas plot` draws them, with their scripts and data) beside it: run summary and\n"
      "integrator statistics; for every journal bearing its polar load diagram, orbit,\n"
      "film thickness and peak pressure and a table of peaks; the bearing loads against\n"
      "crank angle, their order spectra and a table of the largest orders [kN]; friction\n"
      "power; crankshaft torsion (NAME.twist channels); the block's surface velocity\n"
      "(channels *.vn_rms, *.vn_mean, *.erp). The page uses no external resource and\n"
      "links only to files in DIR, so the folder can be moved.\n\noptions");
  opts.add_options()("help,h", "show this help")("out", po::value<std::string>(),
                                                 "the report's folder (created if missing)")(
      "title", po::value<std::string>(&o.title),
      "the page's title (default: Engine report: SCENE)")(
      "cycles", po::value<int>(&o.cycles),
      "the last N whole 720-deg cycles drawn and analysed (default 1, as evas spectrum and "
      "evas plot order; 0: the figures show the whole record, the spectra every whole "
      "cycle)")("overwrite",
                "replace the report in DIR (without it an existing DIR/index.html is "
                "refused, exit 1)");
  po::variables_map vm;
  if (parse_args(args, opts, {"results"}, vm)) return 0;
  if (!vm.count("results") || !vm.count("out")) {
    std::cerr << "evas report: need RESULTS.h5 and --out DIR\n" << opts << "\n";
    return 1;
  }
  if (vm.count("cycles") && o.cycles < 0) throw InputError("--cycles must be >= 0");
  o.overwrite = vm.count("overwrite") > 0;
  const auto t0 = std::chrono::steady_clock::now();
  const ReportResult r =
      write_report(vm["results"].as<std::string>(), vm["out"].as<std::string>(), o);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  for (const auto& n : r.notes) std::cerr << "evas report: note: " << n << "\n";
  std::cout << r.index.string() << "\n";
  std::cerr << "evas report: " << r.figures << " figures over " << r.cycles << " cycles, " << s
            << " s\n";
  return 0;
}

}  // namespace evas::cli
