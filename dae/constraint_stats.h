// Constraint residuals of a state, recorded into the run statistics by the
// integrators at each state they hand back (IntegratorStats::max_constraint,
// max_constraint_rate): the position constraint |g(t, q)| and the velocity
// constraint |G v + g_t| (max norms over the m equations).
#pragma once

#include "model/problem.h"
#include "model/stats.h"

namespace evas::dae {

/// max |g| and max |G v + g_t| at (t, q, v); both 0 when m = 0.
void constraint_norms(Problem& p, double t, const Vec& q, const Vec& v, double& g_max,
                      double& gv_max);

/// Raises s.max_constraint and s.max_constraint_rate to the norms at (t, q, v).
void note_constraints(Problem& p, double t, const Vec& q, const Vec& v, IntegratorStats& s);

}  // namespace evas::dae
