// Generalized-alpha method (J. Chung, G. M. Hulbert, "A time integration
// algorithm for structural dynamics with improved numerical dissipation: the
// generalized-alpha method", J. Appl. Mech. 60 (1993) 371-375) on
//     qdd + f(t, q, v) = 0,
// fixed step h, spectral radius at infinity rho = settings.rho_inf in [0, 1]:
//     alpha_m = (2 rho - 1)/(rho + 1),  alpha_f = rho/(rho + 1),
//     gamma = 1/2 - alpha_m + alpha_f,  beta = (1 - alpha_m + alpha_f)^2 / 4.
// Unknown a = a_{n+1}:
//     q_{n+1} = q_n + h v_n + h^2 ((1/2 - beta) a_n + beta a)
//     v_{n+1} = v_n + h ((1 - gamma) a_n + gamma a)
//     R(a) = (1 - alpha_m) a + alpha_m a_n + (1 - alpha_f) f(t_{n+1}, q_{n+1}, v_{n+1})
//            + alpha_f f_n = 0,                           a_0 = -f(t_0, q_0, v_0).
// gamma = 1/2 - alpha_m + alpha_f makes the method second-order accurate.
//
// Newton: iteration matrix S = dR/da = (1 - alpha_m) I + (1 - alpha_f)(beta h^2 K + gamma h C)
// with K, C from Problem::force_jacobian, factorized by KLU (symbolic analysis
// once, numeric factorization per update). Modified Newton: S is kept across
// iterations and steps; it is refactorized (without a new Jacobian) when h
// changes (a shortened landing step), and the Jacobian is re-evaluated when
// there is none yet or when an iteration contracts by less than a factor 2
// (||delta_k|| > 0.5 ||delta_{k-1}||) with a Jacobian from an earlier step.
//
// Convergence: ||delta a||_inf <= rtol ||a||_inf + atol after the update
// (rtol, atol from the settings; atol in units of acceleration). The force
// associated with the new state, f_{n+1}, is then taken from the balance
// equation itself, f_{n+1} = -((1 - alpha_m) a + alpha_m a_n + alpha_f f_n)/(1 - alpha_f),
// so the discrete equations hold exactly with the accepted a; it differs from
// f(t_{n+1}, q_{n+1}, v_{n+1}) by the Newton tolerance and saves one force
// evaluation per step.
#include <Eigen/KLUSupport>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "integrators/common.h"
#include "integrators/fixed_step.h"

namespace evas {
namespace {

class GeneralizedAlpha final : public FixedStepIntegrator {
 public:
  std::string name() const override { return "generalized-alpha"; }

 protected:
  void setup() override {
    const double rho = s_.rho_inf;
    if (!(rho >= 0.0 && rho <= 1.0))
      throw InputError("generalized-alpha: rho_inf must be in [0, 1] (got " + format_number(rho) +
                       ")");
    am_ = (2.0 * rho - 1.0) / (rho + 1.0);
    af_ = rho / (rho + 1.0);
    gamma_ = 0.5 - am_ + af_;
    beta_ = 0.25 * (1.0 - am_ + af_) * (1.0 - am_ + af_);

    K_ = p_->jacobian_pattern();
    K_.makeCompressed();
    C_ = K_;
    std::vector<Triplet> trip;
    for (int c = 0; c < n_; ++c) {
      trip.emplace_back(c, c, 0.0);
      for (SpMat::InnerIterator it(K_, c); it; ++it) trip.emplace_back(it.row(), c, 0.0);
    }
    S_.resize(n_, n_);
    S_.setFromTriplets(trip.begin(), trip.end());
    S_.makeCompressed();
    pos_kc_.resize(static_cast<std::size_t>(K_.nonZeros()));
    for (int c = 0; c < n_; ++c)
      for (int k = K_.outerIndexPtr()[c]; k < K_.outerIndexPtr()[c + 1]; ++k)
        pos_kc_[static_cast<std::size_t>(k)] = position(K_.innerIndexPtr()[k], c);
    pos_diag_.resize(static_cast<std::size_t>(n_));
    for (int i = 0; i < n_; ++i) pos_diag_[static_cast<std::size_t>(i)] = position(i, i);
    klu_ = std::make_unique<Eigen::KLU<SpMat>>();
    klu_->analyzePattern(S_);
    if (klu_->info() != Eigen::Success)
      throw RunError("generalized-alpha: KLU symbolic analysis of the iteration matrix failed");
    have_jacobian_ = false;
    h_factor_ = 0.0;
    R_.resize(n_);
    delta_.resize(n_);
  }

