// Quasi-static coordinates (Problem::quasi_static): the unit mass matrix with
// their diagonal entries zero, and a start that satisfies their equations.
#pragma once

#include "model/problem.h"

namespace evas {

/// diag(M): 1 for every coordinate, 0 for the quasi-static ones.
Vec mass_diagonal(const Problem& p);

/// Brings (q, v) to a start consistent with the quasi-static rows f_Q(t, q, v) = 0:
/// their velocities set to 0, their coordinates solved by Newton's method with
/// K_QQ = df_Q/dq_Q (the static deflection under the loads at t). The other
/// coordinates are left as they are. Throws RunError, naming the coordinate
/// of the largest residual, when Newton does not converge. Nothing happens
/// without quasi-static coordinates.
void settle_quasi_static(Problem& p, double t, Vec& q, Vec& v);

/// The accelerations of the quasi-static coordinates at a consistent (q, v):
/// those that keep f_Q = 0 along the motion, from its time derivative
///     C_QQ a_Q = -(d/dt f_Q)(a_Q = 0) = -(f_t + K_Q v + C_Qd a_d)_Q,
/// the derivative by a one-sided second-order difference along
/// (t + e, q + e v, v + e a) with the given dynamic accelerations a_d (and
/// a_Q = 0). Writes a[i] for the quasi-static i alone. IDA's yd_v and the
/// Newmark family's a at the start: a first step from a_Q = 0 would have to
/// resolve the jump of v_Q to the motion it follows.
void quasi_static_accelerations(Problem& p, double t, const Vec& q, const Vec& v, Vec& a);

}  // namespace evas
