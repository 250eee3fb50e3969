#include <iostream>

#include "apps/commands.h"
#include "integrators/settings.h"

namespace evas::cli {

int parse_elastic_option(const std::string& value) {
  if (value == "all") return 0;
  std::size_t used = 0;
  long n = -1;
  try {
    n = std::stol(value, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != value.size() || used == 0 || n < 0)
    throw InputError("--elastic '" + value + "': give 'all' or a number of elastic modes >= 1");
  if (n == 0)
    throw InputError(
        "--elastic 0: give --elastic all to keep every elastic mode, or N >= 1 for the lowest "
        "N; a body without elastic modes is made in the scene (modes: {elastic: 0} keeps none)");
  if (n > 1000000) throw InputError("--elastic " + value + ": more modes than any body has");
  return static_cast<int>(n);
}

bool parse_args(const std::vector<std::string>& args, const po::options_description& opts,
                const std::vector<std::string>& positional, po::variables_map& vm) {
  po::options_description hidden;
  po::positional_options_description pos;
  for (const auto& name : positional) {
    hidden.add_options()(name.c_str(), po::value<std::string>(), name.c_str());
    pos.add(name.c_str(), 1);
  }
  po::options_description all;
  all.add(opts).add(hidden);
  po::store(po::command_line_parser(std::vector<std::string>(args.begin() + 1, args.end()))
                .options(all)
                .positional(pos)
                .run(),
            vm);
  po::notify(vm);
  if (vm.count("help")) {
    std::cout << opts << "\n";
    return true;
  }
  return false;
}

void warn_unread_settings(const std::string& command, const po::variables_map& vm,
                          const IntegratorSettings& s) {
  std::vector<std::pair<std::string, std::string>> given;  // {option, key}
  for (const char* key : {"rtol", "atol", "step"})
    if (vm.count(key) && !vm[key].defaulted()) given.emplace_back(std::string("--") + key, key);
  if (vm.count("set"))
    for (const auto& a : vm["set"].as<std::vector<std::string>>())
      given.emplace_back("--set " + a, a.substr(0, a.find('=')));
  for (const auto& [option, key] : given)
    if (const std::string why = setting_unread_reason(s, key); !why.empty())
      std::cerr << "evas " << command << ": warning: " << option << ": " << why
                << "; it has no effect on this run\n";
}

}  // namespace evas::cli
