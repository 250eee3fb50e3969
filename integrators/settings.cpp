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

struct Entry {
  SettingInfo info;
  std::function<void(IntegratorSettings&, const std::string&)> set;
  std::function<std::string(const IntegratorSettings&)> get;
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
Entry number(const std::string& key, const std::string& applies, const std::string& doc,
             double IntegratorSettings::*field, double lo, double hi, bool open_lo) {
  Entry e{{key, "number", applies, doc}, nullptr, nullptr};
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
Entry integer(const std::string& key, const std::string& applies, const std::string& doc,
              Int IntegratorSettings::*field, long lo, long hi) {
  Entry e{{key, "integer", applies, doc}, nullptr, nullptr};
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

Entry choice(const std::string& key, const std::string& applies, const std::string& doc,
             std::string IntegratorSettings::*field,
             std::function<std::vector<std::string>()> choices) {
  Entry e{{key, "choice", applies, doc}, nullptr, nullptr};
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

const std::vector<Entry>& table() {
  using S = IntegratorSettings;
  const double inf = std::numeric_limits<double>::max();
  static const std::vector<Entry> t = {
      choice("name", "all", "the integrator", &S::name, [] { return integrator_names(); }),
      number("rtol", "all adaptive", "relative tolerance", &S::rtol, 0.0, 1.0, true),
      number("atol", "all", "absolute tolerance (fixed-step methods: on the acceleration update)",
             &S::atol, 0.0, inf, true),
      number("step", "generalized-alpha, linear-acceleration, radau",
             "fixed step, or the first step when adaptive [s]", &S::step, 0.0, inf, true),
      number("max_step", "all", "largest step, 0 = no limit [s]", &S::max_step, 0.0, inf, false),
      number("min_step", "generalized-alpha, linear-acceleration, radau",
             "smallest step of the step control; below it the run fails [s]", &S::min_step, 0.0,
             inf, true),
      choice("step_control", "generalized-alpha, linear-acceleration, radau",
             "fixed: pure fixed step; substep: fixed step, failed steps retried as sub-steps; "
             "adaptive: local error against rtol/atol",
             &S::step_control,
             [] {
               return std::vector<std::string>{"fixed", "substep", "adaptive"};
             }),
      choice("iteration", "generalized-alpha, linear-acceleration",
             "solution of the implicit step: default = fixed-point for linear-acceleration, "
             "effective-mass for generalized-alpha",
             &S::iteration,
             [] {
               return std::vector<std::string>{"default", "fixed-point", "anderson",
                                               "effective-mass", "newton"};
             }),
      integer("anderson_depth", "iteration=anderson", "earlier iterates mixed by Anderson",
              &S::anderson_depth, 1, 50),
      number("balance_tol", "linear-acceleration",
             "balance error of Eq. 1 that ends the iteration (0.001 = the paper's 0.1 %)",
             &S::balance_tol, 0.0, 1.0, true),
      integer("max_iterations", "generalized-alpha, linear-acceleration, radau",
              "iterations per step (radau: at most 7, RADAU5's limit)", &S::max_iterations, 1,
              100000),
      choice("linear_solver", "ida, cvode",
             "direct linear solver: klu or dense on the 2n x 2n first-order matrix, "
             "second-order on the n x n matrix K + cj C + cj^2 I (theory 7.9)",
             &S::linear_solver,
             [] {
               return std::vector<std::string>{"klu", "dense", "second-order"};
             }),
      integer("jacobian_age", "ida: linear_solver=second-order",
              "steps a Jacobian is reused over (0 = evaluated at every factorization)",
              &S::jacobian_age, 0, 1000000),
      choice("method", "cvode", "linear multistep family", &S::method,
             [] {
               return std::vector<std::string>{"bdf", "adams"};
             }),
      integer("max_order", "ida, cvode", "largest order, 0 = the solver's (5 BDF, 12 Adams)",
              &S::max_order, 0, 12),
      number("newton_coefficient", "ida, cvode",
             "safety factor of the Newton convergence test, 0 = the solver's (0.33 IDA, 0.1 "
             "CVODE)",
             &S::newton_coefficient, 0.0, 1.0, false),
      number("rho_inf", "generalized-alpha", "spectral radius at infinity", &S::rho_inf, 0.0, 1.0,
             false),
      integer("max_steps", "ida, cvode", "steps allowed per output interval", &S::max_steps, 1,
              std::numeric_limits<long>::max()),
      choice("formulation", "constrained problems",
             "how constraints enter: default = ggl for ida, index-3 for generalized-alpha "
             "(linear-acceleration: index-3 on request, diverges); index-2, ggl, index-1 are "
             "ida's; penalty = forces k g + c g' (an ODE: any integrator)",
             &S::formulation,
             [] {
               return std::vector<std::string>{"default", "index-3", "index-2",
                                               "ggl",     "index-1", "penalty"};
             }),
      number("baumgarte_alpha", "formulation=index-1",
             "Baumgarte damping: adds 2 alpha g' to the acceleration constraint [1/s]",
             &S::baumgarte_alpha, 0.0, inf, false),
      number("baumgarte_beta", "formulation=index-1",
             "Baumgarte stiffness: adds beta^2 g to the acceleration constraint [1/s]",
             &S::baumgarte_beta, 0.0, inf, false),
      number("penalty_stiffness", "formulation=penalty",
             "k of the constraint force G^T (k g + c g'), per unit of g [N/m, N m/rad]",
             &S::penalty_stiffness, 0.0, inf, true),
      number("penalty_damping", "formulation=penalty",
             "c of the constraint force G^T (k g + c g'), per unit of g' [N s/m]",
             &S::penalty_damping, 0.0, inf, false),
  };
  return t;
}

const Entry& find(const std::string& key) {
  for (const auto& e : table())
    if (e.info.key == key) return e;
  std::vector<std::string> keys;
  for (const auto& e : table()) keys.push_back(e.info.key);
  throw InputError("'" + key + "' is not an integrator setting (known: " + join(keys) + ")");
}

}  // namespace

const std::vector<SettingInfo>& integrator_settings() {
  static const std::vector<SettingInfo> infos = [] {
    std::vector<SettingInfo> v;
    for (const auto& e : table()) v.push_back(e.info);
    return v;
  }();
  return infos;
}

namespace {

bool is_builtin(const std::string& name) {
  const std::vector<std::string> builtin = builtin_integrator_names();
  return std::find(builtin.begin(), builtin.end(), name) != builtin.end();
}

// An `applies` text of the table: "ida, cvode", "ida: linear_solver=second-order",
// "iteration=anderson", "all adaptive". `methods` are the built-in methods it
// names before ':' (empty when it names anything else); `condition` is the
// KEY=VALUE after ':', or the whole text when it is one.
struct Applies {
  std::vector<std::string> methods;
  std::string condition;
};

Applies parse_applies(const std::string& a) {
  Applies out;
  const auto colon = a.find(':');
  std::string list = colon != std::string::npos ? a.substr(0, colon) : a;
  std::replace(list.begin(), list.end(), ',', ' ');
  std::istringstream words(list);
  for (std::string w; words >> w;) {
    if (!is_builtin(w)) {
      out.methods.clear();
      break;
    }
    out.methods.push_back(w);
  }
  out.condition = colon != std::string::npos         ? a.substr(colon + 1)
                  : a.find('=') != std::string::npos ? a
                                                     : "";
  out.condition.erase(0, out.condition.find_first_not_of(' '));
  return out;
}

bool names(const Applies& ap, const std::string& method) {
  return std::find(ap.methods.begin(), ap.methods.end(), method) != ap.methods.end();
}

}  // namespace

std::vector<std::string> settings_not_read_by(const std::string& integrator) {
  std::vector<std::string> keys;
  if (!is_builtin(integrator)) return keys;
  for (const auto& info : integrator_settings()) {
    const Applies ap = parse_applies(info.applies);
    if (!ap.methods.empty() && !names(ap, integrator)) keys.push_back(info.key);
  }
  return keys;
}

std::string setting_unread_reason(const IntegratorSettings& s, const std::string& key) {
  if (!is_builtin(s.name)) return "";
  const Applies ap = parse_applies(find(key).info.applies);
  if (!ap.methods.empty() && !names(ap, s.name))
    return s.name + " does not read it (" + join(ap.methods) +
           (ap.methods.size() > 1 ? " do)" : " does)");
  const auto eq = ap.condition.find('=');
  if (eq == std::string::npos) return "";
  const std::string ckey = ap.condition.substr(0, eq), cvalue = ap.condition.substr(eq + 1);
  if (!setting_unread_reason(s, ckey).empty())
    return s.name + " does not read it (it applies with " + ap.condition + ")";
  const std::string here = get_integrator_setting(s, ckey);
  if (here != cvalue) return "it is read only with " + ap.condition + " (here: " + here + ")";
  return "";
}

void set_integrator_setting(IntegratorSettings& s, const std::string& key,
                            const std::string& value) {
  find(key).set(s, value);
}

std::string get_integrator_setting(const IntegratorSettings& s, const std::string& key) {
  return find(key).get(s);
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

bool has_fixed_step(const std::string& name) {
  return name == "generalized-alpha" || name == "linear-acceleration" || name == "radau";
}

bool takes_fixed_steps(const IntegratorSettings& s) {
  return has_fixed_step(s.name) && s.step_control != "adaptive";
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
  return out;
}

std::string settings_reference() {
  std::ostringstream os;
  const IntegratorSettings d;
  os << "| setting | default | applies to | meaning |\n|---|---|---|---|\n";
  for (const auto& e : table())
    os << "| `" << e.info.key << "` | " << e.get(d) << " | " << e.info.applies << " | "
       << e.info.doc << " |\n";
  return os.str();
}

}  // namespace evas
