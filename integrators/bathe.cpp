// The rho_inf-Bathe composite method (G. Noh, K.-J. Bathe, "The Bathe time
// integration method with controllable spectral radius: The rho_inf-Bathe
// method", Computers & Structures 212 (2019) 299-310; the standard method with
// rho_inf = 0: K.-J. Bathe, M. M. I. Baig, Computers & Structures 83 (2005)
// 2513-2524) on qdd + f(t, q, v) = 0. One step of h is two sub-steps:
//   1. the trapezoidal rule over gamma h, to t_m = t_n + gamma h:
//        q_m = q_n + (gamma h / 2)(v_n + v_m),  v_m = v_n + (gamma h / 2)(a_n + a_m),
//   2. over the whole step, with
//        q1 = (rho_inf + 1) / (2 gamma (rho_inf - 1) + 4),
//        q0 = (gamma - 1) q1 + 1/2,  q2 = -gamma q1 + 1/2:
//        v_{n+1} = v_n + h (q0 a_n + q1 a_m + q2 a_{n+1}),
//        q_{n+1} = q_n + h (q0 v_n + q1 v_m + q2 v_{n+1}),
// each sub-step ending where a + f(t, q, v) = 0. Second order; unconditionally
// stable; the spectral radius at h/T -> infinity is rho_inf (0: the standard
// Bathe method, annihilating the highest frequencies in one step; 1: two
// trapezoidal steps, no damping). gamma is the splitting for which the two
// sub-steps have the same iteration matrix,
//        gamma = (2 - sqrt(2 + 2 rho_inf)) / (1 - rho_inf)   (1/2 at rho_inf = 1),
// (the condition gamma^2 / 4 = q2^2; 2 - sqrt 2 for the standard method), so
// one factorization of S = I + (gamma h / 2)^2 K + (gamma h / 2) C serves both.
// With rho_inf = 0 and gamma = 1/2 the second sub-step is the three-point
// backward difference of Bathe & Baig (2005).
//
// Settings: rho_inf (shared with generalized-alpha: the same meaning), step,
// step_control fixed or substep (no error estimate: no adaptive steps),
// iteration effective-mass (the default: S held over iterations and steps,
// refreshed when an iteration contracts by less than a factor 2, formed anew
// when h changes by more than 20 %) or newton (S at every iterate), the
// increment test of the Newmark family (newmark.h) at rtol, atol, and
// max_iterations. Constraints as penalty forces; no mass matrix, no
// quasi-static modes, no element internal states (refused with a message).
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "integrators/common.h"
#include "integrators/fixed_step.h"
#include "integrators/second_order_ls.h"

namespace evas {
namespace {

class Bathe final : public FixedStepIntegrator {
 public:
  std::string name() const override { return "bathe"; }

  /// gamma for rho_inf (see above).
  static double splitting(double rho) {
    return rho >= 1.0 ? 0.5 : (2.0 - std::sqrt(2.0 + 2.0 * rho)) / (1.0 - rho);
  }

 protected:
  void setup() override {
    const double rho = s_.rho_inf;
    if (!(rho >= 0.0 && rho <= 1.0))
      throw InputError("bathe: rho_inf must be in [0, 1] (got " + format_number(rho) + ")");
    if (s_.step_control == StepControl::adaptive)
      throw InputError(
          "bathe: step_control=adaptive is not offered (the method has no local error "
          "estimate here); use fixed or substep");
    it_ = s_.iteration == Iteration::method_default ? Iteration::effective_mass : s_.iteration;
    if (it_ != Iteration::effective_mass && it_ != Iteration::newton)
      throw InputError(std::string("bathe: iteration=") + to_text(it_) +
                       " is not offered; use effective-mass (the default) or newton");
    gamma_ = splitting(rho);
    c1_ = (rho + 1.0) / (2.0 * gamma_ * (rho - 1.0) + 4.0);
    c0_ = (gamma_ - 1.0) * c1_ + 0.5;
    c2_ = -gamma_ * c1_ + 0.5;
    so_ = std::make_unique<SecondOrderSolver>(p_->jacobian_pattern());
    so_->C().coeffs().setZero();  // (S = the combination written into K + 0 C)
    factored_ = false;
    h_factor_ = 0.0;
    base_q_.resize(n_);
    base_v_.resize(n_);
    am_.resize(n_);
    qm_.resize(n_);
    vm_.resize(n_);
    fm_.resize(n_);
    R_.resize(n_);
    delta_.resize(n_);
  }

