// Fekete's problem of the Test Set for IVP Solvers (F. Mazzia, C. Magherini,
// University of Bari, release 2.4, 2008; problem "fekete", after E. Hairer,
// "Fekete points on the sphere"): N = 20 points on the unit sphere that repel
// each other, damped, settling into the configuration of largest product of
// mutual distances; index 3 in the general form of model/problem.h (the test
// set states it in the stabilized index-2 (GGL) form, evas's `ggl`).
// q = (p_1, ..., p_N), the points in R^3, with alpha = 1/2,
//     p_i'' = F_i(p) - alpha p_i' - 2 p_i lambda_i,   |p_i|^2 - 1 = 0,
//     F_i = sum_{j != i} (p_i - p_j) / |p_i - p_j|^2,
// so f = alpha v - F, G_i = 2 p_i^T, and the multipliers are the test set's
// with the opposite sign (evas writes + G^T lambda on the left-hand side).
// Start (the test set's): points on four circles of latitude, at rest.
// t in [0, 1000]: the reference is the test set's (RADAU5, rtol = atol = 1e-12).
#pragma once

#include "model/problem.h"

namespace evas::problems {

class Fekete : public Problem {
 public:
  static constexpr int kPoints = 20;
  Fekete();

  int size() const override { return 3 * kPoints; }
  void initial_state(Vec& q, Vec& v) const override;
  void force(double t, const double* q, const double* v, double* f) override;
  void force_jacobian(double t, const double* q, const double* v, SpMat& K, SpMat& C) override;
  const SpMat& jacobian_pattern() const override { return kpat_; }
  int constraint_count() const override { return kPoints; }
  void constraint(double t, const double* q, const double* v, double* g, double* gv,
                  double* ga) override;
  void constraint_jacobian(double t, const double* q, SpMat& G) override;
  const SpMat& constraint_pattern() const override { return gpat_; }
  std::string constraint_name(int i) const override;
  std::string describe_coordinate(int i) const override;

 private:
  SpMat kpat_, gpat_;
};

}  // namespace evas::problems
