// A constrained mechanical problem (model/problem.h)
//     M(q) q'' + f(t, q, q') + G(t, q)^T lambda = 0,   g(t, q) = 0,
// as a first-order implicit DAE with a constant mass matrix
// (model/implicit_dae.h), the form in which RADAU5 solves the mechanical
// problems of the Test Set for IVP Solvers (Mazzia & Magherini, Bari, 2008,
// problem andrews; E. Hairer, G. Wanner, Solving ODEs II, 2nd ed., Springer
// 1996, VII.7): y = (q, v, a, lambda), M = diag(I, I, 0, 0),
//     q' = v,   v' = a,   0 = M(q) a + f(t, q, v) + G^T lambda,   0 = c(t, y),
// with the constraint row c chosen by the formulation:
//     index-3: c = g;   index-2: c = G v + g_t;   index-1: c = G a + ga.
// The index of each component (for the error scaling of Hairer & Wanner
// VII.8): index-3: q 1, v 2, a and lambda 3; index-2: q and v 1, a and lambda
// 2; index-1: all 1.
// A problem whose M is constant (Problem::mass_constant) takes the shorter
// form without a, as the test set states the car axis: y = (q, v, lambda),
// M = diag(I, M, 0), q' = v, M v' = -f - G^T lambda, 0 = c with index-1's
// c = G M^-1 (-f - G^T lambda) + ga; index-3: q 1, v 2, lambda 3; index-2: q
// and v 1, lambda 2. (With a among the unknowns an index-3 run at rtol = atol
// = 1e-4 failed on the car axis: the loose accelerations of one long step made
// every shorter step after it fail the error test.)
// df/dy by central differences (step eps^(1/3) max(1e-3, |y_j|)).
#pragma once

#include <string>

#include "model/implicit_dae.h"
#include "model/problem.h"

namespace evas::dae {

class ImplicitForm final : public ImplicitDae {
 public:
  /// formulation: "index-3", "index-2" or "index-1" (InputError otherwise).
  ImplicitForm(Problem& p, const std::string& formulation);
  int size() const override { return (reduced_ ? 2 : 3) * n_ + m_; }
  Mat mass() const override;
  void rhs(double t, const double* y, double* f) override;
  void rhs_jacobian(double t, const double* y, Mat& J) override;
  void initial(Vec& y, Vec& yp) const override;
  int component_index(int i) const override;
  std::string component_name(int i) const override;

  int n() const { return n_; }
  int m() const { return m_; }
  /// Offset of lambda in y (2 n in the form without a, else 3 n).
  int lambda_offset() const { return (reduced_ ? 2 : 3) * n_; }

 private:
  void rhs_reduced(double t, const double* y, double* f);
  // dyn -= G^T lambda, and the formulation's constraint row into c_out
  void constraint_rows(double t, const double* q, const double* v,
                       const Eigen::Ref<const Vec>& lambda, const Eigen::Ref<const Vec>& a,
                       Eigen::Ref<Vec> dyn, double* c_out);
  Problem& p_;
  int n_, m_, index_;
  bool reduced_;  // M constant: y = (q, v, lambda)
  Mat M0_, M0inv_;
  SpMat Mq_, G_;
  Vec fq_, g_, gv_, ga_, a_;
};

}  // namespace evas::dae
