// The Newmark family on the second-order form qdd + f(t, q, v) = 0, shared by
// generalized-alpha and linear-acceleration, and public for plug-ins: a member
// of the family is a class that gives its four parameters (parameters()), as
// examples/hht_plugin does for HHT-alpha (docs/extending.md).
//
// One step from (q_n, v_n, a_n, f_n) to t_{n+1} = t_n + h, unknown a = a_{n+1}:
//     q_{n+1} = q_n + h v_n + h^2 ((1/2 - beta) a_n + beta a)
//     v_{n+1} = v_n + h ((1 - gamma) a_n + gamma a)
//     R(a) = (1 - alpha_m) a + alpha_m a_n + (1 - alpha_f) f(t_{n+1}, q_{n+1}, v_{n+1})
//            + alpha_f f_n = 0.
// Linear acceleration is alpha_m = alpha_f = 0, beta = 1/6, gamma = 1/2 (R = a + f:
// the balance of Eq. 1 of the paper); generalized-alpha takes its four
// parameters from rho_inf (Chung & Hulbert 1993).
//
// Iterations (settings.iteration), all on the same R(a) = 0, with the
// iteration matrix S(K, C) = (1 - alpha_m) I + (1 - alpha_f)(beta h^2 K + gamma h C):
//   fixed-point     the paper's Steps <4>-<6>: a <- a - S(KB, CB)^-1 R(a), where KB,
//                   CB are only the bodies' own modal terms (Problem::body_operator):
//                   the body responds to the forces exactly, the element loads are
//                   recomputed and iterated. Converges when the elements' stiffness
//                   and damping are small for the step (contraction rate
//                   ~ ||S^-1 (1 - alpha_f)(beta h^2 K_e + gamma h C_e)|| < 1).
//   anderson        the same fixed-point map G(a) = a - S(KB, CB)^-1 R(a),
//                   accelerated by Anderson mixing of the last `anderson_depth`
//                   iterates (Walker & Ni, SIAM J. Numer. Anal. 49 (2011) 1715).
//   effective-mass  the fixed point with the elements' stiffness and damping in
//                   the effective mass: S(K, C) with K, C = df/dq, df/dv
//                   (Problem::force_jacobian), kept across iterations and steps
//                   (modified Newton), refreshed when an iteration contracts by
//                   less than a factor 2 with a matrix from an earlier step, and
//                   refactorized when h changes by more than 20 % (with adaptive
//                   steps from the K, C kept; otherwise S is formed from a new
//                   Problem::force_jacobian_combination at the current iterate,
//                   which needs half the products of K and C apart).
//   newton          full Newton: K, C and S at every iterate (S alone without
//                   adaptive steps).
// Predictor: a extrapolated linearly from a_{n-1}, a_n (a_n on the first step
// after a start, or when an element refuses the extrapolated state).
// Quasi-static coordinates (Problem::quasi_static; mass diagonal m): their
// rows of R are (1 - alpha_f) f_i(t_{n+1}, q_{n+1}, v_{n+1}), so the equation
// f_i = 0 holds at the step's end, not alpha-weighted with f_n (which would
// carry a start's residual along); S has (1 - alpha_m) m in place of
// (1 - alpha_m) I. Their accelerations follow from the Newmark relations.
// The fixed point without a body operator (R scaled by the unit mass) cannot
// take them (refused), nor can parameters whose relations amplify such a
// coordinate's accelerations (algebraic_amplification >= 1: linear
// acceleration, 2 + sqrt 3 per step; generalized-alpha at rho_inf = 1).
// Convergence:
//   balance (linear-acceleration): eps = ||R||_2 / max(||(1 - alpha_m) a + alpha_m a_n||_2,
//     ||a_n||_2, atol) <= balance_tol, checked on the iterate before an update, so
//     the accepted state is balanced to that tolerance (the paper's 0.1 %);
//   increment (generalized-alpha): after the update, ||delta a||_inf <= tol =
//     rtol ||a||_inf + atol, or, from the second update on, the error a linearly
//     converging iteration leaves, rate / (1 - rate) ||delta a||_inf <= tol with
//     rate = ||delta a|| / ||delta a before|| < 0.9 (as SUNDIALS' Newton
//     estimates its convergence rate); f_{n+1} is then taken from R = 0 itself,
//     so the discrete equations hold exactly;
//   adaptive steps (both methods): the q, v changes of the last update,
//     (beta h^2, gamma h) delta a, below 0.1 in the weighted RMS norm of the
//     error test (as SUNDIALS' Newton tests in the error-test norm), then as
//     increment. The error estimate differences accelerations: an iteration
//     error measured any other way made the step control chase it.
//
// Local error estimates (for step_control = adaptive), from Taylor expansion of
// the step about t_n with a_n ~ qdd(t_n) + (alpha_m - alpha_f) h qddd:
//   generalized-alpha:   e_q = (beta - 1/6 + (alpha_m - alpha_f)/2) h^2 (a_{n+1} - a_n)
//     (the Zienkiewicz-Xie estimate, Earthq. Eng. Struct. Dyn. 20 (1991) 871, for
//     alpha_m = alpha_f = 0), e_v = 0;
//   linear acceleration: the h^3 term vanishes (beta = 1/6); e_v = h^3/12 q'''' and
//     e_q = h^4/24 q'''', with q'''' from the divided difference of a_{n-1}, a_n,
//     a_{n+1} (first step: e_v = h^2/12 (a_{n+1} - a_n), an over-estimate).
//   generalized-alpha, velocity: the h^2 term vanishes (gamma = 1/2 - alpha_m +
//     alpha_f); with a_n ~ qdd + (alpha_m - alpha_f) h qddd + kappa h^2 q'''',
//     kappa = (1 - alpha_f)/2 - (1 - alpha_m)(alpha_m - alpha_f + 1/2) (from the
//     balance (1 - alpha_m) a_{n+1} + alpha_m a_n = -(1 - alpha_f) f_{n+1} -
//     alpha_f f_n expanded to h^2), e_v = c_v h^3 q'''' with c_v = kappa +
//     gamma (1/2 + alpha_m - alpha_f) - 1/6 (0.0895 at rho_inf = 0.8), q''''
//     from the divided difference of the physical accelerations -f_{n-1},
//     -f_n, -f_{n+1} (no estimate on the first step after a start). Without
//     it the step control saw the displacement alone, and on the paper's
//     engine the error did not follow rtol (docs/engine-speed.md).
#pragma once

