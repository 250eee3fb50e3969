// Journal bearing element: see journal_bearing.h and docs/elements-journal-bearing.md.
//
// Derivation summary (bearing frame, right-handed x, y, axis a = z).
// A point of the bearing bore at angle phi has outward normal u = (cos phi, sin phi).
// With the journal centre at e (relative to the bearing centre) the radial gap is
// h = c - e . u. The surfaces slide with speed sum om R in +phi (the bearing is the
// reference, so om is the journal spin relative to the bearing), and the journal
// centre moves with ed, so dh/dt = -ed . u and dh/dphi = -e . t, t = (-sin, cos).
// Short-bearing Reynolds' equation (circumferential pressure flow neglected):
//   d/dx (h^3 dp/dx) = 6 eta om dh/dphi + 12 eta dh/dt = -12 eta (ed . u + (om/2) e . t)
// and e . t = -(J e) . u, so the right side is -12 eta W . u with W = ed - (om/2) J e.
// Integrating twice with p(0) = p(B) = 0: p = 6 eta x (B - x) (W . u) / h^3.
// In line-of-centres form (delta from the maximum film, in the direction of
// rotation: u = -cos(delta) e/|e| - sin(delta) J e/|e|): h = c + e cos(delta),
// W . u = (om/2 - gd) e sin(delta) - ed cos(delta), i.e. paper Eq. 3 up to the sign of
// x (x - B) (see header). The pressure acts on the journal along -u:
//   F = -R int_0^B int p u dphi dx = -eta R B^3 int_{W.u > 0} (W . u) u / h^3 dphi.
#include "elements/journal_bearing.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "elements/film_finite.h"

