// A planar pendulum in Cartesian coordinates, the classic index-3 test DAE
// (Hairer & Wanner, Solving ODEs II, 2nd ed. 1996, ch. VII.1):
// q = (x, y), y upwards, a point mass m on a massless rod of length L,
//     m x'' + 2 lambda x = 0,
//     m y'' + m g0 + 2 lambda y = 0,        g(q) = x^2 + y^2 - L^2 = 0,
// i.e. M = m I, f = (0, m g0), G = (2x, 2y), G v = 2(x vx + y vy) (g_t = 0),
// ga = (G v)_q v = 2(vx^2 + vy^2).
//
// Exact solution for release from rest at angle theta0 (from the downward
// vertical, x = L sin theta, y = -L cos theta; theta'' = -(g0/L) sin theta):
// with k = sin(theta0/2), omega0 = sqrt(g0/L), K = K(k) the complete elliptic
// integral of the first kind and u = K - omega0 t,
//     sin(theta/2) = k sn(u, k),   theta' = -2 k omega0 cn(u, k),
// since d/dt sin(theta/2) = (1/2) cos(theta/2) theta' = -k omega0 cn dn and
// cos(theta/2) = dn(u, k) (Lawden, Elliptic Functions and Applications,
// Springer 1989, the simple pendulum; sn(K) = 1 gives theta(0) = theta0, theta'(0) = 0).
// Period 4 K(k)/omega0. The rod force on the mass is -G^T lambda = -2 lambda q,
// of magnitude 2 lambda L towards the pivot, and the radial balance
// T = m (g0 cos theta + L theta'^2) gives lambda = T / (2 L).
//
// M = m I is reported as a mass matrix unless m = 1 (then qdd + f + G^T
// lambda = 0 holds as it stands and has_mass() is false).
#pragma once

#include "model/problem.h"

namespace evas::problems {

class Pendulum : public Problem {
 public:
  /// Throws InputError unless mass > 0, length > 0, gravity > 0 and |theta0| < pi.
  Pendulum(double mass, double length, double gravity, double theta0);

  int size() const override { return 2; }
  void initial_state(Vec& q, Vec& v) const override;
  void force(double t, const double* q, const double* v, double* f) override;
  void force_jacobian(double t, const double* q, const double* v, SpMat& K, SpMat& C) override;
  const SpMat& jacobian_pattern() const override { return diag_; }
  bool has_mass() const override { return m_ != 1.0; }
  void mass(double t, const double* q, SpMat& M) override;
  bool mass_constant() const override { return true; }
  const SpMat& mass_pattern() const override { return diag_; }
  int constraint_count() const override { return 1; }
  void constraint(double t, const double* q, const double* v, double* g, double* gv,
                  double* ga) override;
  void constraint_jacobian(double t, const double* q, SpMat& G) override;
  const SpMat& constraint_pattern() const override { return row_; }
  std::string constraint_name(int i) const override;

  /// Exact angle and angular velocity at t (see above).
  void exact_angle(double t, double& theta, double& theta_dot) const;
  /// Exact state and multiplier at t.
  void exact(double t, Vec& q, Vec& v, double& lambda) const;
  /// Period of the swing [s].
  double period() const;

 private:
  double m_, L_, g0_, theta0_;
  SpMat diag_, row_;
};

}  // namespace evas::problems
