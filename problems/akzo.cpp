#include "problems/akzo.h"

#include <cmath>

namespace evas::problems {

namespace {

constexpr double k1 = 18.7, k2 = 0.58, k3 = 0.09, k4 = 0.42, kK = 34.4, klA = 3.3, Ks = 115.83,
                 pCO2 = 0.9, H = 737.0;

void akzo_rhs(const double* y, double* f) {
  // sqrt of a negative concentration: the trial state of a failed Newton
  // iterate (the test set's code stops there too)
  if (!(y[1] >= 0.0)) throw RangeError("chemakzo: y2 = " + std::to_string(y[1]) + " < 0");
  const double s2 = std::sqrt(y[1]);
  const double r1 = k1 * std::pow(y[0], 4) * s2, r2 = k2 * y[2] * y[3], r3 = k2 / kK * y[0] * y[4],
               r4 = k3 * y[0] * y[3] * y[3], r5 = k4 * y[5] * y[5] * s2,
               fin = klA * (pCO2 / H - y[1]);
  f[0] = -2.0 * r1 + r2 - r3 - r4;
  f[1] = -0.5 * r1 - r4 - 0.5 * r5 + fin;
  f[2] = r1 - r2 + r3;
  f[3] = -r2 + r3 - 2.0 * r4;
  f[4] = r2 - r3 + r5;
  f[5] = Ks * y[0] * y[3] - y[5];
}

}  // namespace

Mat Akzo::mass() const {
  Mat M = Mat::Identity(6, 6);
  M(5, 5) = 0.0;
  return M;
}

void Akzo::rhs(double t, const double* y, double* f) {
  (void)t;
  akzo_rhs(y, f);
}

void Akzo::rhs_jacobian(double t, const double* y, Mat& J) {
  (void)t;
  if (!(y[1] > 0.0)) throw RangeError("chemakzo: y2 = " + std::to_string(y[1]) + " <= 0");
  const double s2 = std::sqrt(y[1]);
  // the rates' derivatives: dr[k][j] = d r_{k+1} / d y_{j+1}
  double dr[5][6] = {};
  dr[0][0] = 4.0 * k1 * std::pow(y[0], 3) * s2;
  dr[0][1] = 0.5 * k1 * std::pow(y[0], 4) / s2;
  dr[1][2] = k2 * y[3];
  dr[1][3] = k2 * y[2];
  dr[2][0] = k2 / kK * y[4];
  dr[2][4] = k2 / kK * y[0];
  dr[3][0] = k3 * y[3] * y[3];
  dr[3][3] = 2.0 * k3 * y[0] * y[3];
  dr[4][1] = 0.5 * k4 * y[5] * y[5] / s2;
  dr[4][5] = 2.0 * k4 * y[5] * s2;
  // f = C r (+ Fin in f2, + the sixth row): C's rows
  const double C[5][5] = {{-2.0, 1.0, -1.0, -1.0, 0.0},
                          {-0.5, 0.0, 0.0, -1.0, -0.5},
                          {1.0, -1.0, 1.0, 0.0, 0.0},
                          {0.0, -1.0, 1.0, -2.0, 0.0},
                          {0.0, 1.0, -1.0, 0.0, 1.0}};
  J.setZero(6, 6);
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 6; ++j)
      for (int k = 0; k < 5; ++k) J(i, j) += C[i][k] * dr[k][j];
  J(1, 1) -= klA;
  J(5, 0) = Ks * y[3];
  J(5, 3) = Ks * y[0];
  J(5, 5) = -1.0;
}

void Akzo::initial(Vec& y, Vec& yp) const {
  y.resize(6);
  y << 0.444, 0.00123, 0.0, 0.007, 0.0, Ks * 0.444 * 0.007;
  yp.resize(6);
  akzo_rhs(y.data(), yp.data());
  // the algebraic y6 = Ks y1 y4 moves with y1 and y4
  yp(5) = Ks * (yp(0) * y(3) + y(0) * yp(3));
}

std::string Akzo::component_name(int i) const {
  static const char* names[] = {"y1 [FLB]", "y2 [CO2]", "y3 [FLBT]",
                                "y4 [ZHU]", "y5 [ZLA]", "y6 [FLB.ZHU]"};
  return i >= 0 && i < 6 ? names[i] : ImplicitDae::component_name(i);
}

}  // namespace evas::problems