#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "integrators/fixed_step.h"
#include "integrators/second_order_ls.h"

namespace evas {

/// What the Newmark family declares (integrator.h): adaptive or fixed steps,
/// the index-3 form for constraints, the settings both methods read; each
/// method adds its own (rho_inf, balance_tol).
IntegratorCapabilities newmark_capabilities();

class NewmarkIntegrator : public FixedStepIntegrator {
 public:
  struct Parameters {
    double alpha_m = 0.0, alpha_f = 0.0, beta = 1.0 / 6.0, gamma = 0.5;
    bool balance = true;                           ///< balance (true) or increment convergence
    Iteration iteration = Iteration::fixed_point;  ///< what "default" means
  };
  /// c_v of the local velocity error c_v h^3 q'''' (see above): kappa +
  /// gamma (1/2 + alpha_m - alpha_f) - 1/6; 1/12 for linear acceleration.
  static double velocity_error_coefficient(const Parameters& par);
  /// The generalized-alpha family's second-order member for alpha_m, alpha_f
  /// with the most high-frequency damping (Chung & Hulbert 1993, eqs. 17 and
  /// 21): gamma = 1/2 - alpha_m + alpha_f, beta = (1 - alpha_m + alpha_f)^2 / 4;
  /// increment convergence, the effective-mass iteration (generalized-alpha,
  /// HHT-alpha).
  static Parameters alpha_method(double alpha_m, double alpha_f);
  bool takes_quasi_static() const override { return true; }
  /// Spectral radius of the Newmark relations' recursion for a coordinate
  /// without inertia (newmark.cpp): at or above 1 quasi-static modes are refused.
  static double algebraic_amplification(const Parameters& par);
  /// The largest h omega at which Newmark's (beta, gamma) with alpha_m =
  /// alpha_f = 0 is stable on the undamped oscillator (Hughes, The Finite
  /// Element Method, section 9.1.2): infinity for 2 beta >= gamma >= 1/2,
  /// else (gamma/2 - beta)^(-1/2) (2 sqrt 3 for linear acceleration, 2 for
  /// the central difference); 0 for gamma < 1/2.
  static double stability_limit(double beta, double gamma);

 protected:
  /// The method's parameters from the settings (s_); throws InputError.
  virtual Parameters parameters() const = 0;

