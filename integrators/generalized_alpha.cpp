// Generalized-alpha method (J. Chung, G. M. Hulbert, "A time integration
// algorithm for structural dynamics with improved numerical dissipation: the
// generalized-alpha method", J. Appl. Mech. 60 (1993) 371-375) on
//     qdd + f(t, q, v) = 0,
// spectral radius at infinity rho = settings.rho_inf in [0, 1]:
//     alpha_m = (2 rho - 1)/(rho + 1),  alpha_f = rho/(rho + 1),
//     gamma = 1/2 - alpha_m + alpha_f,  beta = (1 - alpha_m + alpha_f)^2 / 4.
// gamma = 1/2 - alpha_m + alpha_f makes the method second-order accurate.
// The step, its iterations (default: effective-mass, i.e. modified Newton with
// the analytic K, C), the convergence test on the increment and the local error
// estimate are those of the Newmark family (newmark.h); step control in
// fixed_step.h.
//
// Constrained problems (M(q) qdd + f + G^T lambda = 0, g(t, q) = 0) and
// problems with a mass matrix, formulation index-3 (the default): the form of
// M. Arnold, O. Bruls, "Convergence of the generalized-alpha scheme for
// constrained mechanical systems", Multibody Syst. Dyn. 18 (2007) 185-202.
// The equations of motion hold at t_{n+1} itself, the acceleration-like
// variable a of the Newmark formulas is a filtered acceleration,
//     (1 - alpha_m) a_{n+1} + alpha_m a_n = (1 - alpha_f) qdd_{n+1} + alpha_f qdd_n,
// and the constraint g(t_{n+1}, q_{n+1}) = 0 closes the step (index 3). Newton on
// (q_{n+1}, lambda_{n+1}) with the iteration matrix
//     [ beta' M + gamma' C + K    G^T ]      beta' = (1 - alpha_m) / ((1 - alpha_f) beta h^2)
//     [ G / (beta h^2)            0   ]      gamma' = gamma / (beta h)
// (the constraint rows scaled by 1/(beta h^2) so the matrix stays conditioned
// as h -> 0: Bottasso, Dopico & Trainelli, Multibody Syst. Dyn. 19 (2008)
// 3-20), without the second-derivative terms (M qdd)_q and (G^T lambda)_q
// (modified Newton: they are O(h^2) against beta' M). Positions and velocities
// converge at order 2; lambda at order 2 after an order-1 start-up transient
// (Arnold & Bruls 2007). Start: qdd_0 and lambda_0 from the saddle-point system
// (dae/consistent.h), a_0 = qdd_0.
#include <Eigen/KLUSupport>
#include <algorithm>
#include <cmath>
#include <limits>

#include "dae/consistent.h"
#include "integrators/common.h"
#include "integrators/newmark.h"

namespace evas {
namespace {

class GeneralizedAlpha final : public NewmarkIntegrator {
 public:
  std::string name() const override { return "generalized-alpha"; }

  bool multipliers(Vec& lambda) const override {
    if (!dae_ || m_ == 0) return false;
    // linear in time between the step states (outputs between steps)
    const double t = last_output_time(), t0 = previous_time();
    const double s = t_ > t0 ? (t - t0) / (t_ - t0) : 1.0;
    lambda = lam_prev_ + std::clamp(s, 0.0, 1.0) * (lam_ - lam_prev_);
    return true;
  }

 protected:
  Parameters parameters() const override {
    const double rho = s_.rho_inf;
    if (!(rho >= 0.0 && rho <= 1.0))
      throw InputError("generalized-alpha: rho_inf must be in [0, 1] (got " + format_number(rho) +
                       ")");
    Parameters p;
    p.alpha_m = (2.0 * rho - 1.0) / (rho + 1.0);
    p.alpha_f = rho / (rho + 1.0);
    p.gamma = 0.5 - p.alpha_m + p.alpha_f;
    p.beta = 0.25 * (1.0 - p.alpha_m + p.alpha_f) * (1.0 - p.alpha_m + p.alpha_f);
    p.balance = false;
    p.iteration = "effective-mass";
    return p;
  }

