#include <iostream>

#include "apps/commands.h"

namespace evas::cli {

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

}  // namespace evas::cli