  bool step(double t, double h) override {
    const double h1 = gamma_ * h, c = 0.5 * h1;  // = q2 h: one matrix for both sub-steps
    // 1. trapezoidal rule to t + gamma h
    base_q_ = q_ + h1 * v_ + (c * c) * a_;
    base_v_ = v_ + c * a_;
    am_ = a_;
    if (!solve(t + h1, h, base_q_, base_v_, c, am_, qm_, vm_, fm_)) return false;
    // 2. the whole step, a_{n+1} predicted linearly through a_n, a_m
    base_v_ = v_ + h * (c0_ * a_ + c1_ * am_);
    base_q_ = q_ + h * (c0_ * v_ + c1_ * vm_ + c2_ * base_v_);
    a1_ = a_ + (am_ - a_) / gamma_;
    return solve(t + h, h, base_q_, base_v_, c2_ * h, a1_, q1_, v1_, f1_);
  }

  void local_error(double, bool, Vec& eq, Vec& ev) const override {
    eq.setZero();  // (fixed steps only: never asked for)
    ev.setZero();
  }

 private:
  // One sub-step: a with q = bq + c^2 a, v = bv + c a and a + f(t1, q, v) = 0,
  // from the guess in a; q, v, f the state at the end. h: the whole step (for
  // messages and the refactorization rule).
  bool solve(double t1, double h, const Vec& bq, const Vec& bv, double c, Vec& a, Vec& q, Vec& v,
             Vec& f) {
    const double ck = c * c;
    double prev = std::numeric_limits<double>::infinity();
    bool fresh = false;
    bool refresh = it_ == Iteration::newton || !factored_ || std::abs(h / h_factor_ - 1.0) > 0.2;
    for (int k = 0;; ++k) {
      q = bq + ck * a;
      v = bv + c * a;
      try {
        p_->force(t1, q.data(), v.data(), f.data());
      } catch (const RangeError& e) {
        if (k == 0) throw;  // the predicted state itself: the element's own message
        ++stats_.refused_states;
        return fail(std::string("iteration ") + std::to_string(k) +
                        " reached a state the model refuses (" + e.what() + ")",
                    t1, h, q, v, k);
      }
      ++stats_.residual_evals;
      R_ = a + f;
      if (!R_.allFinite()) return fail("the residual is not finite", t1, h, q, v, k);
      if (k >= s_.max_iterations)
        return fail(
            "the iteration did not converge (last |delta a|_inf = " + format_number(prev) + ")", t1,
            h, q, v, k);
      if (refresh || it_ == Iteration::newton) {
        p_->force_jacobian_combination(t1, q.data(), v.data(), ck, c, so_->K());
        ++stats_.jacobian_evals;
        factored_ = so_->factor_matrix(1.0, 0.0, 1.0);
        ++stats_.linear_setups;
        h_factor_ = h;
        if (!factored_)
          throw RunError("bathe: the iteration matrix is singular" + where(t1, h, q, v));
        fresh = true;
        refresh = false;
      }
      so_->solve_matrix(R_.data(), delta_.data());
      ++stats_.linear_solves;
      ++stats_.nonlinear_iterations;
      a -= delta_;
      const double dn = delta_.lpNorm<Eigen::Infinity>();
      if (!std::isfinite(dn)) return fail("the update is not finite", t1, h, q, v, k + 1);
      const double tol = s_.rtol * a.lpNorm<Eigen::Infinity>() + s_.atol;
      const double rate = k > 0 ? dn / prev : 1.0;
      if (dn <= tol || (rate < 0.9 && rate / (1.0 - rate) * dn <= tol)) {
        q = bq + ck * a;
        v = bv + c * a;
        f = -a;  // the balance the converged iterate implies (as the Newmark family)
        stats_.max_step_iterations = std::max<long>(stats_.max_step_iterations, k + 1);
        return true;
      }
      if (it_ == Iteration::effective_mass && dn > 0.5 * prev && !fresh) refresh = true;
      prev = dn;
    }
  }

  bool fail(const std::string& why, double t1, double h, const Vec& q, const Vec& v,
            int iterations) {
    failure_ = std::string("bathe (iteration ") + to_text(it_) + "): " + why + " after " +
               std::to_string(iterations) + " iterations" + where(t1, h, q, v);
    return false;
  }

  Iteration it_ = Iteration::effective_mass;
  double gamma_ = 0.5, c0_ = 0.0, c1_ = 0.0, c2_ = 0.0;
  std::unique_ptr<SecondOrderSolver> so_;
  bool factored_ = false;
  double h_factor_ = 0.0;
  Vec base_q_, base_v_, am_, qm_, vm_, fm_, R_, delta_;
};

}  // namespace

IntegratorEntry bathe_entry() {
  IntegratorCapabilities c;
  c.declared = true;
  c.fixed_step = true;
  c.reads = {"rtol",           "atol",           "step",    "min_step",    "step_control",
             "iteration",      "max_iterations", "rho_inf", "formulation", "penalty_stiffness",
             "penalty_damping"};
  c.stability_limit = [](const IntegratorSettings&) {
    return std::numeric_limits<double>::infinity();
  };
  return {"bathe", [] { return std::make_unique<Bathe>(); },
          "the rho_inf-Bathe composite method (Noh & Bathe 2019; rho_inf = 0: Bathe & Baig 2005)",
          c};
}

}  // namespace evas
