// make_integrator / integrator_names / register_integrator: the integrators by
// name (integrator.h). The built-in ones are registered first; plug-ins
// (integrators/plugin.h) add theirs at load time.
#include <algorithm>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "integrators/common.h"
#include "integrators/settings.h"

namespace evas {

namespace {

using Entry = IntegratorEntry;

// One line per built-in integrator; each declares itself in its own file.
const std::vector<Entry>& builtin_entries() {
  static const std::vector<Entry> table = {
      ida_entry(),    cvode_entry(),     generalized_alpha_entry(), linear_acceleration_entry(),
      radau_entry(),  hht_alpha_entry(), newmark_entry(),           central_difference_entry(),
      arkode_entry(), bathe_entry(),
  };
  return table;
}

// the built-in ones first, then the plug-ins'
std::vector<Entry>& registry() {
  static std::vector<Entry> table = builtin_entries();
  return table;
}

std::mutex& registry_mutex() {
  static std::mutex m;
  return m;
}

bool valid_name(const std::string& name) {
  if (name.empty() || name.size() > 64) return false;
  for (char c : name)
    if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' || c == '_' || c == '.'))
      return false;
  return true;
}

bool valid_key(const std::string& key) {
  if (key.empty() || key.size() > 32) return false;
  for (char c : key)
    if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_')) return false;
  return true;
}

void check_declared(const std::string& name, const IntegratorCapabilities& caps) {
  const std::string who = "register_integrator: '" + name + "': setting '";
  for (std::size_t i = 0; i < caps.settings.size(); ++i) {
    const DeclaredSetting& d = caps.settings[i];
    if (!valid_key(d.key))
      throw InputError(who + d.key + "' is not a valid key (1 to 32 of a-z, 0-9, '_')");
    if (is_builtin_setting(d.key))
      throw InputError(who + d.key + "' is a built-in setting (declare a key of its own)");
    for (std::size_t j = 0; j < i; ++j)
      if (caps.settings[j].key == d.key) throw InputError(who + d.key + "' is declared twice");
    if (!(d.min <= d.default_value && d.default_value <= d.max))
      throw InputError(who + d.key + "': its default is outside [min, max]");
  }
}

}  // namespace

void register_integrator(const std::string& name, IntegratorFactory factory,
                         const std::string& description,
                         const IntegratorCapabilities& capabilities) {
  if (!valid_name(name))
    throw InputError("register_integrator: '" + name +
                     "' is not a valid integrator name (1 to 64 of a-z, 0-9, '-', '_', '.')");
  if (!factory) throw InputError("register_integrator: '" + name + "' has no factory");
  check_declared(name, capabilities);
  std::lock_guard<std::mutex> lock(registry_mutex());
  for (const Entry& e : registry())
    if (e.name == name)
      throw InputError("register_integrator: an integrator named '" + name +
                       "' is already registered");
  registry().push_back({name, std::move(factory), description, capabilities});
}

std::vector<std::string> integrator_names() {
  std::lock_guard<std::mutex> lock(registry_mutex());
  std::vector<std::string> names;
  for (const auto& entry : registry()) names.push_back(entry.name);
  return names;
}

std::vector<std::string> builtin_integrator_names() {
  std::vector<std::string> names;
  for (const auto& entry : builtin_entries()) names.push_back(entry.name);
  return names;
}

std::string integrator_description(const std::string& name) {
  std::lock_guard<std::mutex> lock(registry_mutex());
  for (const auto& entry : registry())
    if (entry.name == name) return entry.description;
  return "";
}

IntegratorCapabilities integrator_capabilities(const std::string& name) {
  std::lock_guard<std::mutex> lock(registry_mutex());
  for (const auto& entry : registry())
    if (entry.name == name) return entry.capabilities;
  return {};
}

bool IntegratorCapabilities::reads_setting(const std::string& key) const {
  if (!declared || key == "name" || std::find(reads.begin(), reads.end(), key) != reads.end())
    return true;
  for (const auto& d : settings)
    if (d.key == key) return true;
  return false;
}

std::vector<std::pair<std::string, DeclaredSetting>> declared_settings() {
  std::lock_guard<std::mutex> lock(registry_mutex());
  std::vector<std::pair<std::string, DeclaredSetting>> out;
  for (const auto& entry : registry())
    for (const auto& d : entry.capabilities.settings) out.push_back({entry.name, d});
  return out;
}

double own_setting(const IntegratorSettings& s, const std::string& key) {
  if (const auto it = s.own.find(key); it != s.own.end()) return it->second;
  const DeclaredSetting* found = nullptr;
  const auto all = declared_settings();
  for (const auto& [name, d] : all)
    if (d.key == key && (!found || name == s.name)) found = &d;
  if (!found) throw InputError("'" + key + "' is not a setting any loaded integrator declares");
  return found->default_value;
}

std::unique_ptr<Integrator> make_integrator(const std::string& name) {
  IntegratorFactory factory;
  std::string known;
  {
    std::lock_guard<std::mutex> lock(registry_mutex());
    for (const auto& entry : registry()) {
      if (entry.name == name) factory = entry.factory;
      known += (known.empty() ? "" : ", ") + entry.name;
    }
  }
  if (!factory) throw InputError("integrator '" + name + "' is unknown (known: " + known + ")");
  std::unique_ptr<Integrator> integ = factory();
  if (!integ) throw RunError("integrator '" + name + "': its factory returned nothing");
  return integ;
}

}  // namespace evas

namespace evas {

void require_quasi_static_support(const Integrator& integ, const Problem& p) {
  if (p.quasi_static().empty() || integ.takes_quasi_static()) return;
  throw InputError("integrator '" + integ.name() + "' does not solve quasi-static modes (" +
                   p.describe_coordinate(p.quasi_static().front()) + ", " +
                   std::to_string(p.quasi_static().size()) +
                   " in all: rows without inertia); use ida or generalized-alpha, or keep the "
                   "modes dynamic");
}

}  // namespace evas
