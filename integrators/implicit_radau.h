// Radau IIA (three stages, order 5) on a first-order implicit DAE
// M y' = f(t, y) with a constant, possibly singular M (model/implicit_dae.h),
// as RADAU5 solves it (E. Hairer, G. Wanner, Solving Ordinary Differential
// Equations II, 2nd ed., Springer 1996, sections IV.8 and VII.8):
//   - the stage increments Z_i = Y_i - y_n solve
//         (1/h) sum_j D_ij M Z_j - f(t_n + c_i h, y_n + Z_i) = 0,   D = A^-1,
//     by a simplified Newton iteration transformed by D's eigenvectors into
//     one real system (g/h M - J) and one complex one (l/h M - J), J = df/dy
//     at the step's start, both dense LU;
//   - the error estimate of IV.8 with the mass matrix,
//         err = (g/h M - J)^-1 (f(t_n, y_n) + (g/h) sum_j e_j M Z_j),
//     evaluated once more through f when it fails on the first step or after
//     a rejection (RADAU5's ESTRAD);
//   - the user's rtol mapped to 0.1 rtol^(2/3) (atol in proportion) for the
//     order-3 estimate, as RADAU5 does;
//   - components of index k (ImplicitDae::component_index) are measured with
//     their tolerance divided by min(h, 1)^(k-1) (VII.8; RADAU5's NIND1/2/3
//     divide by h^(k-1)), in the error test and in the Newton iteration's norm;
//   - step control by the controller of Gustafsson (Hairer & Wanner IV.8,
//     (8.25)), keeping h while the controller asks for 1 to 1.2 times it.
#pragma once

#include "integrators/implicit_ida.h"

namespace evas {

/// Runs Radau IIA with `s` (rtol, atol, max_steps, max_step, min_step,
/// max_iterations; `step` is the first step, or every step with
/// step_control=fixed: then no error test, and a Newton failure ends the run)
/// from t = 0 to t_end. Failures come
/// back in `failure`; bad settings throw InputError.
ImplicitRun integrate_implicit_radau(ImplicitDae& p, double t_end, const IntegratorSettings& s);

}  // namespace evas
