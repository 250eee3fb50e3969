#include "problems/wheelset.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace evas::problems {

namespace {

// the test set's parameters (SI units)
constexpr double MR = 16.08;      // mass of the wheelset [kg]
constexpr double G = 9.81;        // gravity [m/s^2]
constexpr double V = 30.0;        // nominal speed [m/s]
constexpr double RN0 = 0.1;       // nominal wheel radius [m]
constexpr double LI1 = 0.0605;    // moment of inertia about the axle [kg m^2]
constexpr double LI2 = 0.366;     // about the other two axes [kg m^2]
constexpr double MA = 0.0;        // chassis mass [kg]
constexpr double HA = 0.2;        // chassis height [m]
constexpr double MU = 0.12;       // friction coefficient
constexpr double XL = 0.19;       // spring lever [m]
constexpr double CX = 6400.0;     // lateral spring [N/m]
constexpr double CZ = 6400.0;     // longitudinal spring [N/m]
constexpr double E = 1.3537956;   // elliptic integral of the contact ellipse
constexpr double GG = 0.7115218;  // ratio of its half axes squared
constexpr double SIGMA = 0.28;    // Poisson's ratio
constexpr double GM = 7.92e10;    // shear modulus [N/m^2]
constexpr double C11 = 4.72772197, C22 = 4.27526987, C23 = 1.97203505;  // Kalker's
constexpr double DELTA0 = 0.0262;       // cone angle of the wheels [rad]
constexpr double AR = 0.1506;           // half the distance of the wheels [m]
constexpr double RS = 0.06;             // radius of the rail head [m]
constexpr double EPS = 1e-5;            // margin of the rail profile [m]
constexpr double B1 = 0.0, B2 = 4.0;    // limits of the wheel profile [m]
constexpr double kPiCreep = 3.1415926;  // the test set's pi in its creep routine
constexpr double kLambdaScale = 1e4;    // y16, y17 are the multipliers / 1e4

struct Profile {
  double r, dr, d2r;  // value and its first two derivatives
};

// the conical wheel: r(xi) = RN0 + tan(DELTA0) (AR - |xi|)
Profile wheel_profile(double xi) {
  const double a = std::abs(xi);
  if (!(B1 < a && a < B2))
    throw RangeError("wheelset: contact point xi = " + std::to_string(xi) +
                     " m off the wheel (derailment)");
  const double ta = std::tan(DELTA0);
  return {RN0 + ta * (AR - a), xi >= 0.0 ? -ta : ta, 0.0};
}

// the circular rail head of radius RS, its centre at AR + RS sin(DELTA0)
Profile rail_profile(double x) {
  const double a = std::abs(x), c = AR + std::sin(DELTA0) * RS;
  if (!(c - RS + EPS < a && a < c + RS - EPS))
    throw RangeError("wheelset: contact point x = " + std::to_string(x) +
                     " m off the rail head (derailment)");
  const double w = std::sqrt(RS * RS - (a - c) * (a - c));
  return {w - RN0 - std::cos(DELTA0) * RS, (x >= 0.0 ? 1.0 : -1.0) * (c - a) / w,
          -RS * RS / (w * w * w)};
}

struct Angles {
  double st, ct, sp, cp;  // sin, cos of theta and phi
};

// one contact point: wheel and rail profiles and the angles of its frame
struct Contact {
  double psi = 0.0, xi = 0.0, sps = 0.0, cps = 0.0;  // the contact coordinates
  Profile wheel{}, rail{};
  std::array<double, 5> q{};  // the row of the constraint Jacobian G (CONSTM)
  double delta = 0.0;         // the angle of the contact plane
};

Contact contact(double x, double psi, double xi, const Angles& a, double side) {
  Contact c;
  c.psi = psi;
  c.xi = xi;
  c.sps = std::sin(psi);
  c.cps = std::cos(psi);
  c.wheel = wheel_profile(xi);
  const double rx = c.wheel.r;
  // the lateral coordinate of the contact point in the track frame
  const double xg = x + xi * a.ct * a.cp + rx * (a.ct * a.sp * c.cps - a.st * c.sps);
  c.rail = rail_profile(xg);
  const double dg = c.rail.dr;
  c.q = {dg, -1.0, 0.0, dg * (rx * (-a.ct * c.sps - c.cps * a.sp * a.st) - a.cp * a.st * xi),
         -c.cps * rx * a.sp - a.cp * xi + dg * (a.cp * c.cps * a.ct * rx - a.ct * a.sp * xi)};
  const double dr = c.wheel.dr;
  const double num = (dr * a.cp - a.sp * c.cps) * a.ct + c.sps * a.st;
  // left (side = +1): atan(num / -(dr sp + cps cp)); right (side = -1): with +
  c.delta = std::atan(num / (-side * (dr * a.sp + c.cps * a.cp)));
  return c;
}

// the semi-axis c of the contact ellipse under the normal force fn (Hertz)
double ellipse(const Contact& c, double fn) {
  const double rr = c.wheel.r * std::sqrt(1.0 + c.wheel.dr * c.wheel.dr);
  const double rho_g = -c.rail.d2r / std::pow(1.0 + c.rail.dr * c.rail.dr, 1.5);
  const double rho_r = c.wheel.d2r / std::pow(1.0 + c.wheel.dr * c.wheel.dr, 1.5);
  const double a = 0.5 / rr, b = 0.5 * (rho_g + rho_r);
  return std::cbrt((3.0 * std::abs(fn) * (1.0 - SIGMA) * E) /
                   (2.0 * kPiCreep * (a + b) * GM * std::sqrt(GG)));
}

// the creep force at one contact point in the wheelset's nominal frame (CREEP
// of the test set, straight track: s = alpha = 0); side +1 left, -1 right
std::array<double, 3> creep_force(const double* y, const Contact& c, double fn, double side) {
  const double theta = y[3];
  const double sp = std::sin(y[4]), cp = std::cos(y[4]);
  const double xp = y[5], yp = y[6], zp = y[7], thetap = y[8], phip = y[9];
  const double spin = V / RN0 + y[10];  // angular velocity about the axle
  const double sd = std::sin(c.delta), cd = std::cos(c.delta);
  // the yaw angle enters divided by cos(delta) (as in the test set)
  const double st = std::sin(theta / cd), ct = std::cos(theta / cd);
  const double rx = c.wheel.r, xi = c.xi, sps = c.sps, cps = c.cps;
  const double cl = ellipse(c, fn);
  // relative velocity of the contact point
  const double u = rx * (st * sp * cps + ct * sps) + xi * st * cp;
  const double w1 = -spin * rx * (st * cps + ct * sp * sps) + xp - thetap * u -
                    phip * ct * (xi * sp - rx * cp * cps);
  const double w2 = spin * rx * cp * sps + yp + phip * (xi * cp + rx * sp * cps);
  const double w3 = -spin * rx * (ct * cps - st * sp * sps) + V + zp -
                    thetap * (xi * ct * cp + rx * (ct * sp * cps - st * sps)) +
                    phip * st * (xi * sp - rx * cp * cps);
  // rolling velocity
  const double r1 = w1 - 2.0 * xp, r2 = w2 - 2.0 * yp, r3 = w3 - 2.0 * zp - 2.0 * V;
  const double vr = 0.5 * std::sqrt(r1 * r1 + r2 * r2 + r3 * r3);
  // creepages: longitudinal, lateral, spin
  const double nux = (st * w1 + ct * w3) / vr;
  const double nuy = (ct * cd * w1 + side * sd * w2 - st * cd * w3) / vr;
  const double phis = (-side * sd * spin + cd * thetap) / vr;
  const double wt = MU * fn;
  double tx = -wt * std::tanh(GM * cl * cl * C11 * nux / wt);
  double ty = -wt * std::tanh(GM * cl * cl * C22 * nuy / wt + GM * cl * cl * cl * C23 * phis / wt);
  const double sq = std::sqrt(tx * tx + ty * ty);
  if (sq * sq > wt * wt) {  // beyond the friction limit: scaled back onto it
    tx *= std::abs(wt) / sq;
    ty *= std::abs(wt) / sq;
  }
  return {st * tx + ct * cd * ty, side * sd * ty, ct * tx - st * cd * ty};
}

}  // namespace