  bool takes_constraints(const IntegratorSettings& s) const override {
    return s.formulation == "default" || s.formulation == "index-3";
  }
  std::string constraint_forms() const override {
    return "formulation=index-3 (the default; Arnold & Bruls 2007) or penalty";
  }

  void setup() override {
    dae_ = p_->constraint_count() > 0 || p_->has_mass();
    if (!dae_) {
      NewmarkIntegrator::setup();
      return;
    }
    par_ = parameters();
    if (s_.iteration != "default" && s_.iteration != "newton")
      throw InputError(name() + ": iteration '" + s_.iteration +
                       "' does not apply to constrained problems (modified Newton on q and "
                       "lambda; use iteration=default)");
    m_ = p_->constraint_count();
    K_ = p_->jacobian_pattern();
    C_ = K_;
    if (p_->has_mass()) M_ = p_->mass_pattern();
    if (m_ > 0) G_ = p_->constraint_pattern();
    aa_.resize(n_);
    aa1_.resize(n_);
    lam_ = Vec::Zero(m_);
    lam1_ = lam_;
    lam_prev_ = lam_;
    r_.resize(n_ + m_);
    g_.resize(m_);
    Mqdd_.resize(n_);
  }

  void start_acceleration() override {
    if (!dae_) {
      NewmarkIntegrator::start_acceleration();
      return;
    }
    const dae::ConsistentState cs = dae::consistent_state(*p_, t_, q_, v_);
    a_ = cs.a;
    aa_ = cs.a;
    lam_ = m_ > 0 ? cs.lambda : Vec::Zero(0);
    lam_prev_ = lam_;
  }

  void accepted() override {
    if (!dae_) return;
    aa_.swap(aa1_);
    lam_prev_ = lam_;
    lam_ = lam1_;
  }

  bool step(double t, double h) override {
    if (!dae_) return NewmarkIntegrator::step(t, h);
    const double am = par_.alpha_m, af = par_.alpha_f, be = par_.beta, ga = par_.gamma;
    const double t1 = t + h, bh2 = be * h * h;
    const double bp = (1.0 - am) / ((1.0 - af) * bh2), gp = ga / (be * h);
    // predictor: qdd_{n+1} = qdd_n, lambda_{n+1} = lambda_n
    a1_ = a_;
    aa1_ = (a_ - am * aa_) / (1.0 - am);
    v1_ = v_ + h * ((1.0 - ga) * aa_ + ga * aa1_);
    q1_ = q_ + h * v_ + h * h * ((0.5 - be) * aa_ + be * aa1_);
    lam1_ = lam_;
    const int maxit = std::max(1, s_.max_iterations);
    // modified Newton: the factorization is kept across steps of the same h and
    // refreshed when an iteration contracts by less than a factor 4
    bool refresh = !factored_ || h != h_factored_;
    bool fresh = false;  // factorized in this step
    double last_da = 0.0;
    for (int k = 0; k < maxit; ++k) {
      residual(t1, bh2);
      if (refresh) {
        factored_ = factorize(t1, bp, gp, bh2);
        h_factored_ = h;
        fresh = true;
        refresh = false;
        if (!factored_) {
          failure_ = name() + ": the iteration matrix [beta' M + gamma' C + K, G^T; G, 0] is " +
                     "singular (dependent constraints?)" + where(t1, h, q1_, v1_);
          return false;
        }
      }
      const Vec d = lu_.solve(-r_);
      ++stats_.linear_solves;
      ++stats_.nonlinear_iterations;
      stats_.max_step_iterations = std::max<long>(stats_.max_step_iterations, k + 1);
      const auto dq = d.head(n_);
      const double da = (dq / bh2).cwiseAbs().maxCoeff();
      if (!std::isfinite(da)) break;
      q1_ += dq;
      v1_ += gp * dq;
      aa1_ += dq / bh2;
      a1_ += bp * dq;
      lam1_ += d.tail(m_);
      // converged: the increment below the tolerance, or at the round-off of q
      const double floor =
          16.0 * std::numeric_limits<double>::epsilon() * q1_.cwiseAbs().maxCoeff() / bh2;
      if (da <= std::max(s_.rtol * aa1_.cwiseAbs().maxCoeff() + s_.atol, floor)) return true;
      // an old matrix that contracts by less than a factor 4: a fresh one
      if (k > 0 && da > 0.25 * last_da && !fresh) refresh = true;
      last_da = da;
    }
    factored_ = false;  // the retry starts from a fresh matrix
    failure_ = name() + ": Newton on (q, lambda) did not converge in " + std::to_string(maxit) +
               " iterations" + where(t1, h, q1_, v1_);
    return false;
  }

