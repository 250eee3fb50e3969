// The flexible slider crank of the Test Set for IVP Solvers (F. Mazzia, C.
// Magherini, University of Bari, release 2.4, 2008; problem "crank", after B.
// Simeon, "Modelling a flexible slider crank mechanism by a mixed system of
// DAEs and PDEs", Math. Modelling of Systems 2 (1996) 1-18): a rigid crank
// driven at constant speed, an elastic connecting rod (two lateral modes and
// two longitudinal nodal coordinates of a Galerkin model) and a slider, in the
// general form of model/problem.h:
//     M(p) p'' + f(p, p') + G(p)^T lambda = 0,   g(t, p) = 0,
// p = (phi1, phi2, x3, q1, q2, q3, q4): crank angle, rod angle, slider
// position, elastic coordinates; the constraints close the loop and prescribe
// the crank angle (g3 = phi1 - Omega t, Omega = 150 rad/s). M, f (= -F) and G
// are the test set's (its routine RESMBS: linear stiffness, no damping, no
// gravity, pi as its 3.1415927); the multipliers have its sign. The test set
// states the problem in its index-2 form (G v - g_t = 0). t in [0, 0.1]; the
// start is the report's consistent "smooth" initial value.
#pragma once

#include "model/problem.h"

namespace evas::problems {

class SliderCrank : public Problem {
 public:
  SliderCrank();

  int size() const override { return 7; }
  void initial_state(Vec& q, Vec& v) const override;
  void force(double t, const double* q, const double* v, double* f) override;
  /// K, C from f by forward-mode automatic differentiation (Eigen's
  /// AutoDiffScalar): exact to rounding, checked against differences.
  void force_jacobian(double t, const double* q, const double* v, SpMat& K, SpMat& C) override;
  const SpMat& jacobian_pattern() const override { return dense_; }
  bool has_mass() const override { return true; }
  void mass(double t, const double* q, SpMat& M) override;
  const SpMat& mass_pattern() const override { return mpat_; }
  int constraint_count() const override { return 3; }
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