namespace evas {

namespace {

using V2 = Eigen::Vector2d;
using M2 = Eigen::Matrix2d;

// Rotation by +90 degrees in the bearing plane.
V2 perp(const V2& x) { return V2(-x.y(), x.x()); }
M2 J2() {
  M2 J;
  J << 0.0, -1.0, 1.0, 0.0;
  return J;
}

// Sommerfeld substitution for 1 + eps cos(delta) = (1 - eps^2) / (1 - eps cos(psi)),
// psi(delta) = 2 atan(k tan(delta / 2)), k = sqrt((1 - eps) / (1 + eps)), in its form
// without a branch jump at delta = pi: psi = delta - 2 atan(x),
// x = (1 - k) sin(delta) / ((1 + k) + (1 - k) cos(delta)).
struct Somm {
  double C, S;  // cos psi, sin psi
  double x;     // x above
};
// From cos(delta) = cd and sin(delta) = sd, with k and r = sqrt(1 - eps^2) given
// (shared by both limits). psi itself is not kept: the antiderivatives below are
// linear in psi, and the caller takes the difference of the two limits.
Somm sommerfeld(double cd, double sd, double eps, double k, double r) {
  Somm z;
  z.x = (1.0 - k) * sd / ((1.0 + k) + (1.0 - k) * cd);
  const double inv = 1.0 / (1.0 + eps * cd);
  z.C = (cd + eps) * inv;
  z.S = r * sd * inv;
  return z;
}

// Integrals over delta from lo to hi of cos^a(delta) sin^b(delta) / (1 + eps cos
// delta)^n, a + b = n - 1, by the substitution above:
//   = (1 - eps^2)^((b + 1)/2 - n) [A_ab(psi)]_lo^hi, A_ab = antiderivative in psi
// of (cos psi - eps)^a sin^b psi. dpsi = psi(hi) - psi(lo); `p` holds the
// powers (1 - eps^2)^(-k/2), k = 0..7.
struct FilmIntegrals {
  double i20, i11, i02;       // n = 3 (a + b = 2)
  double i30, i21, i12, i03;  // n = 4 (a + b = 3)
};
FilmIntegrals film_integrals(const Somm& lo, const Somm& hi, double dpsi, double e, const double* p,
                             bool cubic) {
  FilmIntegrals I{};
  const double Ch = hi.C, Sh = hi.S, Cl = lo.C, Sl = lo.S;
  const double dSC = Sh * Ch - Sl * Cl, dS = Sh - Sl, dC = Ch - Cl;
  // a + b = 2: A_20 = psi/2 + S C/2 - 2 e S + e^2 psi, A_11 = -C^2/2 + e C,
  // A_02 = psi/2 - S C/2
  I.i20 = p[5] * (0.5 * dpsi + 0.5 * dSC - 2.0 * e * dS + e * e * dpsi);
  I.i11 = p[4] * (-0.5 * (Ch * Ch - Cl * Cl) + e * dC);
  I.i02 = p[3] * (0.5 * dpsi - 0.5 * dSC);
  if (cubic) {
    // a + b = 3: A_30 = S - S^3/3 - 3 e (psi/2 + S C/2) + 3 e^2 S - e^3 psi,
    // A_21 = -(C - e)^3/3, A_12 = S^3/3 - e (psi/2 - S C/2), A_03 = -C + C^3/3
    const double dS3 = Sh * Sh * Sh - Sl * Sl * Sl, dC3 = Ch * Ch * Ch - Cl * Cl * Cl;
    const double ch = Ch - e, cl = Cl - e;
    I.i30 = p[7] * (dS - dS3 / 3.0 - 3.0 * e * (0.5 * dpsi + 0.5 * dSC) + 3.0 * e * e * dS -
                    e * e * e * dpsi);
    I.i21 = p[6] * (-(ch * ch * ch - cl * cl * cl) / 3.0);
    I.i12 = p[5] * (dS3 / 3.0 - e * (0.5 * dpsi - 0.5 * dSC));
    I.i03 = p[4] * (-dC + dC3 / 3.0);
  }
  return I;
}

std::string brief_number(double x) {
  std::ostringstream os;
  os.precision(6);
  os << x;
  return os.str();
}

}  // namespace

void gauss_legendre(int n, std::vector<double>& x, std::vector<double>& w) {
  x.assign(n, 0.0);
  w.assign(n, 0.0);
  for (int i = 0; i < (n + 1) / 2; ++i) {
    double z = std::cos(M_PI * (i + 0.75) / (n + 0.5)), dp = 0.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = 0.0;
      for (int j = 1; j <= n; ++j) {  // recurrence for P_j(z)
        const double p2 = p1;
        p1 = p0;
        p0 = ((2.0 * j - 1.0) * z * p1 - (j - 1.0) * p2) / j;
      }
      dp = n * (z * p0 - p1) / (z * z - 1.0);
      const double dz = p0 / dp;
      z -= dz;
      if (std::abs(dz) < 1e-15) break;
    }
    x[i] = -z;
    x[n - 1 - i] = z;
    w[i] = w[n - 1 - i] = 2.0 / ((1.0 - z * z) * dp * dp);
  }
}

JournalBearing::JournalBearing(std::string name, std::vector<int> markers,
                               const JournalBearingParams& p)
    : Element(std::move(name), std::move(markers)), p_(p) {
  if (p_.halves == 2) {
    // 2-point Gauss rule for the weight x (B - x) on [0, B]: nodes B/2 +- B/(2 sqrt 5).
    const double s = p_.width / (2.0 * std::sqrt(5.0));
    stations_ = {{-s, 0.5}, {s, 0.5}};
  } else {
    stations_ = {{0.0, 1.0}};
  }
  gauss_legendre(p_.n_delta, gl_x_, gl_w_);
  const std::string where = "journal bearing '" + this->name() + "'";
  if (p_.film == "finite") {
    film_ = Film::Finite;
    const double bd = p_.width / (2.0 * p_.radius);
    if (bd < kFiniteFilmMinWidthRatio || bd > kFiniteFilmMaxWidthRatio)
      throw InputError(where + ": film 'finite' (Butenschoen's fit) holds for width ratios B/D " +
                       brief_number(kFiniteFilmMinWidthRatio) + " to " +
                       brief_number(kFiniteFilmMaxWidthRatio) + "; this bearing's is " +
                       brief_number(bd) + " (use film 'reynolds')");
  } else if (p_.film == "reynolds") {
    film_ = Film::Reynolds;
    try {
      reynolds_ = std::make_shared<const ReynoldsFilm>(p_.radius, p_.width, p_.clearance,
                                                       p_.viscosity, reynolds_grid(p_));
    } catch (const InputError& ex) {
      throw InputError(where + ": " + ex.what());
    }
    if (p_.table) {
      if (p_.cavitation != "swift-stieber")
        throw InputError(where + ": solve 'table' needs cavitation 'swift-stieber' (cavitation '" +
                         p_.cavitation + "': use solve 'grid')");
      if (p_.feed != "none")
        throw InputError(where + ": solve 'table' holds for a plain bearing; feed '" + p_.feed +
                         "' turns the film with the grooves (use solve 'grid')");
      table_ = FilmTable::shared(reynolds_, p_.radius, p_.width, p_.clearance, p_.viscosity,
                                 FilmTableSize{});
    }
  } else if (p_.film != "short") {
    throw InputError(where + ": unknown film '" + p_.film + "' (short, finite, reynolds)");
  }
  if (p_.feed != "none" && film_ != Film::Reynolds)
    throw InputError(where + ": feed '" + p_.feed + "' needs film 'reynolds' (film '" + p_.film +
                     "' has no grooves)");
}

