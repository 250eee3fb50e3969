#include "problems/andrews.h"

#include <cmath>

namespace evas::problems {

namespace {

// Masses [kg], moments of inertia [kg m^2], geometry [m], spring and torque:
// the test set's problem description (Hairer & Wanner 1996, Table VII.7.1).
constexpr double m1 = .04325, m2 = .00365, m3 = .02373, m4 = .00706, m5 = .07050, m6 = .00706,
                 m7 = .05498;
constexpr double i1 = 2.194e-6, i2 = 4.410e-7, i3 = 5.255e-6, i4 = 5.667e-7, i5 = 1.169e-5,
                 i6 = 5.667e-7, i7 = 1.912e-5;
constexpr double xa = -.06934, ya = -.00227, xb = -.03635, yb = .03273, xc = .014, yc = .072;
constexpr double d = 28e-3, da = 115e-4, e = 2e-2, ea = 1421e-5, rr = 7e-3, ra = 92e-5;
constexpr double ss = 35e-3, sa = 1874e-5, sb = 1043e-5, sc = 18e-3, sd = 2e-2;
constexpr double ta = 2308e-5, tb = 916e-5, u = 4e-2, ua = 1228e-5, ub = 449e-5;
constexpr double zf = 2e-2, zt = 4e-2, fa = 1421e-5;
constexpr double mom = 0.033, c0 = 4530.0, lo = 0.07785;

// coefficients of the velocity-quadratic terms
constexpr double A2 = m2 * da * rr, A4 = m4 * zt * (e - ea), A6 = m6 * u * (zf - fa);

enum { BE, TH, GA, PH, DE, OM, EP };

SpMat pattern(int rows, int cols, const std::vector<std::pair<int, int>>& entries) {
  std::vector<Triplet> t;
  for (const auto& rc : entries) t.emplace_back(rc.first, rc.second, 0.0);
  SpMat A(rows, cols);
  A.setFromTriplets(t.begin(), t.end());
  A.makeCompressed();
  return A;
}

// The spring between D (on body 3, angle gamma) and the fixed point C:
// generalised force Q = -dV/dgamma, V = c0 (L - lo)^2 / 2, and dQ/dgamma.
void spring(double gamma, double& Q, double& dQ) {
  const double sg = std::sin(gamma), cg = std::cos(gamma);
  const double x = sd * cg + sc * sg + xb - xc, y = sd * sg - sc * cg + yb - yc;
  const double a = -sd * sg + sc * cg, b = sd * cg + sc * sg;  // d(x, y)/dgamma
  const double L = std::hypot(x, y), s = x * a + y * b;        // s = L dL/dgamma
  Q = -c0 * (1.0 - lo / L) * s;
  const double ds = a * a + b * b - x * b + y * a;  // d(x, y)/dgamma^2 = (-b, a)
  dQ = -c0 * (lo * s * s / (L * L * L) + (1.0 - lo / L) * ds);
}

// Sines and cosines of the angles (and sums) the closure loops use.
struct Angles {
  double sbe, cbe, sbt, cbt, sga, cga, spd, cpd, sde, cde, soe, coe, sep, cep;
  explicit Angles(const double* q)
      : sbe(std::sin(q[BE])),
        cbe(std::cos(q[BE])),
        sbt(std::sin(q[BE] + q[TH])),
        cbt(std::cos(q[BE] + q[TH])),
        sga(std::sin(q[GA])),
        cga(std::cos(q[GA])),
        spd(std::sin(q[PH] + q[DE])),
        cpd(std::cos(q[PH] + q[DE])),
        sde(std::sin(q[DE])),
        cde(std::cos(q[DE])),
        soe(std::sin(q[OM] + q[EP])),
        coe(std::cos(q[OM] + q[EP])),
        sep(std::sin(q[EP])),
        cep(std::cos(q[EP])) {}
};

}  // namespace

Andrews::Andrews() {
  std::vector<std::pair<int, int>> all, m, g;
  for (int c = 0; c < 7; ++c)
    for (int r = 0; r < 7; ++r) all.emplace_back(r, c);
  for (int k : {BE, TH, GA, PH, DE, OM, EP}) m.emplace_back(k, k);
  for (auto p : {std::pair<int, int>{BE, TH}, {PH, DE}, {OM, EP}}) {
    m.emplace_back(p.first, p.second);
    m.emplace_back(p.second, p.first);
  }
  const int cols[3][2] = {{GA, GA}, {PH, DE}, {OM, EP}};  // each loop: beta, Theta + these
  for (int loop = 0; loop < 3; ++loop)
    for (int r = 2 * loop; r < 2 * loop + 2; ++r) {
      g.emplace_back(r, BE);
      g.emplace_back(r, TH);
      g.emplace_back(r, cols[loop][0]);
      if (cols[loop][1] != cols[loop][0]) g.emplace_back(r, cols[loop][1]);
    }
  dense_ = pattern(7, 7, all);
  mpat_ = pattern(7, 7, m);
  gpat_ = pattern(6, 7, g);
}

void Andrews::initial_state(Vec& q, Vec& v) const {
  q.resize(7);
  q << -0.0617138900142764496358948458001, 0.0, 0.455279819163070380255912382449,
      0.222668390165885884674473185609, 0.487364979543842550225598953530,
      -0.222668390165885884674473185609, 1.23054744454982119249735015568;
  v = Vec::Zero(7);
}

void Andrews::force(double t, const double* q, const double* v, double* f) {
  (void)t;
  ++counters.f_evals;
  double Q = 0.0, dQ = 0.0;
  spring(q[GA], Q, dQ);
  const double sth = std::sin(q[TH]), cph = std::cos(q[PH]), com = std::cos(q[OM]);
  // applied forces (the test set's right-hand side), f = -them
  f[BE] = -(mom - A2 * v[TH] * (v[TH] + 2.0 * v[BE]) * sth);
  f[TH] = -(A2 * v[BE] * v[BE] * sth);
  f[GA] = -Q;
  f[PH] = -(A4 * v[DE] * v[DE] * cph);
  f[DE] = A4 * v[PH] * (v[PH] + 2.0 * v[DE]) * cph;
  f[OM] = A6 * v[EP] * v[EP] * com;
  f[EP] = -(A6 * v[OM] * (v[OM] + 2.0 * v[EP]) * com);
}

void Andrews::force_jacobian(double t, const double* q, const double* v, SpMat& K, SpMat& C) {
  (void)t;
  ++counters.jac_evals;
  K.coeffs().setZero();
  C.coeffs().setZero();
  double Q = 0.0, dQ = 0.0;
  spring(q[GA], Q, dQ);
  const double sth = std::sin(q[TH]), cth = std::cos(q[TH]);
  const double sph = std::sin(q[PH]), cph = std::cos(q[PH]);
  const double som = std::sin(q[OM]), com = std::cos(q[OM]);
  K.coeffRef(BE, TH) = A2 * v[TH] * (v[TH] + 2.0 * v[BE]) * cth;
  C.coeffRef(BE, TH) = A2 * (2.0 * v[TH] + 2.0 * v[BE]) * sth;
  C.coeffRef(BE, BE) = A2 * 2.0 * v[TH] * sth;
  K.coeffRef(TH, TH) = -A2 * v[BE] * v[BE] * cth;
  C.coeffRef(TH, BE) = -2.0 * A2 * v[BE] * sth;
  K.coeffRef(GA, GA) = -dQ;
  K.coeffRef(PH, PH) = A4 * v[DE] * v[DE] * sph;
  C.coeffRef(PH, DE) = -2.0 * A4 * v[DE] * cph;
  K.coeffRef(DE, PH) = -A4 * v[PH] * (v[PH] + 2.0 * v[DE]) * sph;
  C.coeffRef(DE, PH) = A4 * (2.0 * v[PH] + 2.0 * v[DE]) * cph;
  C.coeffRef(DE, DE) = 2.0 * A4 * v[PH] * cph;
  K.coeffRef(OM, OM) = -A6 * v[EP] * v[EP] * som;
  C.coeffRef(OM, EP) = 2.0 * A6 * v[EP] * com;
  K.coeffRef(EP, OM) = A6 * v[OM] * (v[OM] + 2.0 * v[EP]) * som;
  C.coeffRef(EP, OM) = -A6 * (2.0 * v[OM] + 2.0 * v[EP]) * com;
  C.coeffRef(EP, EP) = -2.0 * A6 * v[OM] * com;
}

void Andrews::mass(double t, const double* q, SpMat& M) {
  (void)t;
  const double cth = std::cos(q[TH]), sph = std::sin(q[PH]), som = std::sin(q[OM]);
  const double ez = e - ea, zz = zf - fa;
  M.coeffRef(BE, BE) = m1 * ra * ra + m2 * (rr * rr - 2.0 * da * rr * cth + da * da) + i1 + i2;
  M.coeffRef(BE, TH) = M.coeffRef(TH, BE) = m2 * (da * da - da * rr * cth) + i2;
  M.coeffRef(TH, TH) = m2 * da * da + i2;
  M.coeffRef(GA, GA) = m3 * (sa * sa + sb * sb) + i3;
  M.coeffRef(PH, PH) = m4 * ez * ez + i4;
  M.coeffRef(PH, DE) = M.coeffRef(DE, PH) = m4 * (ez * ez + zt * ez * sph) + i4;
  M.coeffRef(DE, DE) =
      m4 * (zt * zt + 2.0 * zt * ez * sph + ez * ez) + m5 * (ta * ta + tb * tb) + i4 + i5;
  M.coeffRef(OM, OM) = m6 * zz * zz + i6;
  M.coeffRef(OM, EP) = M.coeffRef(EP, OM) = m6 * (zz * zz - u * zz * som) + i6;
  M.coeffRef(EP, EP) =
      m6 * (zz * zz - 2.0 * u * zz * som + u * u) + m7 * (ua * ua + ub * ub) + i6 + i7;
}

// Loops: the crank (beta, Theta) reaches B through body 3 (gamma) and A through
// bodies 4-5 (Phi, delta) and 6-7 (Omega, epsilon); rows 2k, 2k+1 = x, y.
void Andrews::constraint(double t, const double* q, const double* v, double* g, double* gv,
                         double* ga) {
  (void)t;
  const Angles a(q);
  const double sbe = a.sbe, cbe = a.cbe, sbt = a.sbt, cbt = a.cbt, sga = a.sga, cga = a.cga;
  const double spd = a.spd, cpd = a.cpd, sde = a.sde, cde = a.cde, soe = a.soe, coe = a.coe;
  const double sep = a.sep, cep = a.cep;
  const double cx = rr * cbe - d * cbt, cy = rr * sbe - d * sbt;  // the crank's end
  if (g) {
    g[0] = cx - ss * sga - xb;
    g[1] = cy + ss * cga - yb;
    g[2] = cx - e * spd - zt * cde - xa;
    g[3] = cy + e * cpd - zt * sde - ya;
    g[4] = cx - zf * coe - u * sep - xa;
    g[5] = cy - zf * soe + u * cep - ya;
  }
  if (gv) {
    SpMat G = gpat_;
    constraint_jacobian(t, q, G);
    Eigen::Map<const Vec> vv(v, 7);
    Eigen::Map<Vec>(gv, 6) = G * vv;  // g_t = 0
  }
  if (ga) {  // (G v)_q v: the second time derivatives at q'' = 0
    const double wb = v[BE], wbt = v[BE] + v[TH], wg = v[GA], wpd = v[PH] + v[DE], wd = v[DE];
    const double woe = v[OM] + v[EP], we = v[EP];
    const double ax = -rr * cbe * wb * wb + d * cbt * wbt * wbt;
    const double ay = -rr * sbe * wb * wb + d * sbt * wbt * wbt;
    ga[0] = ax + ss * sga * wg * wg;
    ga[1] = ay - ss * cga * wg * wg;
    ga[2] = ax + e * spd * wpd * wpd + zt * cde * wd * wd;
    ga[3] = ay - e * cpd * wpd * wpd + zt * sde * wd * wd;
    ga[4] = ax + zf * coe * woe * woe + u * sep * we * we;
    ga[5] = ay + zf * soe * woe * woe - u * cep * we * we;
  }
}

void Andrews::constraint_jacobian(double t, const double* q, SpMat& G) {
  (void)t;
  const Angles a(q);
  const double sbe = a.sbe, cbe = a.cbe, sbt = a.sbt, cbt = a.cbt, sga = a.sga, cga = a.cga;
  const double spd = a.spd, cpd = a.cpd, sde = a.sde, cde = a.cde, soe = a.soe, coe = a.coe;
  const double sep = a.sep, cep = a.cep;
  for (int r : {0, 2, 4}) {  // x rows: d(cx)
    G.coeffRef(r, BE) = -rr * sbe + d * sbt;
    G.coeffRef(r, TH) = d * sbt;
  }
  for (int r : {1, 3, 5}) {  // y rows: d(cy)
    G.coeffRef(r, BE) = rr * cbe - d * cbt;
    G.coeffRef(r, TH) = -d * cbt;
  }
  G.coeffRef(0, GA) = -ss * cga;
  G.coeffRef(1, GA) = -ss * sga;
  G.coeffRef(2, PH) = -e * cpd;
  G.coeffRef(2, DE) = -e * cpd + zt * sde;
  G.coeffRef(3, PH) = -e * spd;
  G.coeffRef(3, DE) = -e * spd - zt * cde;
  G.coeffRef(4, OM) = zf * soe;
  G.coeffRef(4, EP) = zf * soe - u * cep;
  G.coeffRef(5, OM) = -zf * coe;
  G.coeffRef(5, EP) = -zf * coe - u * sep;
}

std::string Andrews::constraint_name(int i) const {
  static const char* names[] = {"loop_B.x",  "loop_B.y",  "loop_A1.x",
                                "loop_A1.y", "loop_A2.x", "loop_A2.y"};
  return i >= 0 && i < 6 ? names[i] : Problem::constraint_name(i);
}

std::string Andrews::describe_coordinate(int i) const {
  static const char* names[] = {"beta", "Theta", "gamma", "Phi", "delta", "Omega", "epsilon"};
  return i >= 0 && i < 7 ? names[i] : Problem::describe_coordinate(i);
}

}  // namespace evas::problems
