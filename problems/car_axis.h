// The car axis problem of the Test Set for IVP Solvers (F. Mazzia, C.
// Magherini, University of Bari; problem "caraxis", after Schneider's thesis
// and Hairer & Wanner, Solving ODEs II, 2nd ed. 1996): a model of a car axle
// on a bumpy road, index 3, in the general form of solver/problem.h.
// q = (xl, yl, xr, yr), the left and right wheel positions; the axle of length
// L joins them; the left wheel touches the road at the origin through a
// spring, the right one at the bump (xb, yb) with yb = r sin(w t),
// xb = sqrt(L^2 - yb^2). With k = M eps^2 / 2,
//     k q'' = F(t, q) + lambda1 G1^T + lambda2 G2^T   (the test set's form),
//     F = (L0 - Ll) pl / Ll - (0, k g),  (L0 - Lr) pr / Lr - (0, k g),
//     pl = (xl, yl), pr = (xr - xb, yr - yb), Ll = |pl|, Lr = |pr|,
//     g1 = xl xb + yl yb = 0,   g2 = (xl - xr)^2 + (yl - yr)^2 - L^2 = 0.
// Here M = k I, f = -F, and the multipliers are those of the test set with the
// opposite sign (evas writes + G^T lambda on the left-hand side).
// eps = 1e-2, M = 10, L = 1, L0 = 1/2, r = 0.1, w = 10, g = 1; t in [0, 3];
// start (0, 1/2, 1, 1/2), velocities (-1/2, 0, -1/2, 0) (consistent).
#pragma once

#include "model/problem.h"

namespace evas::problems {

class CarAxis : public Problem {
 public:
  CarAxis();

  int size() const override { return 4; }
  void initial_state(Vec& q, Vec& v) const override;
  void force(double t, const double* q, const double* v, double* f) override;
  void force_jacobian(double t, const double* q, const double* v, SpMat& K, SpMat& C) override;
  const SpMat& jacobian_pattern() const override { return kpat_; }
  bool has_mass() const override { return true; }
  void mass(double t, const double* q, SpMat& M) override;
  bool mass_constant() const override { return true; }
  const SpMat& mass_pattern() const override { return mpat_; }
  int constraint_count() const override { return 2; }
  void constraint(double t, const double* q, const double* v, double* g, double* gv,
                  double* ga) override;
  void constraint_jacobian(double t, const double* q, SpMat& G) override;
  const SpMat& constraint_pattern() const override { return gpat_; }
  std::string constraint_name(int i) const override;
  std::string describe_coordinate(int i) const override;

 private:
  // bump position and its first two time derivatives
  void bump(double t, double& xb, double& yb, double& xbd, double& ybd, double& xbdd,
            double& ybdd) const;
  double k_;
  SpMat kpat_, mpat_, gpat_;
};

}  // namespace evas::problems