ReynoldsGrid reynolds_grid(const JournalBearingParams& p) {
  ReynoldsGrid g;
  g.n_phi = p.grid_phi;
  g.n_axial = p.grid_axial;
  g.cavitation = p.cavitation != "none";
  g.mass_conserving = p.cavitation == "mass-conserving";
  g.feed.supply_pressure = p.supply_pressure;
  std::vector<double> angles;  // feed_count evenly spaced from feed_angle [rad]
  for (int k = 0; k < p.feed_count; ++k)
    angles.push_back((p.feed_angle + 360.0 * k / p.feed_count) * M_PI / 180.0);
  if (p.feed == "axial-grooves") {
    g.feed.groove_arc = p.feed_arc * M_PI / 180.0;
    g.feed.groove_angles = angles;
  } else if (p.feed == "oil-holes") {
    if (!(p.feed_diameter > 0.0))
      throw InputError("feed 'oil-holes' needs feed_diameter > 0 (the holes' diameter)");
    g.feed.hole_diameter = p.feed_diameter;
    g.feed.hole_angles = angles;
  } else if (p.feed == "circumferential-groove") {
    if (!(p.feed_width > 0.0))
      throw InputError("feed 'circumferential-groove' needs feed_width > 0 (the groove's width)");
    g.feed.groove_width = p.feed_width;
  }
  return g;
}

FilmForce JournalBearing::hydro(const V2& e, const V2& ed, double om, double weight, bool derivs,
                                bool closed_form) const {
  if (film_ == Film::Short) return short_hydro(e, ed, om, weight, derivs, closed_form);
  FilmForce r;
  if (film_ == Film::Finite) {
    r = finite_film(p_.radius, p_.width, p_.clearance, p_.viscosity, e, ed, om, derivs);
  } else {
    // the film is a function of e and W = ed - (om/2) J e (journal_bearing.h)
    const V2 W = ed - 0.5 * om * perp(e);
    M2 df_de = M2::Zero(), df_dW = M2::Zero();
    if (table_) {
      const FilmForce t = table_->force(e, W, derivs);
      r.f = t.f, df_de = t.df_de, df_dW = t.df_ded;
    } else if (reynolds_->grid().mass_conserving) {  // in e, ed and om, not W alone
      const ReynoldsSolution s = reynolds_->solve_mass_conserving(e, ed, om, derivs);
      r.f = s.f, r.df_de = s.df_de, r.df_ded = s.df_dW, r.df_dom = s.df_dom;
    } else {
      const ReynoldsSolution s = reynolds_->solve(e, W, derivs);
      r.f = s.f, df_de = s.df_de, df_dW = s.df_dW;
    }
    if (derivs && !reynolds_->grid().mass_conserving) {
      r.df_ded = df_dW;
      r.df_de = df_de - 0.5 * om * df_dW * J2();
      r.df_dom = -0.5 * df_dW * perp(e);
    }
  }
  // a station of weight w carries that share of the full-width film at its eccentricity
  if (weight != 1.0) {
    r.f *= weight;
    r.df_de *= weight;
    r.df_ded *= weight;
    r.df_dom *= weight;
  }
  return r;
}