// RESWHS of the test set on its straight track: curvature s = 0 and cant
// alpha = 0, so its terms in V s, sin(alpha) and the chassis force FQ1 vanish
// and are left out here.
void Wheelset::forces(const double* y, double* f) const {
  const double x = y[0], zz = y[2], theta = y[3], phi = y[4];
  const double thetap = y[8], phip = y[9], betap = y[10];
  const double lam_l = y[15] * kLambdaScale, lam_r = y[16] * kLambdaScale;
  const Angles a{std::sin(theta), std::cos(theta), std::sin(phi), std::cos(phi)};
  const Contact L = contact(x, y[13], y[14], a, 1.0);
  const Contact R = contact(x, y[11], y[12], a, -1.0);
  const double sdl = std::sin(L.delta), cdl = std::cos(L.delta);
  const double sdr = std::sin(R.delta), cdr = std::cos(R.delta);
  // the normal forces from the multipliers' lateral and vertical forces
  const double det = -sdl * cdr - sdr * cdl;
  if (std::abs(det) < 1e-8) throw RangeError("wheelset: the contact planes are parallel");
  const double g1 = L.q[0] * lam_l + R.q[0] * lam_r, g2 = L.q[1] * lam_l + R.q[1] * lam_r;
  const double fnl = (cdr * g1 - sdr * g2) / det, fnr = (-cdl * g1 - sdl * g2) / det;
  const auto tl = creep_force(y, L, fnl, 1.0), tr = creep_force(y, R, fnr, -1.0);
  // the chassis (MA = 0 here) and the springs
  const double fq1 = 0.0, fq2 = -MA * G, fq3 = -2.0 * CZ * zz;
  const double lm2 = -2.0 * XL * XL * CZ * theta, lm3 = -HA * fq1;
  const double omega = V / RN0;
  auto glam = [&](int k) {
    return L.q[static_cast<std::size_t>(k)] * lam_l + R.q[static_cast<std::size_t>(k)] * lam_r;
  };
  for (int i = 0; i < 5; ++i) f[i] = y[5 + i];  // kinematics
  // Newton: lateral, vertical, longitudinal
  f[5] = tl[0] + tr[0] + fq1 + glam(0) - 2.0 * CX * x;
  f[6] = tl[1] + tr[1] + fq2 - MR * G + glam(1);
  f[7] = tl[2] + tr[2] + fq3 + glam(2);
  // Euler: the moments of the creep forces about the three axes
  const double st = a.st, ct = a.ct, sp = a.sp, cp = a.cp;
  auto m_yaw = [&](const Contact& c, const std::array<double, 3>& t) {
    const double rx = c.wheel.r;
    return -(c.xi * st + rx * c.sps * ct * cp) * t[0] - rx * c.sps * sp * t[1] +
           (-c.xi * ct + rx * c.sps * st * cp) * t[2];
  };
  auto m_roll = [&](const Contact& c, const std::array<double, 3>& t) {
    const double rx = c.wheel.r;
    return -(c.xi * ct * sp - rx * c.cps * ct * cp) * t[0] + (c.xi * cp + rx * c.cps * sp) * t[1] +
           (c.xi * st * sp - rx * c.cps * st * cp) * t[2];
  };
  auto m_spin = [&](const Contact& c, const std::array<double, 3>& t) {
    const double rx = c.wheel.r;
    return -rx * (c.cps * st + c.sps * ct * sp) * t[0] + rx * c.sps * cp * t[1] -
           rx * (c.cps * ct - c.sps * st * sp) * t[2];
  };
  f[8] = LI2 * thetap * phip * sp - LI1 * (omega + betap) * phip -
         (LI1 - LI2) * thetap * sp * phip + m_yaw(L, tl) + m_yaw(R, tr) + cp * lm2 + st * sp * lm3 +
         glam(3);
  f[9] = LI1 * (omega + betap) * thetap * cp + (LI1 - LI2) * thetap * sp * thetap * cp +
         m_roll(L, tl) + m_roll(R, tr) + lm3 + glam(4);
  f[10] = -LI1 * thetap * phip * cp + m_spin(L, tl) + m_spin(R, tr) + sp * lm2;
  // the contact constraints differentiated once: G(p) v = 0 (index 2)
  f[11] = f[12] = 0.0;
  for (int k = 0; k < 5; ++k) {
    f[11] += L.q[static_cast<std::size_t>(k)] * y[5 + k];
    f[12] += R.q[static_cast<std::size_t>(k)] * y[5 + k];
  }
  // the normals of wheel and rail at each contact point are parallel
  auto normals = [&](const Contact& c, double* out) {
    const double dr = c.wheel.dr, dg = c.rail.dr;
    out[0] = dg * (dr * sp + cp * c.cps) + dr * ct * cp - ct * sp * c.cps + st * c.sps;
    out[1] = dr * st * cp - st * sp * c.cps - ct * c.sps;
  };
  normals(L, f + 13);
  normals(R, f + 15);
}

