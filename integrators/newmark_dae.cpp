// The Newmark family on constrained systems (newmark_dae.h).
#include "integrators/newmark_dae.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "dae/consistent.h"
#include "integrators/common.h"

namespace evas {

bool NewmarkDaeIntegrator::multipliers(Vec& lambda) const {
  if (!dae_ || m_ == 0) return false;
  // linear in time between the step states (outputs between steps)
  const double t = last_output_time(), t0 = previous_time();
  const double s = t_ > t0 ? (t - t0) / (t_ - t0) : 1.0;
  lambda = lam_prev_ + std::clamp(s, 0.0, 1.0) * (lam_ - lam_prev_);
  return true;
}

void NewmarkDaeIntegrator::setup() {
  dae_ = p_->constraint_count() > 0 || p_->has_mass();
  if (!dae_) {
    NewmarkIntegrator::setup();
    return;
  }
  par_ = parameters();
  if (!p_->quasi_static().empty())
    throw InputError(name() + ": quasi-static modes (" +
                     p_->describe_coordinate(p_->quasi_static().front()) + ", " +
                     std::to_string(p_->quasi_static().size()) +
                     " in all) are not yet combined with joints as constraints or a mass "
                     "matrix (use formulation=penalty)");
  if (s_.iteration != Iteration::method_default && s_.iteration != Iteration::newton)
    throw InputError(name() + ": iteration '" + to_text(s_.iteration) +
                     "' does not apply to constrained problems (modified Newton on q and "
                     "lambda; use iteration=default)");
  m_ = p_->constraint_count();
  K_ = p_->jacobian_pattern();
  C_ = K_;
  if (p_->has_mass()) M_ = p_->mass_pattern();
  if (m_ > 0) G_ = p_->constraint_pattern();
  aa_.resize(n_);
  aa1_.resize(n_);
  aa_prev_.resize(n_);
  lam_ = Vec::Zero(m_);
  lam1_ = lam_;
  lam_prev_ = lam_;
  r_.resize(n_ + m_);
  g_.resize(m_);
  Mqdd_.resize(n_);
}

void NewmarkDaeIntegrator::start_acceleration() {
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

void NewmarkDaeIntegrator::accepted() {
  NewmarkIntegrator::accepted();
  if (!dae_) return;
  aa_prev_.swap(aa_);  // (the filtered acceleration the step started from, shifted or not)
  aa_.swap(aa1_);
  lam_prev_ = lam_;
  lam_ = lam1_;
}

bool NewmarkDaeIntegrator::step(double t, double h) {
  if (!dae_) return NewmarkIntegrator::step(t, h);
  // the step-change shift of NewmarkIntegrator::step, on the filtered acceleration
  return shifted_step(h, par_.alpha_m - par_.alpha_f, aa_, aa_prev_, aa_save_,
                      [&] { return iterate_dae(t, h); });
}

bool NewmarkDaeIntegrator::iterate_dae(double t, double h) {
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

void NewmarkDaeIntegrator::local_error(double h, bool hist, Vec& eq, Vec& ev) const {
  if (!dae_) {
    NewmarkIntegrator::local_error(h, hist, eq, ev);
    return;
  }
  // the estimates of newmark.h on the filtered acceleration (qdd itself when
  // alpha_m = alpha_f = 0, whose history a_prev_ then is)
  estimate_local_error(par_, h, hist, h_prev_, aa_, aa1_, a_prev_, eq, ev);
}

void NewmarkDaeIntegrator::residual(double t1, double bh2) {
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

bool NewmarkDaeIntegrator::factorize(double t1, double bp, double gp, double bh2) {
  p_->force_jacobian(t1, q1_.data(), v1_.data(), K_, C_);
  ++stats_.jacobian_evals;
  std::vector<Triplet> trip;
  trip.reserve(
      static_cast<std::size_t>(2 * K_.nonZeros() + M_.nonZeros() + 2 * G_.nonZeros() + n_));
  for (int c = 0; c < n_; ++c) {
    for (SpMat::InnerIterator it(K_, c); it; ++it) trip.emplace_back(it.row(), c, it.value());
    for (SpMat::InnerIterator it(C_, c); it; ++it) trip.emplace_back(it.row(), c, gp * it.value());
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

}  // namespace evas