FilmForce JournalBearing::short_hydro(const V2& e, const V2& ed, double om, double weight,
                                      bool derivs, bool closed_form) const {
  const double c = p_.clearance;
  const double K = p_.viscosity * p_.radius * (p_.width * p_.width * p_.width) * weight;
  const V2 W = ed - 0.5 * om * perp(e);
  FilmForce r;
  M2 M3 = M2::Zero();   // int u u^T / h^3 over the positive half circle
  M2 T4W = M2::Zero();  // int (W . u) u u^T / h^4 over the positive half circle
  if (closed_form) {
    const double en = e.norm(), eps = en / c;
    // local basis Q = [a1, perp(a1)], a1 the direction of maximum film
    const V2 a1 = en > 0.0 ? V2(-e / en) : V2(1.0, 0.0), a2 = perp(a1);
    const V2 Wl(a1.dot(W), a2.dot(W));
    // limits delta = dW -+ pi/2, dW the direction of W: cos and sin of both from
    // W itself, and psi(hi) - psi(lo) = pi - 2 (atan x_hi - atan x_lo), the
    // difference of the arc tangents (each in (-pi/2, pi/2)) by one arc tangent
    const double wn = Wl.norm();
    const double cW = wn > 0.0 ? Wl.x() / wn : 1.0, sW = wn > 0.0 ? Wl.y() / wn : 0.0;
    const double rs = std::sqrt(1.0 - eps * eps);
    const double k = (1.0 - eps) / rs;  // sqrt((1 - eps) / (1 + eps))
    const Somm lo = sommerfeld(sW, -cW, eps, k, rs), hi = sommerfeld(-sW, cW, eps, k, rs);
    // (1 + x_hi x_lo > 0 unless eps > 0.97: then atan2 for the quadrant; atan
    // alone takes about 0.6 of atan2's time)
    const double num = hi.x - lo.x, den = 1.0 + hi.x * lo.x;
    const double dpsi = M_PI - 2.0 * (den > 0.0 ? std::atan(num / den) : std::atan2(num, den));
    // s^(-j/2), j = 0..7 (the half-integer exponents (b + 1)/2 - n)
    double pw[8];
    pw[0] = 1.0;
    pw[1] = 1.0 / rs;
    for (int j = 2; j < 8; ++j) pw[j] = pw[j - 1] * pw[1];
    const FilmIntegrals I = film_integrals(lo, hi, dpsi, eps, pw, derivs);
    const double c3 = c * c * c;
    // M3 in the local basis, and f = -K Q (M3l Wl)
    const double m11 = I.i20 / c3, m12 = I.i11 / c3, m22 = I.i02 / c3;
    const V2 fl(m11 * Wl.x() + m12 * Wl.y(), m12 * Wl.x() + m22 * Wl.y());
    r.f = -K * (fl.x() * a1 + fl.y() * a2);
    if (!derivs) return r;
    M2 Q;
    Q.col(0) = a1;
    Q.col(1) = a2;
    M2 M3l;
    M3l << m11, m12, m12, m22;
    M3 = Q * M3l * Q.transpose();
    // T_{ijk} = int u_i u_j u_k / h^4 in the local basis (index 1 = sine).
    const double c4 = c3 * c;
    const double t30 = I.i30 / c4, t21 = I.i21 / c4, t12 = I.i12 / c4, t03 = I.i03 / c4;
    M2 Tl;
    Tl << Wl.x() * t30 + Wl.y() * t21, Wl.x() * t21 + Wl.y() * t12, Wl.x() * t21 + Wl.y() * t12,
        Wl.x() * t12 + Wl.y() * t03;
    T4W = Q * Tl * Q.transpose();
  } else {
    const double phiW = std::atan2(W.y(), W.x());
    for (std::size_t k = 0; k < gl_x_.size(); ++k) {
      const double phi = phiW + 0.5 * M_PI * gl_x_[k], wq = 0.5 * M_PI * gl_w_[k];
      const V2 u(std::cos(phi), std::sin(phi));
      const double h = c - e.dot(u);
      const double ih3 = 1.0 / (h * h * h);
      const M2 uu = u * u.transpose();
      M3 += (wq * ih3) * uu;
      if (derivs) T4W += (wq * W.dot(u) * ih3 / h) * uu;
    }
    r.f = -K * (M3 * W);
  }
  if (derivs) {
    const M2 dW = -K * M3;  // d f / d W
    r.df_ded = dW;
    r.df_de = -3.0 * K * T4W + dW * (-0.5 * om * J2());
    r.df_dom = dW * (-0.5 * perp(e));
  }
  return r;
}

