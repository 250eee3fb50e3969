// The integrator settings table (settings.h).
#include "integrators/settings.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <iomanip>
#include <limits>
#include <sstream>

#include "integrators/common.h"

namespace evas {

namespace {

// A setting read only when another one has a value (anderson_depth with
// iteration=anderson); empty key: always read by the methods that read it.
struct Condition {
  std::string key, value;
};

struct SettingEntry {
  SettingInfo info;
  std::function<void(IntegratorSettings&, const std::string&)> set;
  std::function<std::string(const IntegratorSettings&)> get;
  Condition when;
  SettingEntry& only_with(const std::string& key, const std::string& value) {
    when = {key, value};
    return *this;
  }
};

std::string number_text(double x) {
  std::ostringstream os;
  os << std::setprecision(std::numeric_limits<double>::max_digits10) << x;
  std::string s = os.str();
  // shortest form that still round-trips
  for (int p = 1; p < std::numeric_limits<double>::max_digits10; ++p) {
    std::ostringstream t;
    t << std::setprecision(p) << x;
    if (std::strtod(t.str().c_str(), nullptr) == x) return t.str();
  }
  return s;
}

double parse_number(const std::string& key, const std::string& v) {
  const char* b = v.c_str();
  char* end = nullptr;
  errno = 0;
  const double x = std::strtod(b, &end);
  if (v.empty() || end == b || *end != '\0')
    throw InputError(key + ": '" + v + "' is not a number");
  if (errno == ERANGE || !std::isfinite(x))
    throw InputError(key + ": '" + v + "' is out of the range of a double");
  return x;
}

long parse_integer(const std::string& key, const std::string& v) {
  const char* b = v.c_str();
  char* end = nullptr;
  errno = 0;
  const long x = std::strtol(b, &end, 10);
  if (v.empty() || end == b || *end != '\0')
    throw InputError(key + ": '" + v + "' is not an integer");
  if (errno == ERANGE) throw InputError(key + ": '" + v + "' is too large");
  return x;
}

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

// A number in (lo, hi] (open_lo) or [lo, hi].
SettingEntry number(const std::string& key, const std::string& doc,
                    double IntegratorSettings::*field, double lo, double hi, bool open_lo) {
  SettingEntry e{{key, "number", "", doc}, nullptr, nullptr, {}};
  e.set = [=](IntegratorSettings& s, const std::string& v) {
    const double x = parse_number(key, v);
    if (x < lo || x > hi || (open_lo && x == lo)) {
      std::string range = (open_lo ? "> " : ">= ") + number_text(lo);
      if (hi < 1e300) range += " and <= " + number_text(hi);
      throw InputError(key + ": " + v + " must be " + range);
    }
    s.*field = x;
  };
  e.get = [=](const IntegratorSettings& s) { return number_text(s.*field); };
  return e;
}

template <class Int>
SettingEntry integer(const std::string& key, const std::string& doc, Int IntegratorSettings::*field,
                     long lo, long hi) {
  SettingEntry e{{key, "integer", "", doc}, nullptr, nullptr, {}};
  e.set = [=](IntegratorSettings& s, const std::string& v) {
    const long x = parse_integer(key, v);
    if (x < lo || x > hi)
      throw InputError(key + ": " + v + " must be in [" + std::to_string(lo) + ", " +
                       std::to_string(hi) + "]");
    s.*field = static_cast<Int>(x);
  };
  e.get = [=](const IntegratorSettings& s) { return std::to_string(s.*field); };
  return e;
}

SettingEntry choice(const std::string& key, const std::string& doc,
                    std::string IntegratorSettings::*field,
                    std::function<std::vector<std::string>()> choices) {
  SettingEntry e{{key, "choice", "", doc}, nullptr, nullptr, {}};
  e.set = [=](IntegratorSettings& s, const std::string& v) {
    const auto c = choices();
    for (const auto& x : c)
      if (x == v) {
        s.*field = v;
        return;
      }
    throw InputError(key + ": '" + v + "' is unknown (expected one of: " + join(c) + ")");
  };
  e.get = [=](const IntegratorSettings& s) { return s.*field; };
  e.info.doc += " (" + join(choices()) + ")";
  return e;
}

// A choice kept as an enum: its values in their text form.
template <class E>
SettingEntry enum_choice(const std::string& key, const std::string& doc,
                         E IntegratorSettings::*field, std::vector<E> values) {
  SettingEntry e{{key, "choice", "", doc}, nullptr, nullptr, {}};
  std::vector<std::string> names;
  for (E v : values) names.push_back(to_text(v));
  e.set = [=](IntegratorSettings& s, const std::string& v) {
    for (E x : values)
      if (v == to_text(x)) {
        s.*field = x;
        return;
      }
    throw InputError(key + ": '" + v + "' is unknown (expected one of: " + join(names) + ")");
  };
  e.get = [=](const IntegratorSettings& s) { return std::string(to_text(s.*field)); };
  e.info.doc += " (" + join(names) + ")";
  return e;
}

const std::vector<SettingEntry>& table() {
  using S = IntegratorSettings;
  const double inf = std::numeric_limits<double>::max();
  static const std::vector<SettingEntry> t = {
      choice("name", "the integrator", &S::name, [] { return integrator_names(); }),
      number("rtol", "relative tolerance (fixed-step methods: with step_control=adaptive)",
             &S::rtol, 0.0, 1.0, true),
      number("atol", "absolute tolerance (fixed-step methods: on the acceleration update)",
             &S::atol, 0.0, inf, true),
      number("step", "fixed step, or the first step when adaptive [s]", &S::step, 0.0, inf, true),
      number("max_step", "largest step, 0 = no limit [s]", &S::max_step, 0.0, inf, false),
      number("min_step", "smallest step of the step control; below it the run fails [s]",
             &S::min_step, 0.0, inf, true),
      enum_choice("step_control",
                  "fixed: pure fixed step; substep: fixed step, failed steps retried as "
                  "sub-steps; adaptive: local error against rtol/atol",
                  &S::step_control,
                  std::vector<StepControl>{StepControl::fixed, StepControl::substep,
                                           StepControl::adaptive}),
      enum_choice("iteration",
                  "solution of the implicit step: default = fixed-point for "
                  "linear-acceleration, effective-mass for generalized-alpha",
                  &S::iteration,
                  std::vector<Iteration>{Iteration::method_default, Iteration::fixed_point,
                                         Iteration::anderson, Iteration::effective_mass,
                                         Iteration::newton}),
      integer("anderson_depth", "earlier iterates mixed by Anderson", &S::anderson_depth, 1, 50)
          .only_with("iteration", "anderson"),
      number("balance_tol",
             "balance error of Eq. 1 that ends the iteration (0.001 = the paper's 0.1 %)",
             &S::balance_tol, 0.0, 1.0, true),
      integer("max_iterations", "iterations per step (radau: at most 7, RADAU5's limit)",
              &S::max_iterations, 1, 100000),
      choice("linear_solver",
             "direct linear solver: klu or dense on the 2n x 2n first-order matrix, "
             "second-order on the n x n matrix K + cj C + cj^2 I (theory 7.9)",
             &S::linear_solver,
             [] {
               return std::vector<std::string>{"klu", "dense", "second-order"};
             }),
      integer("jacobian_age",
              "steps a Jacobian is reused over (0 = evaluated at every factorization)",
              &S::jacobian_age, 0, 1000000)
          .only_with("linear_solver", "second-order"),
      choice("method", "linear multistep family", &S::method,
             [] {
               return std::vector<std::string>{"bdf", "adams"};
             }),
      [] {  // (the choices, 37 names, are listed by an unknown one's error, not here)
        SettingEntry e = choice("table", "", &S::table, [] {
          std::vector<std::string> t = arkode_implicit_tables();
          for (const auto& x : arkode_explicit_tables()) t.push_back(x);
          return t;
        });
        e.info.doc =
            "arkode's Runge-Kutta table by ARKODE's name: diagonally implicit (Newton, "
            "linear_solver; e.g. ARKODE_SDIRK_2_1_2, ARKODE_KVAERNO_7_4_5) or explicit (e.g. "
            "ARKODE_DORMAND_PRINCE_7_4_5); docs/study.md lists them";
        return e;
      }(),
      choice("imex",
             "arkode's additive (IMEX) split with an ARK pair's table (e.g. "
             "ARKODE_ARK324L2SA_DIRK_4_2_3): none; body = the bodies' own modal stiffness and "
             "damping implicit (linear; linear_solver=second-order), every other force explicit; "
             "elements = the reverse (linear_solver klu or dense)",
             &S::imex,
             [] {
               return std::vector<std::string>{"none", "body", "elements"};
             }),
      integer("max_order", "largest order, 0 = the solver's (5 BDF, 12 Adams)", &S::max_order, 0,
              12),
      number("newton_coefficient",
             "safety factor of the Newton convergence test, 0 = the solver's (0.33 IDA, 0.1 "
             "CVODE)",
             &S::newton_coefficient, 0.0, 1.0, false),
      number("rho_inf", "spectral radius at infinity", &S::rho_inf, 0.0, 1.0, false),
      integer("max_steps", "steps allowed per output interval", &S::max_steps, 1,
              std::numeric_limits<long>::max()),
      choice("formulation",
             "how constraints enter: default = ggl for ida, index-3 for generalized-alpha "
             "(linear-acceleration: index-3 on request, diverges); index-2, ggl, index-1 are "
             "ida's; penalty = forces k g + c g' (an ODE: any integrator)",
             &S::formulation,
             [] {
               return std::vector<std::string>{"default", "index-3", "index-2",
                                               "ggl",     "index-1", "penalty"};
             }),
      number("baumgarte_alpha",
             "Baumgarte damping: adds 2 alpha g' to the acceleration constraint [1/s]",
             &S::baumgarte_alpha, 0.0, inf, false)
          .only_with("formulation", "index-1"),
      number("baumgarte_beta",
             "Baumgarte stiffness: adds beta^2 g to the acceleration constraint [1/s]",
             &S::baumgarte_beta, 0.0, inf, false)
          .only_with("formulation", "index-1"),
      number("penalty_stiffness",
             "k of the constraint force G^T (k g + c g'), per unit of g [N/m, N m/rad]",
             &S::penalty_stiffness, 0.0, inf, true)
          .only_with("formulation", "penalty"),
      number("penalty_damping",
             "c of the constraint force G^T (k g + c g'), per unit of g' [N s/m]",
             &S::penalty_damping, 0.0, inf, false)
          .only_with("formulation", "penalty"),
  };
  return t;
}

const SettingEntry* find_builtin(const std::string& key) {
  for (const auto& e : table())
    if (e.info.key == key) return &e;
  return nullptr;
}

// The declaration of a plug-in's own key: that of `integrator` when it
// declares it, else the first; false when none does.
bool find_declared(const std::string& key, const std::string& integrator, DeclaredSetting& out,
                   std::string* declarer = nullptr) {
  bool found = false;
  for (const auto& [name, d] : declared_settings())
    if (d.key == key && (!found || name == integrator)) {
      out = d;
      if (declarer) *declarer = name;
      found = true;
    }
  return found;
}

[[noreturn]] void unknown_key(const std::string& key) {
  std::vector<std::string> keys;
  for (const auto& e : table()) keys.push_back(e.info.key);
  for (const auto& [name, d] : declared_settings()) keys.push_back(d.key + " (" + name + ")");
  throw InputError("'" + key + "' is not an integrator setting (known: " + join(keys) + ")");
}

const SettingEntry& find(const std::string& key) {
  if (const SettingEntry* e = find_builtin(key)) return *e;
  unknown_key(key);
}

}  // namespace

namespace {

// The built-in methods whose declarations (integrator_capabilities) read `key`.
std::vector<std::string> builtin_readers(const std::string& key) {
  std::vector<std::string> out;
  for (const auto& name : builtin_integrator_names())
    if (integrator_capabilities(name).reads_setting(key)) out.push_back(name);
  return out;
}

// "all", or the methods that read the setting, and the condition under which
// they do ("ida: linear_solver=second-order").
std::string applies_text(const SettingEntry& e) {
  const std::vector<std::string> readers = builtin_readers(e.info.key);
  std::string out = readers.size() == builtin_integrator_names().size() ? "all" : join(readers);
  if (!e.when.key.empty()) out += ": " + e.when.key + "=" + e.when.value;
  return out;
}

}  // namespace

const std::vector<SettingInfo>& integrator_settings() {
  static const std::vector<SettingInfo> infos = [] {
    std::vector<SettingInfo> v;
    for (const auto& e : table()) {
      v.push_back(e.info);
      v.back().applies = applies_text(e);
    }
    return v;
  }();
  return infos;
}

std::vector<std::string> settings_not_read_by(const std::string& integrator) {
  std::vector<std::string> keys;
  const IntegratorCapabilities caps = integrator_capabilities(integrator);
  if (!caps.declared) return keys;
  for (const auto& e : table())
    if (!caps.reads_setting(e.info.key)) keys.push_back(e.info.key);
  return keys;
}

bool is_builtin_setting(const std::string& key) { return find_builtin(key) != nullptr; }

std::string setting_unread_reason(const IntegratorSettings& s, const std::string& key) {
  if (!find_builtin(key)) {
    DeclaredSetting d;
    std::string declarer;
    if (!find_declared(key, s.name, d, &declarer)) unknown_key(key);
    if (declarer == s.name || !integrator_capabilities(s.name).declared) return "";
    return s.name + " does not read it (it is " + declarer + "'s own setting)";
  }
  const SettingEntry& e = find(key);
  const IntegratorCapabilities caps = integrator_capabilities(s.name);
  if (!caps.declared) return "";
  const std::string cond = e.when.key.empty() ? "" : e.when.key + "=" + e.when.value;
  if (!caps.reads_setting(key)) {
    const std::vector<std::string> readers = builtin_readers(key);
    return s.name + " does not read it (" + join(readers) + (readers.size() > 1 ? " do" : " does") +
           (cond.empty() ? "" : ", with " + cond) + ")";
  }
  if (cond.empty()) return "";
  const std::string here = get_integrator_setting(s, e.when.key);
  if (here != e.when.value) return "it is read only with " + cond + " (here: " + here + ")";
  return "";
}

const char* to_text(StepControl c) {
  switch (c) {
    case StepControl::fixed:
      return "fixed";
    case StepControl::substep:
      return "substep";
    case StepControl::adaptive:
      return "adaptive";
  }
  return "?";
}

const char* to_text(Iteration i) {
  switch (i) {
    case Iteration::method_default:
      return "default";
    case Iteration::fixed_point:
      return "fixed-point";
    case Iteration::anderson:
      return "anderson";
    case Iteration::effective_mass:
      return "effective-mass";
    case Iteration::newton:
      return "newton";
  }
  return "?";
}

void set_integrator_setting(IntegratorSettings& s, const std::string& key,
                            const std::string& value) {
  if (const SettingEntry* e = find_builtin(key)) {
    e->set(s, value);
    return;
  }
  DeclaredSetting d;
  if (!find_declared(key, s.name, d)) unknown_key(key);
  const double x =
      d.integer ? static_cast<double>(parse_integer(key, value)) : parse_number(key, value);
  if (!(x >= d.min && x <= d.max))
    throw InputError(key + ": " + value + " is outside [" + number_text(d.min) + ", " +
                     number_text(d.max) + "]");
  s.own[key] = x;
}

std::string get_integrator_setting(const IntegratorSettings& s, const std::string& key) {
  if (const SettingEntry* e = find_builtin(key)) return e->get(s);
  DeclaredSetting d;
  if (!find_declared(key, s.name, d)) unknown_key(key);
  return number_text(own_setting(s, key));
}

void apply_setting_assignment(IntegratorSettings& s, const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError("--set '" + assignment + "': expected KEY=VALUE");
  try {
    set_integrator_setting(s, assignment.substr(0, eq), assignment.substr(eq + 1));
  } catch (const InputError& e) {
    throw InputError(std::string("--set: ") + e.what());
  }
}

std::string builtin_integrator_list(bool fixed_step_only) {
  std::vector<std::string> names;
  for (const auto& name : builtin_integrator_names())
    if (!fixed_step_only || has_fixed_step(name)) names.push_back(name);
  return join(names);
}

bool has_fixed_step(const std::string& name) { return integrator_capabilities(name).fixed_step; }

bool takes_fixed_steps(const IntegratorSettings& s) {
  const IntegratorCapabilities caps = integrator_capabilities(s.name);
  if (caps.fixed_step_on_request) return s.step_control == StepControl::fixed;
  return caps.fixed_step && s.step_control != StepControl::adaptive;
}

std::string settings_label(const IntegratorSettings& s) {
  IntegratorSettings d;
  d.name = s.name;
  // the accuracy knob is always named, even at its default value
  const bool fixed = takes_fixed_steps(s);
  std::string out = s.name;
  for (const auto& e : table()) {
    const std::string& key = e.info.key;
    if (key == "name") continue;
    const bool knob = (key == "rtol" && !fixed) || (key == "step" && fixed);
    const std::string v = e.get(s);
    if (knob || v != e.get(d)) out += " " + key + "=" + v;
  }
  // a plug-in's own settings that were set (a value equal to its default too:
  // it was chosen), in key order
  for (const auto& [key, value] : s.own) out += " " + key + "=" + number_text(value);
  return out;
}

std::string settings_reference() {
  std::ostringstream os;
  const IntegratorSettings d;
  os << "| setting | default | applies to | meaning |\n|---|---|---|---|\n";
  for (const auto& e : table())
    os << "| `" << e.info.key << "` | " << e.get(d) << " | " << applies_text(e) << " | "
       << e.info.doc << " |\n";
  for (const auto& [name, ds] : declared_settings())
    os << "| `" << ds.key << "` | " << number_text(ds.default_value) << " | " << name
       << " (its own) | " << ds.doc << " [" << number_text(ds.min) << ", " << number_text(ds.max)
       << "]" << (ds.integer ? ", whole numbers" : "") << " |\n";
  return os.str();
}

}  // namespace evas
