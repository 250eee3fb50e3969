#include "problems/slider_crank.h"

#include <cmath>
#include <unsupported/Eigen/AutoDiff>

namespace evas::problems {

namespace {

// The test set's data (RESMBS), pi as it writes it
constexpr double kPi = 3.1415927;
constexpr double M2 = 0.151104, M3 = 0.075552, L1 = 0.15, L2 = 0.30, J1 = 0.002727,
                 J2 = 0.0045339259, EE = 0.20e12, BB = 0.0080, HH = 0.0080, RHO = 7870.0,
                 OMEGA = 150.0;
constexpr double FACM = RHO * BB * HH * L2, FACK = EE * BB * HH / L2, FACB = BB * HH * L2;

struct Rod {
  double MQ[4][4] = {}, KQ[4][4] = {}, BQ[4][4] = {};
  double c1[4] = {}, c2[4] = {}, c12[4] = {}, c21[4] = {};
  Rod() {
    MQ[0][0] = MQ[1][1] = FACM / 2.0;
    MQ[2][2] = 8.0 * FACM;
    MQ[2][3] = MQ[3][2] = FACM;
    MQ[3][3] = 2.0 * FACM;
    const double hl2 = (HH / L2) * (HH / L2), pi4 = kPi * kPi * kPi * kPi;
    KQ[0][0] = FACK * pi4 / 24.0 * hl2;
    KQ[1][1] = FACK * pi4 * (2.0 / 3.0) * hl2;
    KQ[2][2] = 16.0 / 3.0 * FACK;
    KQ[2][3] = KQ[3][2] = -8.0 / 3.0 * FACK;
    KQ[3][3] = 7.0 / 3.0 * FACK;
    const double pi3 = kPi * kPi * kPi;
    BQ[0][2] = -16.0 * FACB / pi3;
    BQ[0][3] = FACB * (8.0 / pi3 - 1.0 / kPi);
    BQ[1][3] = FACB * 0.5 / kPi;
    BQ[2][0] = -BQ[0][2];
    BQ[3][0] = -BQ[0][3];
    BQ[3][1] = -BQ[1][3];
    c1[2] = 2.0 / 3.0 * FACB;
    c1[3] = 1.0 / 6.0 * FACB;
    c2[0] = 2.0 * FACB / kPi;
    c12[2] = L2 * FACB / 3.0;
    c12[3] = L2 * FACB / 6.0;
    c21[0] = L2 * FACB / kPi;
    c21[1] = -L2 * FACB * 0.5 / kPi;
  }
};

const Rod& rod() {
  static const Rod r;
  return r;
}

// The applied and velocity-dependent forces F(p, v) of RESMBS (GRAV = 0,
// linear stiffness, no damping); f = -F.
template <class T>
void applied(const T* p, const T* v, T* F) {
  using std::cos;
  using std::sin;
  const Rod& r = rod();
  const T cp12 = cos(p[0] - p[1]), sp12 = sin(p[0] - p[1]);
  const T V1 = v[0], V2 = v[1];
  const T* q = p + 3;
  const T* qd = v + 3;
  T c1q(0.0), c2q(0.0), c1qd(0.0), c2qd(0.0), c12qd(0.0), qdMq(0.0), qdBqd(0.0);
  T MQq[4], KQq[4], BQqd[4];
  for (int i = 0; i < 4; ++i) {
    c1q += r.c1[i] * q[i];
    c2q += r.c2[i] * q[i];
    c1qd += r.c1[i] * qd[i];
    c2qd += r.c2[i] * qd[i];
    c12qd += r.c12[i] * qd[i];
    MQq[i] = T(0.0);
    KQq[i] = T(0.0);
    BQqd[i] = T(0.0);
    for (int j = 0; j < 4; ++j) {
      MQq[i] += r.MQ[i][j] * q[j];
      KQq[i] += r.KQ[i][j] * q[j];
      BQqd[i] += r.BQ[i][j] * qd[j];
    }
  }
  for (int i = 0; i < 4; ++i) {
    qdMq += qd[i] * MQq[i];
    qdBqd += qd[i] * BQqd[i];
  }
  F[0] = -0.5 * L1 * L2 * M2 * V2 * V2 * sp12 + RHO * L1 * V2 * V2 * (-sp12 * c1q + cp12 * c2q) -
         2.0 * RHO * L1 * V2 * (cp12 * c1qd + sp12 * c2qd);
  F[1] = 0.5 * L1 * L2 * M2 * V1 * V1 * sp12 + RHO * L1 * V1 * V1 * (sp12 * c1q - cp12 * c2q) -
         2.0 * RHO * V2 * c12qd - 2.0 * V2 * qdMq - RHO * qdBqd;
  F[2] = T(0.0);
  for (int i = 0; i < 4; ++i)
    F[3 + i] = V2 * V2 * MQq[i] +
               RHO * (V2 * V2 * r.c12[i] + L1 * V1 * V1 * (cp12 * r.c1[i] + sp12 * r.c2[i]) +
                      2.0 * V2 * BQqd[i]) -
               KQq[i];
}

SpMat pattern(int rows, int cols) {
  std::vector<Triplet> t;
  for (int c = 0; c < cols; ++c)
    for (int r = 0; r < rows; ++r) t.emplace_back(r, c, 0.0);
  SpMat A(rows, cols);
  A.setFromTriplets(t.begin(), t.end());
  A.makeCompressed();
  return A;
}

}  // namespace

SliderCrank::SliderCrank() : dense_(pattern(7, 7)), mpat_(pattern(7, 7)), gpat_(pattern(3, 7)) {}

void SliderCrank::initial_state(Vec& q, Vec& v) const {
  // the report's consistent initial value (release 2.4, section II.19)
  q.resize(7);
  v.resize(7);
  // (x3 and phi2' as the constraints give them from the others: the report
  // prints x3 = 0.450016933 to nine digits)
  const double q4 = 0.169327969e-4, v1 = 0.150000000e3;
  q << 0.0, 0.0, L1 + L2 + q4, 0.0, 0.0, 0.103339863e-4, q4;
  v << v1, -L1 * v1 / (L2 + q4), -0.2689386719979040e-5, 0.4448961125815990, 0.4634339319238670e-2,
      -0.1785910760000550e-5, -0.2689386719979040e-5;
}

void SliderCrank::force(double t, const double* q, const double* v, double* f) {
  (void)t;
  ++counters.f_evals;
  applied(q, v, f);
  for (int i = 0; i < 7; ++i) f[i] = -f[i];
}

void SliderCrank::force_jacobian(double t, const double* q, const double* v, SpMat& K, SpMat& C) {
  (void)t;
  ++counters.jac_evals;
  using D = Eigen::AutoDiffScalar<Eigen::Matrix<double, 14, 1>>;
  D p[7], w[7], F[7];
  for (int i = 0; i < 7; ++i) {
    p[i] = D(q[i], 14, i);
    w[i] = D(v[i], 14, 7 + i);
  }
  applied(p, w, F);
  for (int r = 0; r < 7; ++r)
    for (int c = 0; c < 7; ++c) {
      K.coeffRef(r, c) = -F[r].derivatives()(c);
      C.coeffRef(r, c) = -F[r].derivatives()(7 + c);
    }
}

void SliderCrank::mass(double t, const double* q, SpMat& M) {
  (void)t;
  const Rod& r = rod();
  const double cp12 = std::cos(q[0] - q[1]), sp12 = std::sin(q[0] - q[1]);
  const double* e = q + 3;
  double c1q = 0.0, c2q = 0.0, c12q = 0.0, qMq = 0.0, qB[4] = {};
  for (int i = 0; i < 4; ++i) {
    c1q += r.c1[i] * e[i];
    c2q += r.c2[i] * e[i];
    c12q += r.c12[i] * e[i];
    for (int j = 0; j < 4; ++j) {
      qMq += e[i] * r.MQ[i][j] * e[j];
      qB[i] += e[j] * r.BQ[j][i];
    }
  }
  Eigen::Matrix<double, 7, 7> A = Eigen::Matrix<double, 7, 7>::Zero();
  A(0, 0) = J1 + M2 * L1 * L1;
  A(0, 1) = 0.5 * L1 * L2 * M2 * cp12 + RHO * L1 * (sp12 * c2q + cp12 * c1q);
  A(1, 1) = J2 + qMq + 2.0 * RHO * c12q;
  A(2, 2) = M3;
  for (int i = 0; i < 4; ++i) {
    A(0, 3 + i) = RHO * L1 * (-sp12 * r.c1[i] + cp12 * r.c2[i]);
    A(1, 3 + i) = RHO * r.c21[i] + RHO * qB[i];
    for (int j = 0; j < 4; ++j) A(3 + j, 3 + i) = r.MQ[j][i];
  }
  for (int c = 0; c < 7; ++c)
    for (int rr = 0; rr < c; ++rr) A(c, rr) = A(rr, c);  // symmetric
  for (int c = 0; c < 7; ++c)
    for (int rr = 0; rr < 7; ++rr) M.coeffRef(rr, c) = A(rr, c);
}

void SliderCrank::constraint(double t, const double* q, const double* v, double* g, double* gv,
                             double* ga) {
  const double c1 = std::cos(q[0]), s1 = std::sin(q[0]), c2 = std::cos(q[1]), s2 = std::sin(q[1]),
               l = L2 + q[6];
  if (g) {
    g[0] = L1 * s1 + l * s2;
    g[1] = q[2] - L1 * c1 - l * c2;
    g[2] = q[0] - OMEGA * t;
  }
  if (gv) {
    gv[0] = L1 * c1 * v[0] + l * c2 * v[1] + s2 * v[6];
    gv[1] = L1 * s1 * v[0] + l * s2 * v[1] + v[2] - c2 * v[6];
    gv[2] = v[0] - OMEGA;
  }
  if (ga) {  // (G v)_q v
    ga[0] = -L1 * s1 * v[0] * v[0] - l * s2 * v[1] * v[1] + 2.0 * c2 * v[1] * v[6];
    ga[1] = L1 * c1 * v[0] * v[0] + l * c2 * v[1] * v[1] + 2.0 * s2 * v[1] * v[6];
    ga[2] = 0.0;
  }
}

void SliderCrank::constraint_jacobian(double t, const double* q, SpMat& G) {
  (void)t;
  const double c1 = std::cos(q[0]), s1 = std::sin(q[0]), c2 = std::cos(q[1]), s2 = std::sin(q[1]),
               l = L2 + q[6];
  G.coeffs().setZero();
  G.coeffRef(0, 0) = L1 * c1;
  G.coeffRef(0, 1) = l * c2;
  G.coeffRef(0, 6) = s2;
  G.coeffRef(1, 0) = L1 * s1;
  G.coeffRef(1, 1) = l * s2;
  G.coeffRef(1, 2) = 1.0;
  G.coeffRef(1, 6) = -c2;
  G.coeffRef(2, 0) = 1.0;
}

std::string SliderCrank::constraint_name(int i) const {
  static const char* names[] = {"loop_y", "loop_x", "crank_speed"};
  return i >= 0 && i < 3 ? names[i] : Problem::constraint_name(i);
}

std::string SliderCrank::describe_coordinate(int i) const {
  static const char* names[] = {"phi1", "phi2", "x3", "q1", "q2", "q3", "q4"};
  return i >= 0 && i < 7 ? names[i] : Problem::describe_coordinate(i);
}

}  // namespace evas::problems
