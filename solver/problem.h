// The one interface between a model and the integrators.
//
// Second-order form (unit modal mass; formulation.md section 6; a System with
// inertial elements returns f with its element mass already eliminated):
//     qdd + f(t, q, v) = 0,   v = qd,   q, v in R^n
// with Jacobians K = df/dq and C = df/dv on one fixed sparsity pattern.
// Integrators that need the first-order forms use FirstOrderForm
// (solver/first_order.h), which derives both from this interface.
//
// Stops: times the integrators must land on exactly (speed-profile knots,
// LOF re-anchoring). At a stop the problem may change the state (re-anchoring)
// and the integrator must then restart from the returned state.
#pragma once

#include <limits>
#include <string>

#include "solver/types.h"

namespace evas {

struct ProblemCounters {
  long f_evals = 0;    ///< evaluations of f
  long jac_evals = 0;  ///< evaluations of (K, C)
};

class Problem {
 public:
  virtual ~Problem() = default;
  virtual int size() const = 0;
  virtual void initial_state(Vec& q, Vec& v) const = 0;
  virtual void force(double t, const double* q, const double* v, double* f) = 0;
  /// K and C must have the pattern of jacobian_pattern(); only values are written.
  virtual void force_jacobian(double t, const double* q, const double* v, SpMat& K, SpMat& C) = 0;
  virtual const SpMat& jacobian_pattern() const = 0;
  /// First stop strictly after t (infinity if none).
  virtual double next_stop(double t) const {
    (void)t;
    return std::numeric_limits<double>::infinity();
  }
  /// Called when an integrator has landed on a stop; returns true if (q, v) changed.
  virtual bool at_stop(double t, double* q, double* v) {
    (void)t;
    (void)q;
    (void)v;
    return false;
  }
  /// Body part of f for fixed-point methods (the paper's Steps <4>-<6>):
  /// f = f0(t) + KB q + CB v + (element loads) (times M^-1 when a System has
  /// inertial elements: KB, CB then leave M^-1 out), with KB, CB block-diagonal per
  /// body and on jacobian_pattern(). Default: no body part (KB = CB = 0).
  virtual void body_operator(double t, SpMat& KB, SpMat& CB) {
    (void)t;
    KB.coeffs().setZero();
    CB.coeffs().setZero();
  }
  /// Human-readable description of where a failure happened (element, body, state).
  virtual std::string describe_state(double t, const double* q, const double* v) const;

  ProblemCounters counters;
};

}  // namespace evas