  void step(double t, double h) override {
    const double t1 = t + h;
    Vec& a = a1_;
    a = a_;              // predictor
    bool fresh = false;  // Jacobian evaluated during this step
    bool refresh = !have_jacobian_;
    double prev = std::numeric_limits<double>::infinity();
    for (int k = 1;; ++k) {
      kinematics(h, a);
      p_->force(t1, q1_.data(), v1_.data(), f1_.data());
      ++stats_.residual_evals;
      R_ = (1.0 - am_) * a + am_ * a_ + (1.0 - af_) * f1_ + af_ * f_;
      if (refresh) {
        p_->force_jacobian(t1, q1_.data(), v1_.data(), K_, C_);
        ++stats_.jacobian_evals;
        have_jacobian_ = true;
        fresh = true;
        refresh = false;
        factorize(t1, h);
      } else if (h != h_factor_) {
        factorize(t1, h);
      }
      delta_ = klu_->solve(R_);
      ++stats_.linear_solves;
      ++stats_.nonlinear_iterations;
      a -= delta_;
      const double dn = delta_.lpNorm<Eigen::Infinity>();
      if (!std::isfinite(dn)) fail(t1, h, k, "the Newton update is not finite");
      if (dn <= s_.rtol * a.lpNorm<Eigen::Infinity>() + s_.atol) break;
      if (k >= s_.max_iterations) fail(t1, h, k, "Newton did not converge");
      if (dn > 0.5 * prev && !fresh) refresh = true;  // slow: new Jacobian next iteration
      prev = dn;
    }
    kinematics(h, a);
    f1_ = -((1.0 - am_) * a + am_ * a_ + af_ * f_) / (1.0 - af_);
  }

 private:
  void kinematics(double h, const Vec& a) {
    q1_ = q_ + h * v_ + (h * h) * ((0.5 - beta_) * a_ + beta_ * a);
    v1_ = v_ + h * ((1.0 - gamma_) * a_ + gamma_ * a);
  }

  void factorize(double t1, double h) {
    double* s = S_.valuePtr();
    std::fill(s, s + S_.nonZeros(), 0.0);
    const double ck = (1.0 - af_) * beta_ * h * h;
    const double cc = (1.0 - af_) * gamma_ * h;
    const double* kv = K_.valuePtr();
    const double* cv = C_.valuePtr();
    for (std::size_t e = 0; e < pos_kc_.size(); ++e) s[pos_kc_[e]] += ck * kv[e] + cc * cv[e];
    for (int pos : pos_diag_) s[pos] += 1.0 - am_;
    klu_->factorize(S_);
    ++stats_.linear_setups;
    h_factor_ = h;
    if (klu_->info() != Eigen::Success) {
      throw RunError("generalized-alpha: the iteration matrix is singular" +
                     where(t1, h, q1_, v1_));
    }
  }

  [[noreturn]] void fail(double t1, double h, int iterations, const std::string& why) {
    throw RunError("generalized-alpha: " + why + " after " + std::to_string(iterations) +
                   " iterations (last |delta a|_inf = " +
                   format_number(delta_.lpNorm<Eigen::Infinity>()) + ")" + where(t1, h, q1_, v1_));
  }

  int position(int row, int col) const {
    for (int k = S_.outerIndexPtr()[col]; k < S_.outerIndexPtr()[col + 1]; ++k)
      if (S_.innerIndexPtr()[k] == row) return k;
    throw std::logic_error("generalized-alpha: entry missing from the iteration pattern");
  }

  double am_ = 0.0, af_ = 0.0, gamma_ = 0.5, beta_ = 0.25;
  SpMat K_, C_, S_;
  std::vector<int> pos_kc_, pos_diag_;
  std::unique_ptr<Eigen::KLU<SpMat>> klu_;
  bool have_jacobian_ = false;
  double h_factor_ = 0.0;
  Vec R_, delta_;
};

}  // namespace

std::unique_ptr<Integrator> make_generalized_alpha_integrator() {
  return std::make_unique<GeneralizedAlpha>();
}

}  // namespace evas