void JournalBearing::fail_if_closed(double t, double e) const {
  const double eps = e / p_.clearance;
  if (!(eps < 1.0))
    throw RangeError("journal bearing '" + name() + "': film closed, eccentricity ratio " +
                     brief_number(eps) + " >= 1 at t = " + brief_number(t) + " s (journal centre " +
                     brief_number(e) + " m off the bearing centre, radial clearance " +
                     brief_number(p_.clearance) +
                     " m). At the start this means the two markers do not share a centre: "
                     "give set markers 'centre: fit' (the least-squares cylinder through the "
                     "set's nodes) or a 'centre' on the bearing axis (a surface set's node "
                     "centroid lies off the axis by the mesh's irregularity)");
  if (eps > p_.eps_max && !(p_.contact_stiffness > 0.0))
    throw RangeError(
        "journal bearing '" + name() + "': eccentricity ratio " + brief_number(eps) +
        " >= eps_max = " + brief_number(p_.eps_max) + " at t = " + brief_number(t) +
        " s (film nearly closed; set contact_stiffness > 0 to model asperity contact)");
}

FilmForce JournalBearing::film(double t, const V2& e, const V2& ed, double om, double weight,
                               bool derivs) const {
  const double en = e.norm();
  fail_if_closed(t, en);
  FilmForce r = hydro(e, ed, om, weight, derivs, p_.closed_form);
  const double e0 = p_.eps_max * p_.clearance;
  if (en > e0 && p_.contact_stiffness > 0.0) {
    const double kc = p_.contact_stiffness * weight, n = p_.contact_exponent;
    const V2 nhat = e / en;
    const double pen = en - e0, fc = kc * std::pow(pen, n);
    r.f -= fc * nhat;
    if (derivs) {
      const double dfc = kc * n * std::pow(pen, n - 1.0);
      r.df_de -=
          dfc * nhat * nhat.transpose() + (fc / en) * (M2::Identity() - nhat * nhat.transpose());
    }
  }
  return r;
}

void JournalBearing::station_state(const MarkerMotion* m, double s, V2& e, V2& ed,
                                   double& om) const {
  const Mat3& R0 = m[0].R;
  const Vec3 a = R0.col(2);
  Vec3 d = m[1].p - m[0].p;
  Vec3 dd = m[1].v - m[0].v;
  if (s != 0.0) {
    const Vec3 ta = (m[1].psi - m[0].psi).cross(a);  // tilt of the journal axis
    d += s * ta;
    dd += s * ((m[1].w - m[0].w).cross(a) + m[1].w.cross(ta));
  }
  const Vec3 rel = dd - m[0].w.cross(d);
  e = V2(R0.col(0).dot(d), R0.col(1).dot(d));
  ed = V2(R0.col(0).dot(rel), R0.col(1).dot(rel));
  om = (m[1].w - m[0].w).dot(a) + p_.journal_speed;
}

void JournalBearing::evaluate(double t, const MarkerMotion* m, MarkerLoad* loads) const {
  const Mat3& R0 = m[0].R;
  const Vec3 a = R0.col(2);
  const Eigen::Matrix<double, 3, 2> P = R0.leftCols<2>();
  // The film model needs the journal to spin about the bearing axis (marker 0's z).
  // A relative spin more than 30 deg off that axis, with more than 10 rad/s across it
  // (far beyond any tilting rate of a journal in its film), means wrongly oriented
  // markers.
  const Vec3 w_rel = m[1].w - m[0].w;
  const double w_across2 = a.cross(w_rel).squaredNorm();  // (squares: no root per call)
  if (w_across2 > 100.0 && w_across2 > 0.25 * w_rel.squaredNorm()) {
    const double w_n = w_rel.norm(), w_across = std::sqrt(w_across2);
    throw RangeError(
        "journal bearing '" + name() + "': the journal spins about an axis " +
        std::to_string(std::asin(std::min(1.0, w_across / w_n)) * 180 / M_PI) +
        " deg off the bearing axis (the z axis of the bearing marker) at t = " + std::to_string(t) +
        " s. At the start this means a misoriented marker: give the bearing marker a rotation "
        "that turns its z axis onto the crank axis; later in a run, the motion has left what "
        "the film model describes (a diverging solution or too coarse a step)");
  }
  Vec3 F = Vec3::Zero(), M = Vec3::Zero();
  for (const auto& st : stations_) {
    V2 e, ed;
    double om;
    station_state(m, st.s, e, ed, om);
    const Vec3 Fs = P * film(t, e, ed, om, st.weight, false).f;
    F += Fs;
    M += st.s * a.cross(Fs);
  }
  loads[1].F = F;
  loads[1].M = M;
  loads[0].F = -F;
  loads[0].M = -M - (m[1].p - m[0].p).cross(F);
}

