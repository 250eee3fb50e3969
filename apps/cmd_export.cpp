// evas export RESULTS.h5 --csv FILE: results file to CSV.
#include <boost/program_options.hpp>
#include <iostream>

#include "apps/commands.h"
#include "elements/registry.h"
#include "io/results.h"

namespace evas::cli {

int cmd_export(const std::vector<std::string>& args) {
  po::options_description opts(
      "usage: evas export RESULTS.h5 --csv FILE\n\n"
      "Writes the results as CSV: a header time[s],<channel>[<unit>],... and one row per\n"
      "output time. Partial results of a failed run export as well.\n\n"
      "options");
  opts.add_options()("help,h", "show this help")("csv", po::value<std::string>(),
                                                 "CSV file to write");
  po::variables_map vm;
  if (parse_args(args, opts, {"results"}, vm)) return 0;
  if (!vm.count("results") || !vm.count("csv")) {
    std::cerr << "evas export: need RESULTS.h5 and --csv FILE\n" << opts << "\n";
    return 1;
  }
  const std::string in = vm["results"].as<std::string>(), out = vm["csv"].as<std::string>();
  export_csv(in, out);
  const ResultsData d = read_results(in);
  std::cout << "wrote " << out << ": " << d.time.size() << " rows, " << d.names.size()
            << " channels (status: " << d.status << ")\n";
  return 0;
}

int cmd_elements(const std::vector<std::string>& args) {
  po::options_description opts(
      "usage: evas elements\n\n"
      "Prints the reference of every force element type (parameters, units, defaults,\n"
      "ranges) as Markdown; the scene reader checks parameters against the same table.\n\n"
      "options");
  opts.add_options()("help,h", "show this help");
  po::variables_map vm;
  if (parse_args(args, opts, {}, vm)) return 0;
  std::cout << "# Force elements\n\n" << element_reference_markdown();
  return 0;
}

}  // namespace evas::cli