Mat Wheelset::mass() const {
  Vec d(17);
  d << 1.0, 1.0, 1.0, 1.0, 1.0, MR, MR, MR, LI2, LI2, LI1, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0;
  return d.asDiagonal();
}

void Wheelset::rhs(double t, const double* y, double* f) {
  (void)t;
  const double cp = std::cos(y[4]);
  if (!(std::abs(cp) > 0.5))
    throw RangeError("wheelset: roll angle " + std::to_string(y[4]) + " rad");
  forces(y, f);
  // rows 9 and 11 solved for LI2 y9' and LI1 y11' (the constant-mass form)
  const double f9 = f[8];
  f[8] = f9 / cp;
  f[10] -= (LI1 / LI2) * std::tan(y[4]) * f9;
}

void Wheelset::rhs_jacobian(double t, const double* y, Mat& J) {
  const int n = size();
  J.resize(n, n);
  std::array<double, 17> yy{}, fp{}, fm{};
  for (int i = 0; i < n; ++i) yy[static_cast<std::size_t>(i)] = y[i];
  for (int j = 0; j < n; ++j) {
    const auto uj = static_cast<std::size_t>(j);
    const double h = 6e-6 * std::max(std::abs(y[j]), 1e-3);
    yy[uj] = y[j] + h;
    rhs(t, yy.data(), fp.data());
    yy[uj] = y[j] - h;
    rhs(t, yy.data(), fm.data());
    yy[uj] = y[j];
    for (int i = 0; i < n; ++i) {
      const auto ui = static_cast<std::size_t>(i);
      J(i, j) = (fp[ui] - fm[ui]) / (2.0 * h);
    }
  }
}