  void setup() override;
  bool step(double t, double h) override;
  void local_error(double h, bool hist, Vec& eq, Vec& ev) const override;
  void accepted() override;
  /// A converged step not taken: the acceleration shifted_step() moved is given back.
  void undo_step() override {
    if (shifted_) shifted_->swap(*shifted_save_);
    shifted_ = nullptr;
  }
  /// One step of h by iterate() from the filtered acceleration acc moved for a
  /// change of step (newmark.cpp, step()); acc is given back when it fails,
  /// or by undo_step() when the step converged but is not taken.
  /// shift: alpha_m - alpha_f; acc_prev: acc of the step before; save: scratch.
  template <class Iterate>
  bool shifted_step(double h, double shift, Vec& acc, const Vec& acc_prev, Vec& save,
                    Iterate&& iterate) {
    // (fixed steps differ from each other by the round-off of t + h - t: no shift)
    shifted_ = nullptr;
    if (shift == 0.0 || !has_history() || !(h_prev_ > 0.0) || std::abs(h / h_prev_ - 1.0) < 1e-9)
      return iterate();
    save = acc;
    acc += (shift * (h - h_prev_) / h_prev_) * (acc - acc_prev);
    shifted_ = &acc;
    shifted_save_ = &save;
    bool ok = false;
    try {
      ok = iterate();
    } catch (...) {
      acc.swap(save);
      shifted_ = nullptr;
      throw;
    }
    if (!ok) {
      acc.swap(save);
      shifted_ = nullptr;
    }
    return ok;
  }
  /// The estimates above from the accelerations a_n (a0), a_{n+1} (a1) and the
  /// one before (a_prev, step hp; used when hist).
  static void estimate_local_error(const Parameters& par, double h, bool hist, double hp,
                                   const Vec& a0, const Vec& a1, const Vec& a_prev, Vec& eq,
                                   Vec& ev);

 private:
  void kinematics(double h, const Vec& a);
  /// step() from a_ as it is: the iteration to the new state.
  bool iterate(double t, double h);
  /// The update delta_ of one iterate by the iteration it_ (R_ the residual).
  void solve_update(double t1, double h, double am, bool& refresh, bool& fresh);
  /// What iterate() keeps from one iterate to the next.
  struct IterationState {
    bool adaptive = false;  ///< the error test's norm stops the iteration
    double a_norm = 0.0;    ///< ||a_n||
    bool fresh = false;     ///< effective mass: matrix evaluated during this step
    bool refresh = false;   ///< effective mass: evaluate it before the next update
    double prev = std::numeric_limits<double>::infinity();  ///< the update before
  };
  enum class Verdict { go_on, converged, failed };
  void prepare_body_operator(double t1, double h);
  /// Convergence tests: the balance of the residual rn (before the update) or
  /// the increment delta_ (after it). `failed` has called fail().
  Verdict balance_test(const IterationState& st, double t1, double h, int k, const Vec& a,
                       double rn);
  Verdict increment_test(IterationState& st, double t1, double h, int k, const Vec& a);
  // S = (1 - am) I + (1 - af)(beta h^2 K + gamma h C), factorized by so_ (dense
  // LU up to n = 200, KLU above; integrators/second_order_ls.h)
  void factorize(const SpMat& K, const SpMat& C, double h);
  /// Without adaptive steps the effective-mass and Newton iterations need S at
  /// one h only: S from Problem::force_jacobian_combination at (t1, q1_, v1_),
  /// factorized (a change of h takes a new one; combined_).
  void factorize_combination(double t1, double h);
  bool fail(const std::string& why, double t1, double h, int iterations);
  std::string contraction_advice(double h) const;
  // weighted RMS norm (error-test weights) of the q, v changes of the last update
  double update_norm(double h) const;
  void anderson_update(Vec& a, int k);

  Parameters par_;
  Iteration it_ = Iteration::fixed_point;
  SpMat K_, C_;
  Vec kb_last_, cb_last_;  // body operator of the last factorization (fixed point)
  std::unique_ptr<SecondOrderSolver> so_;
  bool factored_ = false, have_jacobian_ = false, body_ = false;
  bool combined_ = false;  // factorize_combination() in place of K_, C_ (see there)
  double h_factor_ = 0.0;
  Vec f_prev_;  // f one step before the current state (valid with has_history())
  Vec R_, delta_;
  std::vector<int> qs_;          // quasi-static coordinates (Problem::quasi_static)
  Vec* shifted_ = nullptr;       // what the last shifted_step() moved (and kept) ...
  Vec* shifted_save_ = nullptr;  // ... and its value before
  Vec a_save_;                   // a_ before step() shifted it (given back if the step fails)
  std::vector<double> rnorms_;   // ||R|| per iteration of the current step
  // Anderson: differences of the fixed-point map values and residuals
  Mat dG_, dF_;
  Vec g_last_, fres_last_;
};

}  // namespace evas
