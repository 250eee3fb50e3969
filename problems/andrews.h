// Andrews' squeezing mechanism, the seven-body planar mechanism of the Test
// Set for IVP Solvers (F. Mazzia, C. Magherini, University of Bari; problem
// "andrews") and of Hairer & Wanner, Solving ODEs II, 2nd ed. 1996, ch. VII.7
// (after Schiehlen, Multibody Systems Handbook, 1990, and Manning's
// formulation), in the general form of solver/problem.h:
//     M(q) q'' + f(q, q') + G(q)^T lambda = 0,   g(q) = 0,
// q = (beta, Theta, gamma, Phi, delta, Omega, epsilon), the seven body angles;
// six closure constraints (three loops, x and y each); M(q) configuration-
// dependent; f = -(the test set's applied forces: the driving torque mom on
// body 1, the spring c0 between the points D and C on body 3, and the
// velocity-quadratic terms). The multipliers have the test set's sign (it
// writes the same left-hand side). t in [0, 0.03]; the start is the test
// set's consistent position at rest.
#pragma once

#include "model/problem.h"

namespace evas::problems {

class Andrews : public Problem {
 public:
  Andrews();

  int size() const override { return 7; }
  void initial_state(Vec& q, Vec& v) const override;
  void force(double t, const double* q, const double* v, double* f) override;
  void force_jacobian(double t, const double* q, const double* v, SpMat& K, SpMat& C) override;
  const SpMat& jacobian_pattern() const override { return dense_; }
  bool has_mass() const override { return true; }
  void mass(double t, const double* q, SpMat& M) override;
  const SpMat& mass_pattern() const override { return mpat_; }
  int constraint_count() const override { return 6; }
  void constraint(double t, const double* q, const double* v, double* g, double* gv,
                  double* ga) override;
  void constraint_jacobian(double t, const double* q, SpMat& G) override;
  const SpMat& constraint_pattern() const override { return gpat_; }
  std::string constraint_name(int i) const override;
  std::string describe_coordinate(int i) const override;

 private:
  SpMat dense_, mpat_, gpat_;
};

}  // namespace evas::problems