void Wheelset::test_set_residual(double t, const double* y, const double* yp, double* r) const {
  (void)t;
  std::array<double, 17> f{};
  forces(y, f.data());
  const double sp = std::sin(y[4]), cp = std::cos(y[4]);
  for (int i = 0; i < 5; ++i) r[i] = yp[i] - f[static_cast<std::size_t>(i)];
  for (int i = 5; i < 8; ++i) r[i] = MR * yp[i] - f[static_cast<std::size_t>(i)];
  r[8] = LI2 * cp * yp[8] - f[8];
  r[9] = LI2 * yp[9] - f[9];
  r[10] = LI1 * sp * yp[8] + LI1 * yp[10] - f[10];
  for (int i = 11; i < 17; ++i) r[i] = -f[static_cast<std::size_t>(i)];
}

void Wheelset::initial(Vec& y, Vec& yp) const {
  y.resize(17);
  y << 0.14941e-02, 0.40089e-06, 0.11241e-05, -.28573e-03, 0.26459e-03, 0.0, 0.0, 0.0, 0.0, 0.0,
      0.0, -7.4122380357667139e-06, -0.1521364296121248, 7.5634406395172940e-06, 0.1490635714733819,
      -8.3593e-3, -7.4144e-3;
  yp.resize(17);
  yp << 0.0, 0.0, 0.0, 0.0, 0.0, -1.975258894011285, -1.0898297102811276e-03,
      7.8855083626142589e-02, -5.533362821731549, -0.3487021489546511, -2.132968724380927, 0.0, 0.0,
      0.0, 0.0, 0.0, 0.0;
}

std::string Wheelset::component_name(int i) const {
  static const char* const names[17] = {
      "x [m]",    "y [m]",       "z [m]",          "theta [rad]",  "phi [rad]",     "x' [m/s]",
      "y' [m/s]", "z' [m/s]",    "theta' [rad/s]", "phi' [rad/s]", "beta' [rad/s]", "psi_R [rad]",
      "xi_R [m]", "psi_L [rad]", "xi_L [m]",       "lambda_1/1e4", "lambda_2/1e4"};
  return i >= 0 && i < 17 ? names[i] : ImplicitDae::component_name(i);
}

}  // namespace evas::problems
