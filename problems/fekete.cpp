#include "problems/fekete.h"

#include <cmath>

namespace evas::problems {

namespace {

constexpr double kAlpha = 0.5;
constexpr int N = Fekete::kPoints;

// d = p_i - p_j; returns |d|^2
double separation(const double* q, int i, int j, double d[3]) {
  for (int k = 0; k < 3; ++k) d[k] = q[3 * i + k] - q[3 * j + k];
  return d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
}

}  // namespace

Fekete::Fekete() {
  std::vector<Triplet> t;
  for (int c = 0; c < 3 * N; ++c)
    for (int r = 0; r < 3 * N; ++r) t.emplace_back(r, c, 0.0);
  kpat_.resize(3 * N, 3 * N);
  kpat_.setFromTriplets(t.begin(), t.end());
  kpat_.makeCompressed();
  t.clear();
  for (int i = 0; i < N; ++i)
    for (int k = 0; k < 3; ++k) t.emplace_back(i, 3 * i + k, 0.0);
  gpat_.resize(N, 3 * N);
  gpat_.setFromTriplets(t.begin(), t.end());
  gpat_.makeCompressed();
}

void Fekete::initial_state(Vec& q, Vec& v) const {
  const double pi = 3.14159265358979323846;
  q.resize(3 * N);
  v = Vec::Zero(3 * N);
  // four circles of latitude beta, the points at longitudes alpha
  auto put = [&](int i, double alpha, double beta) {
    q(3 * i) = std::cos(alpha) * std::cos(beta);
    q(3 * i + 1) = std::sin(alpha) * std::cos(beta);
    q(3 * i + 2) = std::sin(beta);
  };
  for (int i = 1; i <= 3; ++i) put(i - 1, 2.0 * pi * i / 3.0 + pi / 13.0, 3.0 * pi / 8.0);
  for (int i = 4; i <= 10; ++i) put(i - 1, 2.0 * pi * (i - 3) / 7.0 + pi / 29.0, pi / 8.0);
  for (int i = 11; i <= 16; ++i) put(i - 1, 2.0 * pi * (i - 10) / 6.0 + pi / 7.0, -2.0 * pi / 15.0);
  for (int i = 17; i <= 20; ++i)
    put(i - 1, 2.0 * pi * (i - 17) / 4.0 + pi / 17.0, -3.0 * pi / 10.0);
}

void Fekete::force(double t, const double* q, const double* v, double* f) {
  (void)t;
  ++counters.f_evals;
  for (int i = 0; i < 3 * N; ++i) f[i] = kAlpha * v[i];
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j) {
      if (i == j) continue;
      double d[3];
      const double r2 = separation(q, i, j, d);
      for (int k = 0; k < 3; ++k) f[3 * i + k] -= d[k] / r2;
    }
}

void Fekete::force_jacobian(double t, const double* q, const double* v, SpMat& K, SpMat& C) {
  (void)t;
  (void)v;
  ++counters.jac_evals;
  K.coeffs().setZero();
  C.coeffs().setZero();
  for (int i = 0; i < 3 * N; ++i) C.coeffRef(i, i) = kAlpha;
  // d/dd (d / |d|^2) = I / |d|^2 - 2 d d^T / |d|^4 =: A; f_i = ... - sum_j d_ij / |d_ij|^2
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j) {
      if (i == j) continue;
      double d[3];
      const double r2 = separation(q, i, j, d);
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) {
          const double A = ((a == b ? 1.0 : 0.0) - 2.0 * d[a] * d[b] / r2) / r2;
          K.coeffRef(3 * i + a, 3 * i + b) -= A;
          K.coeffRef(3 * i + a, 3 * j + b) += A;
        }
    }
}

void Fekete::constraint(double t, const double* q, const double* v, double* g, double* gv,
                        double* ga) {
  (void)t;
  for (int i = 0; i < N; ++i) {
    const double* p = q + 3 * i;
    if (g) g[i] = p[0] * p[0] + p[1] * p[1] + p[2] * p[2] - 1.0;
    if (gv) gv[i] = 2.0 * (p[0] * v[3 * i] + p[1] * v[3 * i + 1] + p[2] * v[3 * i + 2]);
    if (ga) {  // (G v)_q v = 2 |v_i|^2
      const double* w = v + 3 * i;
      ga[i] = 2.0 * (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    }
  }
}

void Fekete::constraint_jacobian(double t, const double* q, SpMat& G) {
  (void)t;
  for (int i = 0; i < N; ++i)
    for (int k = 0; k < 3; ++k) G.coeffRef(i, 3 * i + k) = 2.0 * q[3 * i + k];
}

std::string Fekete::constraint_name(int i) const { return "on_sphere" + std::to_string(i + 1); }

std::string Fekete::describe_coordinate(int i) const {
  if (i < 0 || i >= 3 * N) return Problem::describe_coordinate(i);
  static const char* axis[] = {"x", "y", "z"};
  return "p" + std::to_string(i / 3 + 1) + "." + axis[i % 3];
}

}  // namespace evas::problems
