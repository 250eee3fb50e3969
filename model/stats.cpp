// The statistics table (stats.h).
#include "model/stats.h"

#include <cmath>
#include <cstdio>

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

}  // namespace evas
