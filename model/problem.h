// The one interface between a model and the integrators.
//
// Second-order form (unit modal mass; formulation.md section 6; a System with
// inertial elements returns f with its element mass already eliminated):
//     qdd + f(t, q, v) = 0,   v = qd,   q, v in R^n
// with Jacobians K = df/dq and C = df/dv on one fixed sparsity pattern.
// Integrators that need the first-order forms use FirstOrderForm
// (solver/first_order.h), which derives both from this interface.
//
// Constrained systems (DAE; docs/theory.md section 10). A problem may add a
// (possibly non-unit, configuration-dependent) mass matrix and holonomic
// constraints, giving the general form
//     M(q) qdd + f(t, q, v) + G(t, q)^T lambda = 0,   g(t, q) = 0,   G = dg/dq,
// with lambda in R^m the multipliers. The defaults (M = I, m = 0) are the ODE
// form above, and integrators take today's path for such problems unchanged.
// The formulations (index-3, index-2, GGL, index-1 with Baumgarte, penalty) are
// built from these parts by dae/formulation.h; no problem writes them itself.
//
// Stops: times the integrators must land on exactly (speed-profile knots,
// LOF re-anchoring). At a stop the problem may change the state (re-anchoring)
// and the integrator must then restart from the returned state.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "model/types.h"

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
  /// S = ck K + cc C at (t, q, v), values on jacobian_pattern(): for an
  /// integrator that needs this one combination and keeps no K, C apart (the
  /// Newmark family's iteration matrix at a fixed step). Counts as a Jacobian.
  /// Default: force_jacobian() and the sum; a System forms the sum directly.
  virtual void force_jacobian_combination(double t, const double* q, const double* v, double ck,
                                          double cc, SpMat& S);
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
  // ---- DAE parts (defaults: M = I, no constraints) ----
  /// True when M(q) is not the identity.
  virtual bool has_mass() const { return false; }
  /// True when M does not depend on t or q (the identity included).
  virtual bool mass_constant() const { return !has_mass(); }
  /// M(q) on mass_pattern() (n x n, symmetric positive definite); only values written.
  virtual void mass(double t, const double* q, SpMat& M);
  virtual const SpMat& mass_pattern() const;
  /// Number of constraint equations m (0: an ODE).
  virtual int constraint_count() const { return 0; }
  /// Constraint values at (t, q, v): g = g(t, q); gv = dg/dt = G v + g_t (the
  /// velocity constraint); ga = the acceleration constraint at qdd = 0, i.e.
  ///   d(gv)/dt = G qdd + ga,  ga = (G v)_q v + 2 g_tq v + g_tt.
  /// Any output pointer may be null (not wanted). Each is m long.
  virtual void constraint(double t, const double* q, const double* v, double* g, double* gv,
                          double* ga);
  /// G = dg/dq (m x n) on constraint_pattern(); only values are written.
  virtual void constraint_jacobian(double t, const double* q, SpMat& G);
  virtual const SpMat& constraint_pattern() const;
  /// True when G does not depend on q and g_t is constant in time (e.g. joints of
  /// a body whose frame does not move): then (G^T lambda)_q, (G v)_q and the
  /// derivatives of ga vanish, and formulations skip them.
  virtual bool constraints_linear() const { return false; }
  /// Name of constraint equation i (for outputs and messages), e.g. "weld1.x".
  virtual std::string constraint_name(int i) const;

  // ---- Internal states z (defaults: none) ----
  // First-order states of the model's elements (e.g. a Maxwell mount branch,
  // a massless clutch disk): z' = h(t, q, v, z) for differential states,
  // 0 = h(t, q, v, z) for algebraic ones, with f = f(t, q, v, z). The problem
  // keeps "the current z": set_internal() stores it, and force(),
  // force_jacobian(), constraint parts, outputs and messages read it. An
  // integrator that takes internal states (Integrator::takes_internal_states)
  // sets z before every evaluation and, after advance(), to the state it
  // returns; integrate() refuses the others.
  /// Number of internal states nz (0: none).
  virtual int internal_count() const { return 0; }
  /// True for an algebraic state (0 = h_i), false for a differential one.
  virtual bool internal_algebraic(int i) const;
  /// Initial states at the initial (q, v), consistent for algebraic ones.
  virtual void internal_initial(double t, const Vec& q, const Vec& v, Vec& z);
  /// Stores z (internal_count() values) as the current states.
  virtual void set_internal(const double* z);
  /// The current states (internal_count() values; nullptr when there are none).
  virtual const double* internal() const { return nullptr; }
  /// h(t, q, v, z) at the current z (internal_count() values).
  virtual void internal_rate(double t, const double* q, const double* v, double* h);
  /// Fz = df/dz (n x nz), Hq = dh/dq, Hv = dh/dv (nz x n), Hz = dh/dz (nz x nz) at
  /// the current z, on the patterns of internal_patterns(); only values are written.
  virtual void internal_jacobian(double t, const double* q, const double* v, SpMat& Fz, SpMat& Hq,
                                 SpMat& Hv, SpMat& Hz);
  /// Patterns of Fz, Hq, Hv, Hz (in that order).
  virtual void internal_patterns(SpMat& Fz, SpMat& Hq, SpMat& Hv, SpMat& Hz) const;
  /// Name of state i for messages, e.g. "element 'mount1' z_x".
  virtual std::string internal_name(int i) const;

  // ---- Coordinates without inertia (defaults: none) ----
  /// Coordinates whose equation has no acceleration term: f_i(t, q, v) = 0 in
  /// place of qdd_i + f_i = 0, i.e. the mass matrix diag(m) with m_i = 0 for
  /// them and 1 for the others (quasi-static modes, docs/theory.md section 11).
  /// Sorted, each once. An integrator that takes them
  /// (Integrator::takes_quasi_static) solves those rows as algebraic
  /// equations; integrate() refuses the others.
  virtual const std::vector<int>& quasi_static() const;

  /// Human-readable description of where a failure happened (element, body, state).
  virtual std::string describe_state(double t, const double* q, const double* v) const;
  /// What coordinate i of q is, for messages (e.g. "body 'block', mode 12 (elastic, 834 Hz)").
  virtual std::string describe_coordinate(int i) const;

  ProblemCounters counters;

 private:
  SpMat comb_K_, comb_C_;  // force_jacobian_combination()'s default: K, C
};

/// Sets the problem's current internal states to their initial values at
/// (t, q, v) (nothing without states): for outputs recorded before an
/// integrator's init().
void start_internal_states(Problem& p, double t, const Vec& q, const Vec& v);

}  // namespace evas
