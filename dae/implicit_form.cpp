#include "dae/implicit_form.h"

#include <cmath>
#include <limits>

#include "dae/consistent.h"
#include "dae/fixed_order_lu.h"

namespace evas::dae {

ImplicitForm::ImplicitForm(Problem& p, const std::string& formulation)
    : p_(p), n_(p.size()), m_(p.constraint_count()) {
  if (formulation == "index-3")
    index_ = 3;
  else if (formulation == "index-2")
    index_ = 2;
  else if (formulation == "index-1")
    index_ = 1;
  else
    throw InputError("formulation '" + formulation +
                     "': radau's first-order form y = (q, v, a, lambda) takes index-3, "
                     "index-2 or index-1");
  if (p.internal_count() > 0)
    throw InputError("the first-order form of a mechanical problem takes no internal states");
  if (p.has_mass()) Mq_ = p.mass_pattern();
  if (m_ > 0) G_ = p.constraint_pattern();
  reduced_ = p.mass_constant();
  M0_ = Mat::Identity(n_, n_);
  if (reduced_ && p.has_mass()) {
    Vec q, v;
    p.initial_state(q, v);
    p.mass(0.0, q.data(), Mq_);
    M0_ = Mat(Mq_);
  }
  // M0^-1 column by column in a fixed order (dae/fixed_order_lu.h): Eigen's
  // inverse and products differ in the last bits between builds
  M0inv_.resize(n_, n_);
  dae::FixedOrderLU lu;
  if (!lu.factor(M0_))
    throw InputError("the first-order form: the constant mass matrix is singular");
  Vec e = Vec::Zero(n_), col;
  for (int j = 0; j < n_; ++j) {
    e[j] = 1.0;
    lu.solve(e, col);
    M0inv_.col(j) = col;
    e[j] = 0.0;
  }
  fq_.setZero(n_);
  a_.setZero(n_);
  g_.setZero(m_);
  gv_.setZero(m_);
  ga_.setZero(m_);
}

Mat ImplicitForm::mass() const {
  Mat M = Mat::Zero(size(), size());
  for (int i = 0; i < n_; ++i) M(i, i) = 1.0;
  if (reduced_)
    M.block(n_, n_, n_, n_) = M0_;
  else
    for (int i = n_; i < 2 * n_; ++i) M(i, i) = 1.0;
  return M;
}

void ImplicitForm::rhs(double t, const double* y, double* f) {
  if (reduced_) {
    rhs_reduced(t, y, f);
    return;
  }
  const double* q = y;
  const double* v = y + n_;
  const double* a = y + 2 * n_;
  const double* lam = y + 3 * n_;
  for (int i = 0; i < n_; ++i) {
    f[i] = v[i];
    f[n_ + i] = a[i];
  }
  // 0 = -(M(q) a + f(t, q, v) + G^T lambda)
  p_.force(t, q, v, fq_.data());
  const Eigen::Map<const Vec> av(a, n_), lv(lam, m_);
  Eigen::Map<Vec> dyn(f + 2 * n_, n_);
  if (p_.has_mass()) {
    p_.mass(t, q, Mq_);
    dyn = -(Mq_ * av + fq_);
  } else {
    dyn = -(av + fq_);
  }
  if (m_ > 0) constraint_rows(t, q, v, lv, av, dyn, f + 3 * n_);
}

void ImplicitForm::constraint_rows(double t, const double* q, const double* v,
                                   const Eigen::Ref<const Vec>& lambda,
                                   const Eigen::Ref<const Vec>& a, Eigen::Ref<Vec> dyn,
                                   double* c_out) {
  p_.constraint_jacobian(t, q, G_);
  dyn -= G_.transpose() * lambda;
  p_.constraint(t, q, v, g_.data(), gv_.data(), ga_.data());
  Eigen::Map<Vec> c(c_out, m_);
  if (index_ == 3)
    c = g_;
  else if (index_ == 2)
    c = gv_;
  else
    c = G_ * a + ga_;  // the acceleration constraint
}

void ImplicitForm::rhs_reduced(double t, const double* y, double* f) {
  const double* q = y;
  const double* v = y + n_;
  const Eigen::Map<const Vec> lv(y + 2 * n_, m_);
  for (int i = 0; i < n_; ++i) f[i] = v[i];
  // M v' = -(f(t, q, v) + G^T lambda)
  p_.force(t, q, v, fq_.data());
  Eigen::Map<Vec> dyn(f + n_, n_);
  dyn = -fq_;
  if (m_ == 0) return;
  // index-1 reads a = M^-1 (-f - G^T lambda): dyn with the multipliers' term
  if (index_ == 1) {
    p_.constraint_jacobian(t, q, G_);
    const Vec rhs_a = dyn - G_.transpose() * lv;
    dae::mat_vec_fixed_order(M0inv_, rhs_a, a_);
  }
  constraint_rows(t, q, v, lv, a_, dyn, f + 2 * n_);
}

void ImplicitForm::rhs_jacobian(double t, const double* y, Mat& J) {
  const int N = size();
  J.resize(N, N);
  Vec yy = Eigen::Map<const Vec>(y, N), f0(N), f1(N);
  const double eps = std::numeric_limits<double>::epsilon();
  for (int j = 0; j < N; ++j) {
    const double keep = yy(j);
    const double d = std::cbrt(eps) * std::max(1e-3, std::abs(keep));
    yy(j) = keep + d;
    rhs(t, yy.data(), f1.data());
    yy(j) = keep - d;
    rhs(t, yy.data(), f0.data());
    yy(j) = keep;
    J.col(j) = (f1 - f0) / (2.0 * d);
  }
}

void ImplicitForm::initial(Vec& y, Vec& yp) const {
  Vec q, v;
  p_.initial_state(q, v);
  const ConsistentState c = consistent_state(p_, 0.0, q, v);
  y.resize(size());
  if (reduced_)
    y << c.q, c.v, c.lambda;
  else
    y << c.q, c.v, c.a, c.lambda;
  // y' is not needed by Radau; q' = v, v' = a, the rest unknown (zero)
  yp = Vec::Zero(size());
  yp.head(n_) = c.v;
  yp.segment(n_, n_) = c.a;
}

int ImplicitForm::component_index(int i) const {
  if (i < n_) return 1;                        // q
  if (i < 2 * n_) return index_ == 3 ? 2 : 1;  // v
  return index_;                               // a, lambda
}

std::string ImplicitForm::component_name(int i) const {
  if (i < n_) return "q " + p_.describe_coordinate(i);
  if (i < 2 * n_) return "v " + p_.describe_coordinate(i - n_);
  if (i < lambda_offset()) return "a " + p_.describe_coordinate(i - 2 * n_);
  return "lambda " + p_.constraint_name(i - lambda_offset());
}

}  // namespace evas::dae