void JournalBearing::derivatives(double t, const MarkerMotion* m, Mat& D) const {
  const Mat3& R0 = m[0].R;
  const Vec3 a = R0.col(2);
  const Eigen::Matrix<double, 3, 2> P = R0.leftCols<2>();
  const Mat3 Sa = skew(a), Sw0 = skew(m[0].w), Sw1 = skew(m[1].w);
  // Column blocks of marker j: p at 12 j, v at 12 j + 3, psi at 12 j + 6, w at 12 j + 9.
  Eigen::Matrix<double, 3, 24> DF = Eigen::Matrix<double, 3, 24>::Zero(), DM = DF;
  Vec3 F = Vec3::Zero();
  for (const auto& st : stations_) {
    const double s = st.s;
    V2 e, ed;
    double om;
    station_state(m, s, e, ed, om);
    const FilmForce ff = film(t, e, ed, om, st.weight, true);
    // Jacobians of d, dd (3 x 24) and om (1 x 24).
    Eigen::Matrix<double, 3, 24> Jd = Eigen::Matrix<double, 3, 24>::Zero(), Jdd = Jd;
    Eigen::Matrix<double, 1, 24> Jom = Eigen::Matrix<double, 1, 24>::Zero();
    Jd.block<3, 3>(0, 0) = -Mat3::Identity();
    Jd.block<3, 3>(0, 12) = Mat3::Identity();
    Jdd.block<3, 3>(0, 3) = -Mat3::Identity();
    Jdd.block<3, 3>(0, 15) = Mat3::Identity();
    Vec3 d = m[1].p - m[0].p;
    if (s != 0.0) {
      const Vec3 ta = (m[1].psi - m[0].psi).cross(a);
      d += s * ta;
      // ta = -Sa theta, theta = psi1 - psi0
      Jd.block<3, 3>(0, 18) = -s * Sa;
      Jd.block<3, 3>(0, 6) = s * Sa;
      // dd += s ((w1 - w0) x a + w1 x ta)
      Jdd.block<3, 3>(0, 21) = -s * (Sa + skew(ta));
      Jdd.block<3, 3>(0, 9) = s * Sa;
      Jdd.block<3, 3>(0, 18) = -s * Sw1 * Sa;
      Jdd.block<3, 3>(0, 6) = s * Sw1 * Sa;
    }
    // rel = dd - w0 x d
    Eigen::Matrix<double, 3, 24> Jrel = Jdd - Sw0 * Jd;
    Jrel.block<3, 3>(0, 9) += skew(d);
    Jom.block<1, 3>(0, 21) = a.transpose();
    Jom.block<1, 3>(0, 9) = -a.transpose();
    const Eigen::Matrix<double, 2, 24> Df =
        ff.df_de * (P.transpose() * Jd) + ff.df_ded * (P.transpose() * Jrel) + ff.df_dom * Jom;
    const Eigen::Matrix<double, 3, 24> DFs = P * Df;
    DF += DFs;
    DM += s * Sa * DFs;
    F += P * ff.f;
  }
  const Vec3 dp = m[1].p - m[0].p;
  D.setZero(12, 24);
  D.block<3, 24>(6, 0) = DF;
  D.block<3, 24>(9, 0) = DM;
  D.block<3, 24>(0, 0) = -DF;
  // M0 = -M1 - dp x F1
  D.block<3, 24>(3, 0) = -DM - skew(dp) * DF;
  D.block<3, 3>(3, 12) += skew(F);
  D.block<3, 3>(3, 0) -= skew(F);
}

