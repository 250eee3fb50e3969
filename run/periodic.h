// The periodic solution of a problem whose forcing repeats with period T:
// the state x* = (q, v) at t0 that the cycle map G (the integrator run from
// t0 to t0 + T) returns, G(x*) = x* (evas periodic; docs/periodic.md).
//
// Methods (PeriodicMethod), all on the same cycle map, with any integrator:
//  - fixed-point  x_{k+1} = G(x_k): a transient run, cycle after cycle;
//  - anderson     Anderson-accelerated fixed point (Walker & Ni 2011), type II,
//                 on the defect scaled per coordinate;
//  - newton       shooting: Newton on G(x) - x with the monodromy matrix from
//                 finite differences of the cycle map (2n more cycles per
//                 iteration: small models; its eigenvalues are the Floquet
//                 multipliers);
//  - projected    recursive projection (Shroff & Keller 1993): Newton on the
//                 few slow multipliers' subspace, fixed point on the rest. The
//                 subspace and its first Jacobian come from the model's own
//                 linearization, K and C averaged over the first cycle
//                 (exp(A T) on the invariant subspace of the eigenvalues with
//                 |exp(lambda T)| >= slow); secant (Broyden) updates of that
//                 p x p Jacobian follow from the cycles themselves.
// The integration error is the integrator's (its settings); the periodicity
// defect is measured apart: max_i |G(x)_i - x_i| / s_i, s_i the coordinate's
// largest |value| over the cycle, floored at 1e-4 of the largest of its kind
// (positions, velocities), and the cycle is accepted when it is <= tol.
#pragma once

#include <complex>
#include <functional>
#include <string>
#include <vector>

#include "integrators/integrator.h"
#include "model/problem.h"

namespace evas::run {

enum class PeriodicMethod { projected, newton, anderson, fixed_point };
const char* to_text(PeriodicMethod m);
/// Throws InputError listing the names when `name` is none of them.
PeriodicMethod periodic_method(const std::string& name);

struct PeriodicOptions {
  PeriodicMethod method = PeriodicMethod::projected;
  double tol = 3e-4;    ///< periodicity defect at which the cycle is accepted
  int max_cycles = 40;  ///< cycle integrations at most (newton's difference cycles count)
  double slow = 0.02;   ///< projected: multipliers |mu| >= slow are solved by Newton
  int depth = 5;        ///< anderson: earlier iterates mixed
  int samples = 24;     ///< projected: states of the first cycle in the averaged linearization
  bool secant = true;   ///< projected: Broyden updates of the slow subspace's Jacobian
  /// projected: the slow subspace's Jacobian by differences of the cycle map
  /// along its p directions (p more cycles), not from the linearization
  bool difference_jacobian = false;
  /// projected: the linearization whose slow subspace is used: "stepped" (the
  /// time-varying one over the first cycle) or "averaged" (K, C averaged)
  std::string linearization = "stepped";
  /// After convergence, the Floquet multipliers from the monodromy matrix by
  /// differences at the periodic state (2n more cycles), not the estimates
  bool difference_floquet = false;
  /// The first cycles at rtol and atol times this (1: none), until a cycle's
  /// defect is below 30 x tol; the cycle accepted is always at the settings'
  /// own tolerances (a fixed-step method's steps are not changed; newton,
  /// whose differences need one tolerance, takes every cycle at the settings').
  double coarse = 10.0;
  int steps = 180;  ///< stepped: implicit Euler steps over the cycle (at most one per sample)
};

struct FloquetMultiplier {
  std::complex<double> mu;
  std::vector<std::string> lives_in;  ///< the coordinates with the largest scaled share
};

struct PeriodicIteration {
  int cycles = 0;       ///< cycle integrations so far
  double defect = 0.0;  ///< the scaled periodicity defect of the cycle integrated last
  std::string worst;    ///< the coordinate that sets it
  std::string step;     ///< what the method did before that cycle
  double wall = 0.0;    ///< seconds since the start
};

struct PeriodicResult {
  bool converged = false;
  std::string message;  ///< why not ("" when converged)
  Vec q, v;             ///< the state at t0 of the cycle integrated last
  std::vector<PeriodicIteration> iterations;
  int cycles = 0;                              ///< cycle integrations in all
  std::vector<FloquetMultiplier> multipliers;  ///< largest modulus first
  std::string multiplier_source;               ///< how they were found ("" none)
  int slow_dimension = 0;                      ///< projected: p
  IntegratorStats stats;                       ///< summed over every cycle
  double wall = 0.0;
  /// The cycle integrated last from (q, v): its states at the sample times
  /// (the rows of the periodic cycle, once converged).
  std::vector<double> sample_t;
  std::vector<Vec> sample_q, sample_v;
};

/// Sees the cycles the method integrates from its iterates (not newton's
/// difference cycles): begin(k) before cycle k, state() at every sample time.
class CycleObserver {
 public:
  virtual ~CycleObserver() = default;
  virtual void begin(int cycle) { (void)cycle; }
  virtual void state(double t, const Vec& q, const Vec& v) = 0;
  /// Between the integrator's accepted steps of every cycle (may throw to stop).
  virtual void between_steps(double t, double h) {
    (void)t;
    (void)h;
  }
};

/// Finds the periodic state of `p` from (q0, v0) at t0 with period T.
/// `samples`: times in [t0, t0 + T) at which the observer sees each cycle and
/// the scales are taken (empty: 64 uniform). Throws InputError for a problem
/// or option the method cannot take; a failing integration throws RunError
/// (with the cycle in its message); a method that does not converge within
/// max_cycles returns converged = false with the defect history.
PeriodicResult find_periodic(Problem& p, double t0, double T, const Vec& q0, const Vec& v0,
                             const IntegratorSettings& settings, const PeriodicOptions& opt,
                             std::vector<double> samples = {}, CycleObserver* observer = nullptr);

/// An estimate of the monodromy matrix from the model's linearization at the
/// states of one cycle: Phi (2n x 2n, on x = (q, v)), its eigenvalues (the
/// Floquet multipliers' estimates) and right eigenvectors.
struct Linearization {
  Mat Phi;
  std::vector<std::complex<double>> mu;
  Eigen::MatrixXcd X;
  std::string source;  ///< how Phi was made
};
/// exp(A T), A = [[0, I], [-K, -C]] with K and C averaged over the states
/// (a time-invariant estimate: a coupling through a rotating frame averages out).
Linearization averaged_linearization(Problem& p, double T, const std::vector<double>& t,
                                     const std::vector<Vec>& q, const std::vector<Vec>& v);
/// The product over the cycle of implicit Euler steps of the linearized
/// (time-varying) equations, (I - h A(t_{k+1}))^-1, with A at the states at
/// the times t (ascending, in [t0, t0 + T)), about `steps` of them evenly
/// picked (all when there are fewer): the variational equation's monodromy to
/// first order in the step, L-stable (stiff films' multipliers go to 0, as
/// they should).
Linearization stepped_linearization(Problem& p, double t0, double T, const std::vector<double>& t,
                                    const std::vector<Vec>& q, const std::vector<Vec>& v,
                                    int steps);

}  // namespace evas::run
