#include "problems/transistor.h"

#include <cmath>

namespace evas::problems {

namespace {

constexpr double Ub = 6.0, UF = 0.026, a = 0.99, b = 1e-6, R0 = 1000.0, R = 9000.0;
constexpr double C[5] = {1e-6, 2e-6, 3e-6, 4e-6, 5e-6};
constexpr double kPi = 3.14159265358979323846;

// g(x) = b (exp(x / UF) - 1); a diode voltage beyond 30 V (exp(1150)) is a
// failed Newton iterate, not a state of the circuit
double diode(double x, double* slope) {
  if (!(x < 30.0)) throw RangeError("transamp: diode voltage " + std::to_string(x) + " V");
  const double e = std::exp(x / UF);
  if (slope) *slope = b * e / UF;
  return b * (e - 1.0);
}

}  // namespace

Mat Transistor::mass() const {
  Mat M = Mat::Zero(8, 8);
  auto pair = [&](int i, double c) {  // the capacitor between nodes i and i + 1
    M(i, i) = -c;
    M(i, i + 1) = c;
    M(i + 1, i) = c;
    M(i + 1, i + 1) = -c;
  };
  pair(0, C[0]);
  M(2, 2) = -C[1];
  pair(3, C[2]);
  M(5, 5) = -C[3];
  pair(6, C[4]);
  return M;
}

void Transistor::rhs(double t, const double* y, double* f) {
  const double ue = 0.1 * std::sin(200.0 * kPi * t);
  const double g1 = diode(y[1] - y[2], nullptr), g2 = diode(y[4] - y[5], nullptr);
  f[0] = (y[0] - ue) / R0;
  f[1] = y[1] / R + (y[1] - Ub) / R + (1.0 - a) * g1;
  f[2] = y[2] / R - g1;
  f[3] = (y[3] - Ub) / R + a * g1;
  f[4] = y[4] / R + (y[4] - Ub) / R + (1.0 - a) * g2;
  f[5] = y[5] / R - g2;
  f[6] = (y[6] - Ub) / R + a * g2;
  f[7] = y[7] / R;
}

void Transistor::rhs_jacobian(double t, const double* y, Mat& J) {
  (void)t;
  double s1 = 0.0, s2 = 0.0;
  diode(y[1] - y[2], &s1);
  diode(y[4] - y[5], &s2);
  J.setZero(8, 8);
  J(0, 0) = 1.0 / R0;
  J(1, 1) = 2.0 / R + (1.0 - a) * s1;
  J(1, 2) = -(1.0 - a) * s1;
  J(2, 1) = -s1;
  J(2, 2) = 1.0 / R + s1;
  J(3, 1) = a * s1;
  J(3, 2) = -a * s1;
  J(3, 3) = 1.0 / R;
  J(4, 4) = 2.0 / R + (1.0 - a) * s2;
  J(4, 5) = -(1.0 - a) * s2;
  J(5, 4) = -s2;
  J(5, 5) = 1.0 / R + s2;
  J(6, 4) = a * s2;
  J(6, 5) = -a * s2;
  J(6, 6) = 1.0 / R;
  J(7, 7) = 1.0 / R;
}

void Transistor::initial(Vec& y, Vec& yp) const {
  const double u = Ub / (R / R + 1.0);  // Ub / (R2 / R1 + 1), the divider
  y.resize(8);
  y << 0.0, u, u, Ub, u, u, Ub, 0.0;
  yp.resize(8);
  yp << 51.338775, 51.338775, -u / (C[1] * R), -24.9757667, -24.9757667, -u / (C[3] * R),
      -10.00564453, -10.00564453;
}

std::string Transistor::component_name(int i) const {
  return i >= 0 && i < 8 ? "U" + std::to_string(i + 1) + " [V]" : ImplicitDae::component_name(i);
}

}  // namespace evas::problems
