// The paper's linear acceleration method: Newmark with beta = 1/6, gamma = 1/2
// (the acceleration varies linearly over the step), fixed step h, on
//     qdd + f(t, q, v) = 0,   f = f0(t) + KB q + CB v + (element loads).
// Per step (the paper's Steps <4>-<6>):
//   guess a = a_n; then repeat
//     q = q_n + h v_n + h^2 (a_n/3 + a/6),   v = v_n + h (a_n + a)/2
//     r = a + f(t_{n+1}, q, v)                          (out-of-balance of Eq. 1)
//     eps = ||r||_2 / max(||a||_2, atol)                (balance error)
//     stop when eps <= balance_tol (default 1e-3, the paper's 0.1 %)
//     else solve Meff delta = -r,  a += delta,
//          Meff = I + (h/2) CB + (h^2/6) KB.
//
// Balance error: the 2-norm of the out-of-balance of Eq. 1 (inertia plus all
// forces, r = a + f) relative to the 2-norm of the inertia term a (floored at
// atol so a state at rest does not divide by zero). eps = 0.001 means the
// equation of motion balances to 0.1 % of the inertia forces.
//
// KB, CB (Problem::body_operator) are the bodies' own linear modal terms; they
// are solved for implicitly through Meff, so the body "responds to the forces"
// exactly, while the element loads are recomputed and iterated by fixed point
// ("forces are recomputed"). With no body part (KB = CB = 0) Meff = I and the
// iteration is a pure fixed point a <- -f(q(a), v(a)); it converges when the
// loads' stiffness and damping are small enough for the step
// (roughly h^2/6 |K| + h/2 |C| < 1) and diverges otherwise.
//
// Meff is factorized (KLU) at most once per step, and only when h, KB or CB
// changed since the last factorization. Counters: nonlinear_iterations = number
// of fixed-point updates; residual_evals = force evaluations; jacobian_evals =
// body_operator evaluations (one per step); linear_setups / linear_solves =
// factorizations of / solves with Meff (none when Meff = I).
#include <Eigen/KLUSupport>
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "integrators/common.h"
#include "integrators/fixed_step.h"

namespace evas {
namespace {

class LinearAcceleration final : public FixedStepIntegrator {
 public:
  std::string name() const override { return "linear-acceleration"; }

 protected:
  void setup() override {
    if (!(s_.balance_tol > 0.0))
      throw InputError("linear-acceleration: balance_tol must be > 0 (got " +
                       format_number(s_.balance_tol) + ")");
    KB_ = p_->jacobian_pattern();
    KB_.makeCompressed();
    CB_ = KB_;
    kb_last_ = Vec::Zero(KB_.nonZeros());
    cb_last_ = Vec::Zero(CB_.nonZeros());
    std::vector<Triplet> trip;
    for (int c = 0; c < n_; ++c) {
      trip.emplace_back(c, c, 0.0);
      for (SpMat::InnerIterator it(KB_, c); it; ++it) trip.emplace_back(it.row(), c, 0.0);
    }
    M_.resize(n_, n_);
    M_.setFromTriplets(trip.begin(), trip.end());
    M_.makeCompressed();
    pos_body_.resize(static_cast<std::size_t>(KB_.nonZeros()));
    for (int c = 0; c < n_; ++c)
      for (int k = KB_.outerIndexPtr()[c]; k < KB_.outerIndexPtr()[c + 1]; ++k)
        pos_body_[static_cast<std::size_t>(k)] = position(KB_.innerIndexPtr()[k], c);
    pos_diag_.resize(static_cast<std::size_t>(n_));
    for (int i = 0; i < n_; ++i) pos_diag_[static_cast<std::size_t>(i)] = position(i, i);
    klu_ = std::make_unique<Eigen::KLU<SpMat>>();
    klu_->analyzePattern(M_);
    if (klu_->info() != Eigen::Success)
      throw RunError("linear-acceleration: KLU symbolic analysis of Meff failed");
    factored_ = false;
    h_factor_ = 0.0;
    r_.resize(n_);
    delta_.resize(n_);
  }

  void step(double t, double h) override {
    const double t1 = t + h;
    p_->body_operator(t1, KB_, CB_);
    ++stats_.jacobian_evals;
    Eigen::Map<const Vec> kb(KB_.valuePtr(), KB_.nonZeros());
    Eigen::Map<const Vec> cb(CB_.valuePtr(), CB_.nonZeros());
    const bool body = kb.lpNorm<Eigen::Infinity>() > 0.0 || cb.lpNorm<Eigen::Infinity>() > 0.0;
    if (body && (!factored_ || h != h_factor_ || kb != kb_last_ || cb != cb_last_))
      factorize(t1, h);

    Vec& a = a1_;
    a = a_;  // predictor
    for (int it = 0;; ++it) {
      q1_ = q_ + h * v_ + (h * h) * (a_ / 3.0 + a / 6.0);
      v1_ = v_ + (0.5 * h) * (a_ + a);
      p_->force(t1, q1_.data(), v1_.data(), f1_.data());
      ++stats_.residual_evals;
      r_ = a + f1_;
      const double eps = r_.norm() / std::max(a.norm(), s_.atol);
      if (eps <= s_.balance_tol) return;  // balanced: (q1_, v1_, a1_, f1_) consistent
      if (!std::isfinite(eps) || it >= s_.max_iterations) {
        throw RunError("linear-acceleration: balance error " + format_number(eps) +
                       " > balance_tol " + format_number(s_.balance_tol) + " after " +
                       std::to_string(it) + " iterations" + where(t1, h, q1_, v1_));
      }
      if (body) {
        delta_ = klu_->solve(r_);
        ++stats_.linear_solves;
        a -= delta_;
      } else {
        a -= r_;
      }
      ++stats_.nonlinear_iterations;
    }
  }

 private:
  void factorize(double t1, double h) {
    double* m = M_.valuePtr();
    std::fill(m, m + M_.nonZeros(), 0.0);
    const double ck = h * h / 6.0, cc = 0.5 * h;
    const double* kv = KB_.valuePtr();
    const double* cv = CB_.valuePtr();
    for (std::size_t e = 0; e < pos_body_.size(); ++e) m[pos_body_[e]] += ck * kv[e] + cc * cv[e];
    for (int pos : pos_diag_) m[pos] += 1.0;
    klu_->factorize(M_);
    ++stats_.linear_setups;
    if (klu_->info() != Eigen::Success)
      throw RunError("linear-acceleration: Meff is singular" + where(t1, h, q_, v_));
    factored_ = true;
    h_factor_ = h;
    kb_last_ = Eigen::Map<const Vec>(KB_.valuePtr(), KB_.nonZeros());
    cb_last_ = Eigen::Map<const Vec>(CB_.valuePtr(), CB_.nonZeros());
  }

  int position(int row, int col) const {
    for (int k = M_.outerIndexPtr()[col]; k < M_.outerIndexPtr()[col + 1]; ++k)
      if (M_.innerIndexPtr()[k] == row) return k;
    throw std::logic_error("linear-acceleration: entry missing from the Meff pattern");
  }

  SpMat KB_, CB_, M_;
  Vec kb_last_, cb_last_;
  std::vector<int> pos_body_, pos_diag_;
  std::unique_ptr<Eigen::KLU<SpMat>> klu_;
  bool factored_ = false;
  double h_factor_ = 0.0;
  Vec r_, delta_;
};

}  // namespace

std::unique_ptr<Integrator> make_linear_acceleration_integrator() {
  return std::make_unique<LinearAcceleration>();
}

}  // namespace evas
