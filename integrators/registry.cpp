// make_integrator / integrator_names: the integrators by name (integrator.h).
#include <string>
#include <utility>
#include <vector>

#include "integrators/common.h"

namespace evas {

namespace {

using Factory = std::unique_ptr<Integrator> (*)();

const std::vector<std::pair<std::string, Factory>>& registry() {
  static const std::vector<std::pair<std::string, Factory>> table = {
      {"ida", &make_ida_integrator},
      {"cvode", &make_cvode_integrator},
      {"generalized-alpha", &make_generalized_alpha_integrator},
      {"linear-acceleration", &make_linear_acceleration_integrator},
  };
  return table;
}

}  // namespace

std::vector<std::string> integrator_names() {
  std::vector<std::string> names;
  for (const auto& entry : registry()) names.push_back(entry.first);
  return names;
}

std::unique_ptr<Integrator> make_integrator(const std::string& name) {
  for (const auto& entry : registry())
    if (entry.first == name) return entry.second();
  std::string known;
  for (const auto& entry : registry()) known += (known.empty() ? "" : ", ") + entry.first;
  throw InputError("integrator '" + name + "' is unknown (known: " + known + ")");
}

}  // namespace evas
