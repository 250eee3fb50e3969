// IDA on a first-order implicit DAE M y' = f(t, y) (model/implicit_dae.h): the
// residual F(t, y, y') = M y' - f(t, y) with the dense iteration matrix
// dF/dy + cj dF/dy' = cj M - df/dy, from the problem's consistent start to
// t_end in one go. Components of index > 1 leave the local error test
// (IDASetSuppressAlg; Brenan, Campbell & Petzold, Numerical Solution of
// Initial-Value Problems in DAEs, SIAM 1996, ch. 5), index-1 ones stay in it.
#pragma once

#include <string>

#include "integrators/integrator.h"
#include "model/implicit_dae.h"

namespace evas {

struct ImplicitRun {
  Vec y;           ///< at t_end (where the run stopped when it failed)
  double t = 0.0;  ///< time reached
  IntegratorStats stats;
  double wall = 0.0;    ///< set-up and integration [s]
  std::string failure;  ///< empty: completed
};

/// Runs IDA with `s` (rtol, atol, max_steps, max_order, max_step) from t = 0
/// to t_end. Failures come back in `failure`; settings IDA cannot take throw
/// InputError.
ImplicitRun integrate_implicit_ida(ImplicitDae& p, double t_end, const IntegratorSettings& s);

}  // namespace evas
