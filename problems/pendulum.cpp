// The Cartesian pendulum and its elliptic-function solution (see pendulum.h).
#include "problems/pendulum.h"

#include <boost/math/special_functions/ellint_1.hpp>
#include <boost/math/special_functions/jacobi_elliptic.hpp>
#include <cmath>

namespace evas::problems {

Pendulum::Pendulum(double mass, double length, double gravity, double theta0)
    : m_(mass), L_(length), g0_(gravity), theta0_(theta0) {
  if (!(mass > 0.0)) throw InputError("pendulum: mass must be > 0");
  if (!(length > 0.0)) throw InputError("pendulum: length must be > 0");
  if (!(gravity > 0.0)) throw InputError("pendulum: gravity must be > 0");
  if (!(std::abs(theta0) < M_PI)) throw InputError("pendulum: |theta0| must be < pi");
  diag_.resize(2, 2);
  diag_.insert(0, 0) = 0.0;
  diag_.insert(1, 1) = 0.0;
  diag_.makeCompressed();
  row_.resize(1, 2);
  row_.insert(0, 0) = 0.0;
  row_.insert(0, 1) = 0.0;
  row_.makeCompressed();
}

void Pendulum::initial_state(Vec& q, Vec& v) const {
  q = Vec(2);
  q << L_ * std::sin(theta0_), -L_ * std::cos(theta0_);
  v = Vec::Zero(2);
}

void Pendulum::force(double, const double*, const double*, double* f) {
  ++counters.f_evals;
  f[0] = 0.0;
  f[1] = m_ * g0_;
}

void Pendulum::force_jacobian(double, const double*, const double*, SpMat& K, SpMat& C) {
  ++counters.jac_evals;
  K.coeffs().setZero();
  C.coeffs().setZero();
}

void Pendulum::mass(double, const double*, SpMat& M) { M.coeffs().setConstant(m_); }

void Pendulum::constraint(double, const double* q, const double* v, double* g, double* gv,
                          double* ga) {
  if (g) g[0] = q[0] * q[0] + q[1] * q[1] - L_ * L_;
  if (gv) gv[0] = 2.0 * (q[0] * v[0] + q[1] * v[1]);
  if (ga) ga[0] = 2.0 * (v[0] * v[0] + v[1] * v[1]);
}

void Pendulum::constraint_jacobian(double, const double* q, SpMat& G) {
  G.valuePtr()[0] = 2.0 * q[0];  // column-major: (0, 0) then (0, 1)
  G.valuePtr()[1] = 2.0 * q[1];
}

std::string Pendulum::constraint_name(int) const { return "rod"; }

void Pendulum::exact_angle(double t, double& theta, double& theta_dot) const {
  const double k = std::sin(0.5 * theta0_), w0 = std::sqrt(g0_ / L_);
  if (k == 0.0) {
    theta = theta_dot = 0.0;
    return;
  }
  const double K = boost::math::ellint_1(std::abs(k));
  double cn = 0.0, dn = 0.0;
  const double sn = boost::math::jacobi_elliptic(std::abs(k), K - w0 * t, &cn, &dn);
  theta = 2.0 * std::asin(k * sn);
  theta_dot = -2.0 * k * w0 * cn;
}

void Pendulum::exact(double t, Vec& q, Vec& v, double& lambda) const {
  double th = 0.0, thd = 0.0;
  exact_angle(t, th, thd);
  q = Vec(2);
  v = Vec(2);
  q << L_ * std::sin(th), -L_ * std::cos(th);
  v << L_ * std::cos(th) * thd, L_ * std::sin(th) * thd;
  lambda = m_ * (g0_ * std::cos(th) + L_ * thd * thd) / (2.0 * L_);
}

double Pendulum::period() const {
  const double k = std::abs(std::sin(0.5 * theta0_));
  return 4.0 * boost::math::ellint_1(k) / std::sqrt(g0_ / L_);
}

}  // namespace evas::problems
