// The Newmark family and its iterations (newmark.h).
#include "integrators/newmark.h"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>

#include "solver/quasi_static.h"

namespace evas {

IntegratorCapabilities newmark_capabilities() {
  IntegratorCapabilities c;
  c.declared = true;
  c.adaptive = true;
  c.fixed_step = true;
  c.formulations = {"index-3"};  // linear-acceleration: on request only (it diverges)
  c.reads = {"rtol",
             "atol",
             "step",
             "max_step",
             "min_step",
             "step_control",
             "iteration",
             "anderson_depth",
             "max_iterations",
             "formulation",
             "penalty_stiffness",
             "penalty_damping"};
  return c;
}

void NewmarkIntegrator::setup() {
  par_ = parameters();
  it_ = s_.iteration == Iteration::method_default ? par_.iteration : s_.iteration;
  if (it_ == Iteration::method_default)
    throw InputError(name() + ": its parameters name no default iteration");
  if (it_ == Iteration::anderson && s_.anderson_depth < 1)
    throw InputError(name() + ": anderson_depth must be >= 1");

  K_ = p_->jacobian_pattern();
  K_.makeCompressed();
  C_ = K_;
  so_ = std::make_unique<SecondOrderSolver>(K_);
  qs_ = p_->quasi_static();
  if (!qs_.empty()) {
    if (const double rho = algebraic_amplification(par_); rho >= 1.0 - 1e-12)
      throw InputError(name() + ": its Newmark relations (beta " + format_number(par_.beta) +
                       ", gamma " + format_number(par_.gamma) +
                       ") amplify the accelerations of a coordinate without inertia by " +
                       format_number(rho) + " per step, so it cannot solve quasi-static modes (" +
                       p_->describe_coordinate(qs_.front()) +
                       "); use generalized-alpha with rho_inf < 1, or ida");
    so_->set_mass_diagonal(mass_diagonal(*p_));
  }
  combined_ = (it_ == Iteration::effective_mass || it_ == Iteration::newton) &&
              s_.step_control != StepControl::adaptive;
  so_->C().coeffs().setZero();  // (factorize_combination's S = K + 0 C)
  factored_ = false;
  have_jacobian_ = false;
  body_ = false;
  h_factor_ = 0.0;
  kb_last_ = Vec::Zero(K_.nonZeros());
  cb_last_ = Vec::Zero(C_.nonZeros());
  R_.resize(n_);
  f_prev_ = Vec::Zero(n_);
  delta_.resize(n_);
  if (it_ == Iteration::anderson) {
    dG_.resize(n_, s_.anderson_depth);
    dF_.resize(n_, s_.anderson_depth);
  }
}

void NewmarkIntegrator::kinematics(double h, const Vec& a) {
  q1_ = q_ + h * v_ + (h * h) * ((0.5 - par_.beta) * a_ + par_.beta * a);
  v1_ = v_ + h * ((1.0 - par_.gamma) * a_ + par_.gamma * a);
}

void NewmarkIntegrator::factorize(const SpMat& K, const SpMat& C, double h) {
  std::copy(K.valuePtr(), K.valuePtr() + K.nonZeros(), so_->K().valuePtr());
  std::copy(C.valuePtr(), C.valuePtr() + C.nonZeros(), so_->C().valuePtr());
  const double ck = (1.0 - par_.alpha_f) * par_.beta * h * h;
  const double cc = (1.0 - par_.alpha_f) * par_.gamma * h;
  factored_ = so_->factor_matrix(ck, cc, 1.0 - par_.alpha_m);
  ++stats_.linear_setups;
  h_factor_ = h;
  if (!factored_)
    throw RunError(name() + ": the iteration matrix is singular" + where(t_ + h, h, q1_, v1_));
}

void NewmarkIntegrator::factorize_combination(double t1, double h) {
  const double ck = (1.0 - par_.alpha_f) * par_.beta * h * h;
  const double cc = (1.0 - par_.alpha_f) * par_.gamma * h;
  p_->force_jacobian_combination(t1, q1_.data(), v1_.data(), ck, cc, so_->K());
  ++stats_.jacobian_evals;
  have_jacobian_ = true;
  factored_ = so_->factor_matrix(1.0, 0.0, 1.0 - par_.alpha_m);
  ++stats_.linear_setups;
  h_factor_ = h;
  if (!factored_)
    throw RunError(name() + ": the iteration matrix is singular" + where(t1, h, q1_, v1_));
}

bool NewmarkIntegrator::step(double t, double h) {
  // Generalized-alpha's a_n approximates the acceleration at t_n + (alpha_m -
  // alpha_f) h, not at t_n (Arnold & Bruls, Multibody Syst. Dyn. 18 (2007)
  // 185-202): the offset moves with the step. A step of h after one of
  // h_prev starts from a_n moved along the acceleration's slope by (alpha_m -
  // alpha_f)(h - h_prev), the slope from the last two steps' a. Without it each
  // change of step leaves an O(h) error in a, and steps that keep changing lose
  // the second order (tests/test_step_control.cpp,
  // ChangingStepsKeepSecondOrder). A step that fails gives a_n back.
  return shifted_step(h, par_.alpha_m - par_.alpha_f, a_, a_prev_, a_save_,
                      [&] { return iterate(t, h); });
}

// The update delta_ of the acceleration by the step's iteration: Newton
// (a fresh matrix at every iterate), effective mass (a held matrix, refreshed
// when the iteration contracts slowly), or the fixed point and Anderson (the
// body operator's matrix, or the residual scaled by the unit mass).
void NewmarkIntegrator::solve_update(double t1, double h, double am, bool& refresh, bool& fresh) {
  switch (it_) {
    case Iteration::newton:
      if (combined_) {
        factorize_combination(t1, h);
      } else {
        p_->force_jacobian(t1, q1_.data(), v1_.data(), K_, C_);
        ++stats_.jacobian_evals;
        factorize(K_, C_, h);
      }
      so_->solve_matrix(R_.data(), delta_.data());
      ++stats_.linear_solves;
      break;
    case Iteration::effective_mass:
      if (refresh || (combined_ && (!factored_ || std::abs(h / h_factor_ - 1.0) > 0.2))) {
        if (combined_) {
          factorize_combination(t1, h);
        } else {
          p_->force_jacobian(t1, q1_.data(), v1_.data(), K_, C_);
          ++stats_.jacobian_evals;
          have_jacobian_ = true;
          factorize(K_, C_, h);
        }
        fresh = true;
        refresh = false;
      } else if (!factored_ || std::abs(h / h_factor_ - 1.0) > 0.2) {
        factorize(K_, C_, h);
      }
      so_->solve_matrix(R_.data(), delta_.data());
      ++stats_.linear_solves;
      break;
    case Iteration::method_default:  // (resolved to the method's own in setup())
    case Iteration::fixed_point:
    case Iteration::anderson:
      if (body_) {
        so_->solve_matrix(R_.data(), delta_.data());
        ++stats_.linear_solves;
      } else {
        if (!qs_.empty())
          throw InputError(name() + ": iteration " + to_text(it_) +
                           " without a body operator cannot solve quasi-static modes (" +
                           p_->describe_coordinate(qs_.front()) +
                           "); use iteration=effective-mass or newton");
        delta_ = R_ / (1.0 - am);
      }
      break;
  }
}

// Fixed point and Anderson: the body operator's matrix at t1, refactorized
// when it, or h, changed (body_ = false when the bodies carry no operator).
void NewmarkIntegrator::prepare_body_operator(double t1, double h) {
  p_->body_operator(t1, K_, C_);
  ++stats_.jacobian_evals;
  Eigen::Map<const Vec> kb(K_.valuePtr(), K_.nonZeros());
  Eigen::Map<const Vec> cb(C_.valuePtr(), C_.nonZeros());
  body_ = kb.lpNorm<Eigen::Infinity>() > 0.0 || cb.lpNorm<Eigen::Infinity>() > 0.0;
  if (body_ && (!factored_ || h != h_factor_ || kb != kb_last_ || cb != cb_last_)) {
    factorize(K_, C_, h);
    kb_last_ = kb;
    cb_last_ = cb;
  }
}

// The paper's balance test on the residual rn of iterate k (before its update).
NewmarkIntegrator::Verdict NewmarkIntegrator::balance_test(const IterationState& st, double t1,
                                                           double h, int k, const Vec& a,
                                                           double rn) {
  const double am = par_.alpha_m, btol = s_.balance_tol;
  // relative to the inertia over the step: a step that ends where the
  // acceleration crosses zero is measured against the one it starts with
  const double inertia = am == 0.0 ? a.norm() : ((1.0 - am) * a + am * a_).norm();
  const double eps = rn / std::max({inertia, st.a_norm, s_.atol});
  if (eps <= btol) {
    stats_.max_step_iterations = std::max<long>(stats_.max_step_iterations, k);
    return Verdict::converged;  // balanced: (q1_, v1_, a1_, f1_) consistent
  }
  if (k >= s_.max_iterations) {
    fail("balance error " + format_number(eps) + " > balance_tol " + format_number(btol), t1, h, k);
    return Verdict::failed;
  }
  // the paper's fixed point contracts linearly: once the rate is known, give up
  // on a step that cannot balance within max_iterations (sub-steps are cheaper)
  if (it_ == Iteration::fixed_point && k >= 4) {
    const double rho = std::cbrt(rn / rnorms_[static_cast<std::size_t>(k - 3)]);
    const double needed = rho < 1.0 ? std::log(eps / btol) / -std::log(rho) : 1e300;
    if (k + needed > 1.5 * s_.max_iterations) {
      fail("balance error " + format_number(eps) + " > balance_tol " + format_number(btol) +
               " and would not fall below it within " +
               "max_iterations = " + std::to_string(s_.max_iterations),
           t1, h, k);
      return Verdict::failed;
    }
  }
  return Verdict::go_on;
}

// The increment test after update k: the last update dn, or from the second
// update on, the rest of a linearly converging iteration, rate / (1 - rate) dn
// with rate = dn / (the update before); with adaptive steps the error test's
// norm of the implied q, v changes (update_norm). On convergence the state is
// brought to a and f1_ to the balance it implies.
NewmarkIntegrator::Verdict NewmarkIntegrator::increment_test(IterationState& st, double t1,
                                                             double h, int k, const Vec& a) {
  const double am = par_.alpha_m, af = par_.alpha_f;
  const double dn = delta_.lpNorm<Eigen::Infinity>();
  if (!std::isfinite(dn)) {
    fail("the update is not finite", t1, h, k + 1);
    return Verdict::failed;
  }
  const double tol = s_.rtol * a.lpNorm<Eigen::Infinity>() + s_.atol;
  const double rate = k > 0 ? dn / st.prev : 1.0;
  const bool converged = st.adaptive ? update_norm(h) <= 0.1
                                     : dn <= tol || (rate < 0.9 && rate / (1.0 - rate) * dn <= tol);
  if (converged) {
    kinematics(h, a);
    f1_ = -((1.0 - am) * a + am * a_ + af * f_) / (1.0 - af);
    for (int i : qs_) f1_[i] = 0.0;  // (their rows of R = 0)
    stats_.max_step_iterations = std::max<long>(stats_.max_step_iterations, k + 1);
    return Verdict::converged;
  }
  if (it_ == Iteration::effective_mass && dn > 0.5 * st.prev && !st.fresh) st.refresh = true;
  st.prev = dn;
  return Verdict::go_on;
}

bool NewmarkIntegrator::iterate(double t, double h) {
  const double t1 = t + h;
  const double am = par_.alpha_m, af = par_.alpha_f;
  if (it_ == Iteration::fixed_point || it_ == Iteration::anderson) prepare_body_operator(t1, h);
  // With adaptive steps the iteration stops in the norm of the error test, as
  // SUNDIALS' Newton does: the changes of q and v implied by the last update,
  // (beta h^2, gamma h) delta a, at 0.1 in the weighted RMS norm (fixed_step.h);
  // otherwise on the method's own test (balance or increment).
  IterationState st;
  st.adaptive = s_.step_control == StepControl::adaptive;
  const bool balance = par_.balance && !st.adaptive;
  Vec& a = a1_;
  // predictor: the acceleration extrapolated linearly from the last two steps
  // (a_n at the start); a state it predicts that an element refuses falls back
  // to a_n
  bool extrapolated = has_history() && h_prev_ > 0.0;
  a = a_;
  if (extrapolated) a += (h / h_prev_) * (a_ - a_prev_);
  st.a_norm = a_.norm();
  rnorms_.clear();
  st.refresh = it_ == Iteration::effective_mass && !have_jacobian_;
  for (int k = 0;; ++k) {
    kinematics(h, a);
    try {
      p_->force(t1, q1_.data(), v1_.data(), f1_.data());
    } catch (const RangeError& e) {
      if (k == 0 && extrapolated) {  // try the constant predictor instead
        extrapolated = false;
        a = a_;
        --k;
        continue;
      }
      if (k == 0) throw;  // the predictor itself: the element's own message
      ++stats_.refused_states;
      return fail(std::string("iteration ") + std::to_string(k) +
                      " reached a state the model refuses (" + e.what() + ")",
                  t1, h, k);
    }
    ++stats_.residual_evals;
    R_ = (1.0 - am) * a + am * a_ + (1.0 - af) * f1_ + af * f_;
    for (int i : qs_) R_[i] = (1.0 - af) * f1_[i];  // f_i = 0 at t_{n+1}
    const double rn = R_.norm();
    rnorms_.push_back(rn);
    if (!std::isfinite(rn)) return fail("the residual is not finite", t1, h, k);
    if (balance) {
      const Verdict v = balance_test(st, t1, h, k, a, rn);
      if (v != Verdict::go_on) return v == Verdict::converged;
      if (it_ == Iteration::effective_mass && k > 0 && rn > 0.5 * rnorms_[k - 1] && !st.fresh)
        st.refresh = true;
    } else if (k >= s_.max_iterations) {
      return fail("the iteration did not converge (last |delta a|_inf = " +
                      format_number(delta_.lpNorm<Eigen::Infinity>()) + ")",
                  t1, h, k);
    }

    solve_update(t1, h, am, st.refresh, st.fresh);
    ++stats_.nonlinear_iterations;
    if (it_ == Iteration::anderson)
      anderson_update(a, k);
    else
      a -= delta_;

    if (!balance) {
      const Verdict v = increment_test(st, t1, h, k, a);
      if (v != Verdict::go_on) return v == Verdict::converged;
    }
  }
}

double NewmarkIntegrator::update_norm(double h) const {
  const double cq = par_.beta * h * h, cv = par_.gamma * h;
  double sum = 0.0;
  for (int i = 0; i < n_; ++i) {
    const double wq = 1.0 / (s_.rtol * std::abs(q1_[i]) + s_.atol);
    const double wv = 1.0 / (s_.rtol * std::abs(v1_[i]) + s_.atol);
    const double dq = cq * delta_[i] * wq, dv = cv * delta_[i] * wv;
    sum += dq * dq + dv * dv;
  }
  return std::sqrt(sum / (2.0 * n_));
}

// Anderson mixing (type II, Walker & Ni 2011) of the map G(a) = a - delta with
// residual F(a) = G(a) - a = -delta: a_{k+1} = G(a_k) - dG gamma, gamma the
// least-squares solution of dF gamma = F(a_k) over the last m differences.
void NewmarkIntegrator::anderson_update(Vec& a, int k) {
  const int m = static_cast<int>(dG_.cols());
  Vec g = a - delta_;
  Vec fres = -delta_;
  if (k > 0) {
    const int col = (k - 1) % m;
    dG_.col(col) = g - g_last_;
    dF_.col(col) = fres - fres_last_;
  }
  g_last_ = g;
  fres_last_ = fres;
  const int cols = std::min(k, m);
  if (cols == 0) {
    a = g;
    return;
  }
  const Vec gamma = dF_.leftCols(cols).colPivHouseholderQr().solve(fres);
  if (gamma.allFinite())
    a = g - dG_.leftCols(cols) * gamma;
  else
    a = g;
}

std::string NewmarkIntegrator::contraction_advice(double h) const {
  const std::size_t n = rnorms_.size();
  if (n < 3) return "";
  const std::size_t j = std::min<std::size_t>(5, n - 1);
  const double rho = std::pow(rnorms_[n - 1] / rnorms_[n - 1 - j], 1.0 / static_cast<double>(j));
  std::string s = "; the residual ";
  if (!(rho < 1.0))
    s += "grows by a factor " + format_number(rho) + " per iteration (the iteration diverges)";
  else
    s += "contracts by only " + format_number(rho) + " per iteration";
  if (it_ == Iteration::fixed_point || it_ == Iteration::anderson) {
    // the rate scales like h for the elements' damping and h^2 for their
    // stiffness: h * 0.5 / rho gives rate <= 0.5 in either case
    const double h_ok = h * std::min(0.5, 0.5 / std::max(rho, 1e-300));
    s += "; a step of about " + format_number(h_ok) +
         " s would converge (the contraction rate falls like h or h^2), or use "
         "iteration=effective-mass or newton, which put the elements' stiffness and damping "
         "into the effective mass";
  }
  return s;
}

bool NewmarkIntegrator::fail(const std::string& why, double t1, double h, int iterations) {
  failure_ = name() + " (iteration " + to_text(it_) + "): " + why + " after " +
             std::to_string(iterations) + " iterations" + contraction_advice(h) +
             where(t1, h, q1_, v1_);
  return false;
}

double NewmarkIntegrator::stability_limit(double beta, double gamma) {
  if (gamma < 0.5) return 0.0;
  if (2.0 * beta >= gamma) return std::numeric_limits<double>::infinity();
  return 1.0 / std::sqrt(0.5 * gamma - beta);
}

double NewmarkIntegrator::algebraic_amplification(const Parameters& par) {
  // A coordinate whose position its equation fixes (q_{n+1} given) takes its
  // v and h a from the Newmark relations alone:
  //   h a_{n+1} = (dq/h - v_n - (1/2 - beta) h a_n) / beta,
  //   v_{n+1} = v_n + (1 - gamma) h a_n + gamma h a_{n+1},
  // a linear recursion in (v, h a) whose homogeneous matrix is B below; its
  // spectral radius (2 + sqrt 3 for linear acceleration, 1 for the
  // trapezoidal rule, 0.8 for generalized-alpha at rho_inf 0.8).
  const double b = par.beta, g = par.gamma;
  if (!(b > 0.0)) return std::numeric_limits<double>::infinity();  // a explicit in q
  const double b11 = 1.0 - g / b, b12 = (1.0 - g) - g * (0.5 - b) / b;
  const double b21 = -1.0 / b, b22 = -(0.5 - b) / b;
  const double tr = b11 + b22, det = b11 * b22 - b12 * b21, disc = tr * tr - 4.0 * det;
  if (disc < 0.0) return std::sqrt(det);
  const double r = std::sqrt(disc);
  return std::max(std::abs(0.5 * (tr + r)), std::abs(0.5 * (tr - r)));
}

NewmarkIntegrator::Parameters NewmarkIntegrator::alpha_method(double alpha_m, double alpha_f) {
  Parameters p;
  p.alpha_m = alpha_m;
  p.alpha_f = alpha_f;
  p.gamma = 0.5 - alpha_m + alpha_f;
  p.beta = 0.25 * (1.0 - alpha_m + alpha_f) * (1.0 - alpha_m + alpha_f);
  p.balance = false;
  p.iteration = Iteration::effective_mass;
  return p;
}

double NewmarkIntegrator::velocity_error_coefficient(const Parameters& par) {
  const double am = par.alpha_m, af = par.alpha_f, d = am - af;
  const double kappa = 0.5 * (1.0 - af) - (1.0 - am) * (d + 0.5);
  return kappa + par.gamma * (0.5 + d) - 1.0 / 6.0;
}

void NewmarkIntegrator::accepted() {
  f_prev_ = f1_;  // after the swap: the force at the start of the step just taken
}

void NewmarkIntegrator::local_error(double h, bool hist, Vec& eq, Vec& ev) const {
  estimate_local_error(par_, h, hist, h_prev_, a_, a1_, a_prev_, eq, ev);
  const double am = par_.alpha_m, af = par_.alpha_f;
  if ((am == 0.0 && af == 0.0) || !hist) return;
  // generalized-alpha: the velocity error is of third order, c_v h^3 q(4)
  // (see newmark.h), q(4) from the divided difference of the physical
  // accelerations -f over the last three steps
  const double cv = velocity_error_coefficient(par_);
  const double hp = h_prev_;
  ev = ((f_ - f1_) / h - (f_prev_ - f_) / hp) * (2.0 / (h + hp) * cv * h * h * h);
}

void NewmarkIntegrator::estimate_local_error(const Parameters& par, double h, bool hist, double hp,
                                             const Vec& a0, const Vec& a1, const Vec& a_prev,
                                             Vec& eq, Vec& ev) {
  const double cq = par.beta - 1.0 / 6.0 + 0.5 * (par.alpha_m - par.alpha_f);
  if (std::abs(cq) > 1e-12) {
    eq = (cq * h * h) * (a1 - a0);
    ev.setZero();
    return;
  }
  // linear acceleration: fourth derivative from three accelerations
  if (!hist) {
    eq.setZero();
    ev = (h * h / 12.0) * (a1 - a0);
    return;
  }
  ev = ((a1 - a0) / h - (a0 - a_prev) / hp) * (2.0 / (h + hp));  // q''''
  eq = (h * h * h * h / 24.0) * ev;
  ev *= h * h * h / 12.0;
}

}  // namespace evas