double JournalBearing::friction_torque(const V2& e, double om, const V2& f, double weight) const {
  const double c = p_.clearance, R = p_.radius, eps = e.norm() / c;
  const double couette = 2.0 * M_PI * p_.viscosity * R * R * R * weight * p_.width * om /
                         (c * std::sqrt(1.0 - eps * eps));
  return -couette - 0.5 * (e.x() * f.y() - e.y() * f.x());
}

double JournalBearing::peak_pressure(const V2& e, const V2& ed, double om, double* angle) const {
  if (film_ == Film::Reynolds && table_)
    return table_->peak_pressure(e, ed - 0.5 * om * perp(e), angle);
  if (film_ == Film::Reynolds) {
    const ReynoldsSolution s = reynolds_->grid().mass_conserving
                                   ? reynolds_->solve_mass_conserving(e, ed, om, false)
                                   : reynolds_->solve(e, ed - 0.5 * om * perp(e), false);
    if (angle) *angle = s.p_max_angle;
    return s.p_max;
  }
  const double p = short_peak_pressure(e, ed, om, angle);
  if (film_ == Film::Short) return p;
  // finite: no pressure field of its own; the short film's scaled to the finite film's force
  const double fs = short_hydro(e, ed, om, 1.0, false, true).f.norm();
  return fs > 0.0 ? p * hydro(e, ed, om, 1.0, false, true).f.norm() / fs : 0.0;
}

double JournalBearing::short_peak_pressure(const V2& e, const V2& ed, double om,
                                           double* angle) const {
  const double c = p_.clearance;
  const V2 W = ed - 0.5 * om * perp(e);
  if (angle) *angle = 0.0;
  if (W.squaredNorm() == 0.0) return 0.0;
  const double phiW = std::atan2(W.y(), W.x());
  auto q = [&](double phi) {
    const V2 u(std::cos(phi), std::sin(phi));
    const double h = c - e.dot(u);
    return W.dot(u) / (h * h * h);
  };
  // Coarse scan of the positive half circle phiW - pi/2 + i dphi, i = 0..n, with
  // the angles' cosines and sines from a table: in the frame turned to phiW -
  // pi/2, W = (0, |W|) and e is turned once; the points are independent (they
  // vectorize; a unit vector turned point by point chained them), then Newton
  // in the best bracket.
  constexpr int n = 64;
  constexpr double dphi = M_PI / n;
  struct Table {
    double c[n + 1], s[n + 1];
  };
  static const Table tab = [] {
    Table t{};
    for (int i = 0; i <= n; ++i) t.c[i] = std::cos(i * dphi), t.s[i] = std::sin(i * dphi);
    return t;
  }();
  const double wn = W.norm();
  const double cb = W.y() / wn, sb = -W.x() / wn;  // cos, sin of phiW - pi/2
  const double e1 = cb * e.x() + sb * e.y(), e2 = cb * e.y() - sb * e.x();
  double qs[n + 1];
  for (int i = 0; i <= n; ++i) {
    const double h = c - (e1 * tab.c[i] + e2 * tab.s[i]);
    qs[i] = wn * tab.s[i] / (h * h * h);
  }
  int best = 0;
  double qbest = -1.0;
  for (int i = 0; i <= n; ++i)
    if (qs[i] > qbest) qbest = qs[i], best = i;
  // Safeguarded Newton on dq/dphi = 0 in the bracket around the best point,
  // with u' = perp(u), u'' = -u:  N = W.u, h = c - e.u,
  //   q' = N' / h^3 - 3 N h' / h^4,
  //   q'' = -N / h^3 - 6 N' h' / h^4 + 12 N h'^2 / h^5 - 3 N h'' / h^4,
  // N' = W.u', h' = -e.u', h'' = e.u. A step leaving the bracket, or taken
  // where q is not concave, bisects instead.
  double lo = phiW - 0.5 * M_PI + (best - 1) * dphi, hi = lo + 2.0 * dphi;
  double phi = lo + dphi, qpeak = qbest;
  for (int it = 0; it < 40; ++it) {
    const V2 uu(std::cos(phi), std::sin(phi)), up(-uu.y(), uu.x());
    const double N = W.dot(uu), Np = W.dot(up);
    const double h = c - e.dot(uu), hp = -e.dot(up), hpp = e.dot(uu);
    const double h3 = h * h * h, h4 = h3 * h;
    qpeak = std::max(qpeak, N / h3);
    const double d1 = Np / h3 - 3.0 * N * hp / h4;
    const double d2 =
        -N / h3 - 6.0 * Np * hp / h4 + 12.0 * N * hp * hp / (h4 * h) - 3.0 * N * hpp / h4;
    if (d1 > 0.0)
      lo = phi;
    else
      hi = phi;
    double next = d2 < 0.0 ? phi - d1 / d2 : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    // q is flat at its maximum: a step of 1e-10 rad leaves q exact to rounding
    if (std::abs(next - phi) < 1e-10 || hi - lo < 1e-10) {
      phi = next;
      break;
    }
    phi = next;
  }
  const double qphi = q(phi);
  if (angle) {
    // the angle of the larger of the refined point and the best grid point
    const double a = qphi >= qbest ? phi : phiW - 0.5 * M_PI + best * dphi;
    *angle = std::remainder(a, 2.0 * M_PI);
  }
  qpeak = std::max(qpeak, qphi);
  // p = 6 eta x (B - x) q, largest at the mid-plane x = B/2.
  return 1.5 * p_.viscosity * p_.width * p_.width * qpeak;
}

