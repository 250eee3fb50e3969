// The statistics table (stats.h).
#include "model/stats.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace evas {

const std::vector<StatField>& stat_fields() {
  using S = IntegratorStats;
  static const std::vector<StatField> f = {
      {"steps", "", "accepted steps", true, [](const S& s) { return double(s.steps); }},
      {"residual_evals", "", "residual (f or F) evaluations, finite differences included", true,
       [](const S& s) { return double(s.residual_evals); }},
      {"jacobian_evals", "", "Jacobian evaluations", true,
       [](const S& s) { return double(s.jacobian_evals); }},
      {"linear_setups", "", "factorizations of the iteration matrix", true,
       [](const S& s) { return double(s.linear_setups); }},
      {"linear_solves", "", "linear solves", true,
       [](const S& s) { return double(s.linear_solves); }},
      {"nonlinear_iterations", "", "Newton or fixed-point iterations", true,
       [](const S& s) { return double(s.nonlinear_iterations); }},
      {"error_test_failures", "", "steps rejected by the local error test", true,
       [](const S& s) { return double(s.error_test_failures); }},
      {"convergence_failures", "", "steps whose iteration did not converge", true,
       [](const S& s) { return double(s.convergence_failures); }},
      {"restarts", "", "re-initializations at stops that changed the state", true,
       [](const S& s) { return double(s.restarts); }},
      {"refused_states", "", "trial states an element refused, each retried", true,
       [](const S& s) { return double(s.refused_states); }},
      {"substeps", "", "fixed steps retried as sub-steps after a failed iteration", true,
       [](const S& s) { return double(s.substeps); }},
      {"max_step_iterations", "", "most iterations taken in one fixed step", true,
       [](const S& s) { return double(s.max_step_iterations); }},
      {"wall_seconds", "s", "wall time of the integration", false,
       [](const S& s) { return s.wall_seconds; }},
      {"last_step", "s", "the last step taken", false, [](const S& s) { return s.last_step; }},
      {"min_step", "s", "smallest accepted step", false, [](const S& s) { return s.min_step; }},
      {"max_step", "s", "largest accepted step", false, [](const S& s) { return s.max_step; }},
      {"last_order", "", "order of the last step (BDF, Adams)", true,
       [](const S& s) { return double(s.last_order); }},
      {"max_constraint", "m, rad", "largest |g| at the outputs (constrained problems)", false,
       [](const S& s) { return s.max_constraint; }},
      {"max_constraint_rate", "m/s, rad/s", "largest |G v + g_t| at the outputs", false,
       [](const S& s) { return s.max_constraint_rate; }},
  };
  return f;
}

std::string stat_text(const StatField& f, const IntegratorStats& s) {
  double x = f.get(s);
  char buf[40];
  if (f.integer)
    std::snprintf(buf, sizeof buf, "%lld", static_cast<long long>(x));
  else if (!std::isfinite(x))
    return "null";
  else if (x == 0.0)
    return "0";  // no "-0"
  else
    std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

std::string stats_json_members(const IntegratorStats& s, const std::string& indent) {
  std::string out;
  for (const StatField& f : stat_fields()) {
    if (!out.empty()) out += ",\n";
    out += indent + "\"" + f.name + "\": " + stat_text(f, s);
  }
  return out;
}

namespace {

// Every field, in declaration order, handed to `f` (a long, double or int).
template <class S, class F>
void each_field(S& s, F&& f) {
  f(s.steps);
  f(s.residual_evals);
  f(s.jacobian_evals);
  f(s.linear_setups);
  f(s.linear_solves);
  f(s.nonlinear_iterations);
  f(s.error_test_failures);
  f(s.convergence_failures);
  f(s.restarts);
  f(s.refused_states);
  f(s.substeps);
  f(s.max_step_iterations);
  f(s.wall_seconds);
  f(s.last_step);
  f(s.min_step);
  f(s.max_step);
  f(s.last_order);
  f(s.max_constraint);
  f(s.max_constraint_rate);
}

// a new field must be added to each_field (and to stat_fields)
static_assert(sizeof(IntegratorStats) == 12 * sizeof(long) + 6 * sizeof(double) + 8,
              "IntegratorStats changed: update each_field");

}  // namespace

std::string stats_to_bytes(const IntegratorStats& s) {
  std::string out;
  each_field(s, [&](const auto& v) { out.append(reinterpret_cast<const char*>(&v), sizeof v); });
  return out;
}

IntegratorStats stats_from_bytes(const std::string& bytes) {
  IntegratorStats s;
  std::size_t need = 0;
  each_field(s, [&](const auto& v) { need += sizeof v; });
  if (bytes.size() != need)
    throw std::runtime_error("statistics of " + std::to_string(bytes.size()) + " bytes, expected " +
                             std::to_string(need));
  std::size_t pos = 0;
  each_field(s, [&](auto& v) {
    std::memcpy(&v, bytes.data() + pos, sizeof v);
    pos += sizeof v;
  });
  return s;
}

}  // namespace evas
