// Constraint residuals for the run statistics (see constraint_stats.h).
#include "dae/constraint_stats.h"

#include <algorithm>

namespace evas::dae {

void constraint_norms(Problem& p, double t, const Vec& q, const Vec& v, double& g_max,
                      double& gv_max) {
  const int m = p.constraint_count();
  g_max = gv_max = 0.0;
  if (m == 0) return;
  Vec g(m), gv(m);
  p.constraint(t, q.data(), v.data(), g.data(), gv.data(), nullptr);
  g_max = g.cwiseAbs().maxCoeff();
  gv_max = gv.cwiseAbs().maxCoeff();
}

void note_constraints(Problem& p, double t, const Vec& q, const Vec& v, IntegratorStats& s) {
  double g = 0.0, gv = 0.0;
  constraint_norms(p, t, q, v, g, gv);
  s.max_constraint = std::max(s.max_constraint, g);
  s.max_constraint_rate = std::max(s.max_constraint_rate, gv);
}

}  // namespace evas::dae
