#include "problems/car_axis.h"

#include <cmath>

namespace evas::problems {

namespace {

constexpr double kEps = 1e-2, kMass = 10.0, kL = 1.0, kL0 = 0.5, kR = 0.1, kW = 10.0, kG = 1.0;

SpMat pattern(int rows, int cols, bool diagonal) {
  std::vector<Triplet> t;
  for (int c = 0; c < cols; ++c)
    for (int r = 0; r < rows; ++r)
      if (!diagonal || r == c) t.emplace_back(r, c, 0.0);
  SpMat A(rows, cols);
  A.setFromTriplets(t.begin(), t.end());
  A.makeCompressed();
  return A;
}

// Spring of rest length L0 along p: force (L0 - |p|) p / |p| on the wheel and
// its Jacobian d/dp = (L0/|p| - 1) I - L0 p p^T / |p|^3.
void spring(double px, double py, double F[2], double J[2][2]) {
  const double L = std::hypot(px, py), s = kL0 / L - 1.0, c = kL0 / (L * L * L);
  F[0] = s * px;
  F[1] = s * py;
  J[0][0] = s - c * px * px;
  J[0][1] = -c * px * py;
  J[1][0] = J[0][1];
  J[1][1] = s - c * py * py;
}

}  // namespace

CarAxis::CarAxis() : k_(kMass * kEps * kEps / 2.0) {
  kpat_ = pattern(4, 4, false);
  mpat_ = pattern(4, 4, true);
  gpat_ = pattern(2, 4, false);
}

void CarAxis::initial_state(Vec& q, Vec& v) const {
  q.resize(4);
  v.resize(4);
  q << 0.0, kL0, kL, kL0;
  v << -kL0 / kL, 0.0, -kL0 / kL, 0.0;
}

void CarAxis::bump(double t, double& xb, double& yb, double& xbd, double& ybd, double& xbdd,
                   double& ybdd) const {
  yb = kR * std::sin(kW * t);
  ybd = kR * kW * std::cos(kW * t);
  ybdd = -kW * kW * yb;
  xb = std::sqrt(kL * kL - yb * yb);
  xbd = -yb * ybd / xb;
  xbdd = -(ybd * ybd + yb * ybdd) / xb - (yb * ybd) * (yb * ybd) / (xb * xb * xb);
}

void CarAxis::force(double t, const double* q, const double* v, double* f) {
  (void)v;
  ++counters.f_evals;
  double xb, yb, xbd, ybd, xbdd, ybdd, Fl[2], Fr[2], J[2][2];
  bump(t, xb, yb, xbd, ybd, xbdd, ybdd);
  spring(q[0], q[1], Fl, J);
  spring(q[2] - xb, q[3] - yb, Fr, J);
  f[0] = -Fl[0];
  f[1] = -Fl[1] + k_ * kG;
  f[2] = -Fr[0];
  f[3] = -Fr[1] + k_ * kG;
}

void CarAxis::force_jacobian(double t, const double* q, const double* v, SpMat& K, SpMat& C) {
  (void)v;
  ++counters.jac_evals;
  double xb, yb, xbd, ybd, xbdd, ybdd, F[2], Jl[2][2], Jr[2][2];
  bump(t, xb, yb, xbd, ybd, xbdd, ybdd);
  spring(q[0], q[1], F, Jl);
  spring(q[2] - xb, q[3] - yb, F, Jr);
  K.coeffs().setZero();
  C.coeffs().setZero();
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 2; ++c) {
      K.coeffRef(r, c) = -Jl[r][c];
      K.coeffRef(2 + r, 2 + c) = -Jr[r][c];
    }
}

void CarAxis::mass(double t, const double* q, SpMat& M) {
  (void)t;
  (void)q;
  for (int i = 0; i < 4; ++i) M.coeffRef(i, i) = k_;
}

void CarAxis::constraint(double t, const double* q, const double* v, double* g, double* gv,
                         double* ga) {
  double xb, yb, xbd, ybd, xbdd, ybdd;
  bump(t, xb, yb, xbd, ybd, xbdd, ybdd);
  const double dx = q[0] - q[2], dy = q[1] - q[3];
  if (g) {
    g[0] = q[0] * xb + q[1] * yb;
    g[1] = dx * dx + dy * dy - kL * kL;
  }
  if (!gv && !ga) return;
  const double du = v[0] - v[2], dv = v[1] - v[3];
  if (gv) {
    gv[0] = xb * v[0] + yb * v[1] + q[0] * xbd + q[1] * ybd;  // G v + g_t
    gv[1] = 2.0 * (dx * du + dy * dv);
  }
  if (ga) {  // (G v)_q v + 2 g_tq v + g_tt
    ga[0] = 2.0 * (xbd * v[0] + ybd * v[1]) + q[0] * xbdd + q[1] * ybdd;
    ga[1] = 2.0 * (du * du + dv * dv);
  }
}

void CarAxis::constraint_jacobian(double t, const double* q, SpMat& G) {
  double xb, yb, xbd, ybd, xbdd, ybdd;
  bump(t, xb, yb, xbd, ybd, xbdd, ybdd);
  const double dx = q[0] - q[2], dy = q[1] - q[3];
  const double row0[4] = {xb, yb, 0.0, 0.0};
  const double row1[4] = {2.0 * dx, 2.0 * dy, -2.0 * dx, -2.0 * dy};
  for (int c = 0; c < 4; ++c) {
    G.coeffRef(0, c) = row0[c];
    G.coeffRef(1, c) = row1[c];
  }
}

std::string CarAxis::constraint_name(int i) const {
  return i == 0 ? "wheel_on_axle" : "axle_length";
}

std::string CarAxis::describe_coordinate(int i) const {
  static const char* names[] = {"xl", "yl", "xr", "yr"};
  return i >= 0 && i < 4 ? names[i] : Problem::describe_coordinate(i);
}

}  // namespace evas::problems
