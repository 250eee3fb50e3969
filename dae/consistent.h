// Consistent initial values of a constrained mechanical system
//     M(q) a + f(t, q, v) + G^T lambda = 0,  g(t, q) = 0   (solver/problem.h):
//  1. positions: Gauss-Newton on g(t, q) = 0 with the minimum-norm correction
//        q <- q - G^+ g,   G^+ = G^T (G G^T)^-1   (pseudo-inverse),
//     until the correction is at round-off;
//  2. velocities: the minimum-norm correction onto the velocity constraint
//        v <- v - G^+ (G v + g_t);
//  3. accelerations and multipliers from the saddle-point system
//        [ M  G^T ] [ a      ]   [ -f  ]
//        [ G  0   ] [ lambda ] = [ -ga ]
//     (the acceleration constraint G a + ga = 0; Hairer & Wanner, Solving ODEs
//     II, 2nd ed. 1996, ch. VII.1; Brenan, Campbell & Petzold 1996,
//     ch. 6). Dense complete orthogonal decompositions decide the rank, so
//     redundant constraints give the minimum-norm multipliers; independent
//     ones are solved by fixed-order Gaussian elimination
//     (dae/fixed_order_dense.h), which gives the same start in every build.
// Without constraints only step 3 remains: a = -M^-1 f (a = -f when M = I).
#pragma once

#include "model/problem.h"

namespace evas::dae {

struct ConsistentState {
  Vec q, v, a, lambda;
  double g_norm = 0.0;   ///< max |g| left at q
  double gv_norm = 0.0;  ///< max |G v + g_t| left at (q, v)
  int iterations = 0;    ///< Gauss-Newton iterations of step 1
};

/// Throws RunError naming the constraint when the projection does not
/// converge in 50 iterations.
ConsistentState consistent_state(Problem& p, double t, const Vec& q, const Vec& v);

}  // namespace evas::dae