  void local_error(double h, bool hist, Vec& eq, Vec& ev) const override {
    if (!dae_) {
      NewmarkIntegrator::local_error(h, hist, eq, ev);
      return;
    }
    // the Zienkiewicz-Xie term of newmark.h on the filtered acceleration
    const double c = par_.beta - 1.0 / 6.0 + 0.5 * (par_.alpha_m - par_.alpha_f);
    eq = c * h * h * (aa1_ - aa_);
    ev.setZero();
  }

 private:
  // r = [M qdd + f + G^T lambda; g / (beta h^2)] at (t1, q1_, v1_, a1_, lam1_)
  void residual(double t1, double bh2) {
    p_->force(t1, q1_.data(), v1_.data(), f1_.data());
    ++stats_.residual_evals;
    if (p_->has_mass()) {
      p_->mass(t1, q1_.data(), M_);
      Mqdd_.noalias() = M_ * a1_;
    } else {
      Mqdd_ = a1_;
    }
    r_.head(n_) = Mqdd_ + f1_;
    if (m_ > 0) {
      p_->constraint_jacobian(t1, q1_.data(), G_);
      r_.head(n_).noalias() += G_.transpose() * lam1_;
      p_->constraint(t1, q1_.data(), v1_.data(), g_.data(), nullptr, nullptr);
      r_.tail(m_) = g_ / bh2;
    }
  }

  bool factorize(double t1, double bp, double gp, double bh2) {
    p_->force_jacobian(t1, q1_.data(), v1_.data(), K_, C_);
    ++stats_.jacobian_evals;
    std::vector<Triplet> trip;
    trip.reserve(
        static_cast<std::size_t>(2 * K_.nonZeros() + M_.nonZeros() + 2 * G_.nonZeros() + n_));
    for (int c = 0; c < n_; ++c) {
      for (SpMat::InnerIterator it(K_, c); it; ++it) trip.emplace_back(it.row(), c, it.value());
      for (SpMat::InnerIterator it(C_, c); it; ++it)
        trip.emplace_back(it.row(), c, gp * it.value());
      if (!p_->has_mass()) trip.emplace_back(c, c, bp);
    }
    if (p_->has_mass())
      for (int c = 0; c < n_; ++c)
        for (SpMat::InnerIterator it(M_, c); it; ++it)
          trip.emplace_back(it.row(), c, bp * it.value());
    if (m_ > 0)
      for (int c = 0; c < n_; ++c)
        for (SpMat::InnerIterator it(G_, c); it; ++it) {
          trip.emplace_back(n_ + it.row(), c, it.value() / bh2);
          trip.emplace_back(c, n_ + it.row(), it.value());
        }
    A_.resize(n_ + m_, n_ + m_);
    A_.setFromTriplets(trip.begin(), trip.end());
    A_.makeCompressed();
    lu_.compute(A_);
    ++stats_.linear_setups;
    return lu_.info() == Eigen::Success;
  }

  bool dae_ = false;
  int m_ = 0;
  Parameters par_;
  SpMat K_, C_, M_, G_, A_;
  Eigen::KLU<SpMat> lu_;
  Vec aa_, aa1_;               // filtered acceleration at t_ and of the trial step
  Vec lam_, lam1_, lam_prev_;  // multipliers at t_, of the trial step, at the step before
  Vec r_, g_, Mqdd_;
  bool factored_ = false;
  double h_factored_ = 0.0;
};

}  // namespace

std::unique_ptr<Integrator> make_generalized_alpha_integrator() {
  return std::make_unique<GeneralizedAlpha>();
}

}  // namespace evas