std::vector<Channel> JournalBearing::channels() const {
  return {{"fx", "N"},
          {"fy", "N"},
          {"mx", "N m"},
          {"my", "N m"},
          {"eps", "-"},
          {"attitude", "rad"},
          {"h_min", "m"},
          {"p_max", "Pa"},
          {"ex", "m"},
          {"ey", "m"},
          {"h_min_angle", "rad"},
          {"p_max_angle", "rad"},
          {"friction_torque", "N m"},
          {"friction_power", "W"},
          {"fx_journal", "N"},
          {"fy_journal", "N"}};
}

void JournalBearing::channel_values(double t, const MarkerMotion* m, double* out) const {
  MarkerLoad loads[2];
  evaluate(t, m, loads);
  const Mat3& R0 = m[0].R;
  const Vec3 F = R0.transpose() * loads[1].F, M = R0.transpose() * loads[1].M;
  V2 e, ed;
  double om;
  station_state(m, 0.0, e, ed, om);
  double emax = 0.0, torque = 0.0;
  V2 e_thin = e;  // eccentricity of the station with the thinnest film
  for (const auto& st : stations_) {
    V2 es, eds;
    double oms;
    station_state(m, st.s, es, eds, oms);
    if (es.norm() > emax) emax = es.norm(), e_thin = es;
    torque += friction_torque(es, oms, hydro(es, eds, oms, st.weight, false, p_.closed_form).f,
                              st.weight);
  }
  out[0] = F.x();
  out[1] = F.y();
  out[2] = M.x();
  out[3] = M.y();
  out[4] = e.norm() / p_.clearance;
  out[5] = std::atan2(e.y(), e.x());
  out[6] = p_.clearance - emax;
  out[7] = peak_pressure(e, ed, om, &out[11]);
  out[8] = e.x();
  out[9] = e.y();
  out[10] = std::atan2(e_thin.y(), e_thin.x());  // h = c - e . u is thinnest along e
  out[12] = torque;
  out[13] = -torque * om;  // the power the journal's spin loses to the film
  // the force on the journal in axes that turn with the journal (polar diagram
  // on the journal): the bearing's axes at t0, turned by the journal's rotation
  // about the bearing axis since t0, th = (psi_journal - psi_bearing) . a
  const double th = (m[1].psi - m[0].psi).dot(R0.col(2)), ct = std::cos(th), st = std::sin(th);
  out[14] = ct * F.x() + st * F.y();
  out[15] = -st * F.x() + ct * F.y();
}

std::string JournalBearing::run_refusal() const {
  if (film_ != Film::Reynolds || p_.cavitation != "mass-conserving") return {};
  return "cavitation 'mass-conserving' gives evas bearing's static answer only: in a run its "
         "film fraction would need a history (the element's state), which is not built; use "
         "cavitation 'swift-stieber'";
}

}  // namespace evas
