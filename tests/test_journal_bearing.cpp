// Journal bearing element (elements/journal_bearing.*) against the short-bearing
// (Ocvirk) results collected in references.md section 1:
//   - film forces in the line-of-centres frame (Ocvirk, pi-film),
//   - steady load capacity, the Sommerfeld quartic and the attitude angle,
//   - linearised stiffness and damping coefficients a_ij, b_ij (Friswell, Penny,
//     Garvey, Lees, "Dynamics of Rotating Machines", CUP 2010, short-bearing model),
//   - oil whirl of a rigid rotor above the threshold speed from the linearised
//     coefficients (Lund's stability method).
#include "journal_bearing_support.h"

// (1) Quadrature against the closed form, and the closed form against references.md s.1.
TEST(JournalBearing, QuadratureMatchesClosedForm) {
  const double om = 300.0;
  const JournalBearingParams pc = base_params(true);
  const JournalBearing closed = make_bearing(pc);
  const double c = pc.clearance;
  struct State {
    double eps, epsd, gd;  // eps, eps_dot [1/s], gamma_dot [rad/s]
  };
  const std::vector<State> states = {{0.1, 0.0, 0.0},   {0.5, 0.0, 0.0},   {0.8, 0.0, 0.0},
                                     {0.95, 0.0, 0.0},  {0.5, 0.0, 40.0},  {0.5, 0.0, -60.0},
                                     {0.5, 50.0, 0.0},  {0.5, -80.0, 0.0}, {0.7, 30.0, 20.0},
                                     {0.3, -200., 90.}, {0.6, 0.0, 200.0}, {0.9, 20.0, -30.0}};
  std::printf("(1) relative difference |F_quad - F_closed| / |F_closed| vs n_delta\n");
  std::printf("%5s %7s %7s |", "eps", "epsd", "gd");
  const std::vector<int> nds = {4, 8, 16, 32, 64, 128};
  for (int n : nds) std::printf(" %9d", n);
  std::printf(" | ref-formula diff\n");
  double worst64 = 0.0;
  for (const auto& s : states) {
    const double gam = 0.7;  // arbitrary line-of-centres angle
    const V2 r(std::cos(gam), std::sin(gam)), t(-r.y(), r.x());
    const V2 e = s.eps * c * r, ed = s.epsd * c * r + s.eps * c * s.gd * t;
    const V2 fc = closed.hydro(e, ed, om, 1.0, false, true).f;
    std::printf("%5.2f %7.1f %7.1f |", s.eps, s.epsd, s.gd);
    for (int n : nds) {
      const JournalBearing q = make_bearing(base_params(false, n));
      const double d = (q.hydro(e, ed, om, 1.0, false, false).f - fc).norm() / fc.norm();
      std::printf(" %9.2e", d);
      if (n == 64) worst64 = std::max(worst64, d);
    }
    // references.md s.1 integrates over delta in (0, pi): exact when epsd = 0 and om > 2 gd.
    const double dref = (ocvirk_reference(pc, e, ed, om) - fc).norm() / fc.norm();
    std::printf(" | %9.2e%s\n", dref, s.epsd == 0.0 ? "" : " (film region shifted by epsd)");
    if (s.epsd == 0.0 && om > 2 * s.gd) {
      EXPECT_LT(dref, 1e-12) << "closed form vs references.md s.1 at eps " << s.eps;
    }
  }
  std::printf("worst n_delta = 64 difference: %.3e\n", worst64);
  EXPECT_LT(worst64, 1e-9);
  // Centred journal (e = 0) with a squeeze velocity: finite and the methods agree.
  const V2 fz = closed.hydro(V2::Zero(), V2(0.0, 0.01), om, 1.0, false, true).f;
  const V2 fq =
      make_bearing(base_params(false)).hydro(V2::Zero(), V2(0.0, 0.01), om, 1.0, false, false).f;
  EXPECT_TRUE(fz.allFinite());
  EXPECT_LT((fz - fq).norm(), 1e-12 * fz.norm());
  EXPECT_LT(fz.y(), 0.0);  // squeeze film resists the approach
}

// (2) Static equilibrium against the load-capacity quartic and tan(phi).
TEST(JournalBearing, StaticEquilibrium) {
  const double om = 2 * M_PI * 50;
  for (bool closed_form : {true, false}) {
    const JournalBearingParams p = base_params(closed_form);
    const JournalBearing jb = make_bearing(p);
    std::printf("(2) static equilibrium, method %s\n", closed_form ? "ocvirk" : "quadrature");
    for (double W : {50.0, 300.0, 1500.0, 8000.0}) {
      int its = 0;
      const V2 e = equilibrium(jb, om, W, &its);
      const double eps = e.norm() / p.clearance;
      const double Ss = 2 * p.radius * om * p.viscosity * std::pow(p.width, 3) /
                        (8 * p.clearance * p.clearance * W);
      const double eps_ref = eps_from_quartic(Ss);
      // Attitude angle between the load line (-y) and the line of centres.
      const double phi = std::acos(-e.y() / e.norm());
      const double phi_ref = std::atan(M_PI * std::sqrt(1 - eps_ref * eps_ref) / (4 * eps_ref));
      std::printf(
          "  W = %7.1f N: eps %.12f (quartic %.12f, err %.2e)  phi %.12f (ref %.12f, err %.2e)"
          "  e_x %+.3e  Newton its %d\n",
          W, eps, eps_ref, eps - eps_ref, phi, phi_ref, phi - phi_ref, e.x(), its);
      EXPECT_NEAR(eps, eps_ref, 1e-10);
      EXPECT_NEAR(phi, phi_ref, 1e-10);
      EXPECT_NEAR(load_capacity(p, om, eps_ref), W, 1e-8 * W);
      // Journal displaced down and, for rotation from +x to +y, towards +x.
      EXPECT_LT(e.y(), 0.0);
      EXPECT_GT(e.x(), 0.0);
    }
  }
}

// (3) Linearised stiffness and damping by finite differences of the element about
// the equilibrium against the short-bearing a_ij, b_ij (Friswell et al.).
TEST(JournalBearing, LinearisedCoefficients) {
  const double om = 2 * M_PI * 50;
  const JournalBearingParams p = base_params(true);
  const JournalBearing jb = make_bearing(p);
  const double c = p.clearance;
  std::printf("(3) linearised coefficients (FD of the element) vs Friswell et al.\n");
  for (double eps_target : {0.2, 0.5, 0.7}) {
    const double W = load_capacity(p, om, eps_target);
    const V2 e0 = equilibrium(jb, om, W);
    ASSERT_NEAR(e0.norm() / c, eps_target, 1e-10);
    M2 K, C;
    const double hx = 1e-5 * c, hv = 1e-5 * c * om;
    for (int j = 0; j < 2; ++j) {
      V2 dx = V2::Zero();
      dx[j] = hx;
      K.col(j) = -(jb.film(0, e0 + dx, V2::Zero(), om, 1, false).f -
                   jb.film(0, e0 - dx, V2::Zero(), om, 1, false).f) /
                 (2 * hx);
      V2 dv = V2::Zero();
      dv[j] = hv;
      C.col(j) =
          -(jb.film(0, e0, dv, om, 1, false).f - jb.film(0, e0, -dv, om, 1, false).f) / (2 * hv);
    }
    const M2 a_el = K * c / W, b_el = C * c * om / W;
    M2 a, b;
    friswell(eps_target, a, b);
    const char* n[2][2] = {{"xx", "xy"}, {"yx", "yy"}};
    std::printf("  eps = %.1f\n", eps_target);
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) {
        const double ea = (a_el(i, j) - a(i, j)) / std::abs(a(i, j));
        const double eb = (b_el(i, j) - b(i, j)) / std::abs(b(i, j));
        std::printf(
            "    a_%s elem %+.10f ref %+.10f rel err %+.2e   b_%s elem %+.10f ref %+.10f rel err "
            "%+.2e\n",
            n[i][j], a_el(i, j), a(i, j), ea, n[i][j], b_el(i, j), b(i, j), eb);
        EXPECT_LT(std::abs(ea), 1e-7);
        EXPECT_LT(std::abs(eb), 1e-7);
      }
    // The analytic element derivatives give the same matrices.
    const FilmForce f = jb.film(0, e0, V2::Zero(), om, 1, true);
    EXPECT_LT((-f.df_de * c / W - a).norm(), 1e-9 * a.norm());
    EXPECT_LT((-f.df_ded * c * om / W - b).norm(), 1e-9 * b.norm());
  }
}

namespace {

// A general marker state: a rotated, slowly moving bearing marker and a spinning,
// slightly tilted journal, in a scaled bearing (clearance 1 cm) so that the fixed
// finite-difference steps of derivatives_fd (1e-6) are small against the clearance.
void general_state(MarkerMotion m[2], double eps) {
  m[0].R = rotation_from_vector(Vec3(0.3, -0.2, 0.5));
  m[0].p = Vec3(0.1, 0.2, -0.3);
  m[0].v = Vec3(0.02, -0.01, 0.03);
  m[0].psi = Vec3(0.001, -0.002, 0.003);
  m[0].w = Vec3(0.4, -0.3, 0.2);
  const Vec3 x = m[0].R.col(0), y = m[0].R.col(1), z = m[0].R.col(2);
  m[1].p = m[0].p + 0.01 * eps * (0.6 * x - 0.8 * y) + 0.002 * z;
  m[1].v = m[0].v + 0.05 * x + 0.08 * y - 0.01 * z;
  m[1].psi = Vec3(0.02, 0.01, -0.015) + 1.3 * z;
  m[1].w = 120.0 * z + Vec3(0.5, -0.7, 0.3);
}

JournalBearingParams scaled_params(bool closed_form, int halves) {
  JournalBearingParams p;
  p.radius = 0.05;
  p.width = 0.04;
  p.clearance = 0.01;
  p.viscosity = 0.05;
  p.closed_form = closed_form;
  p.n_delta = 64;
  p.halves = halves;
  return p;
}

}  // namespace

// (4) Analytic derivatives against the finite-difference fallback.
TEST(JournalBearing, DerivativesMatchFiniteDifferences) {
  std::printf("(4) max |D - D_fd| / max |D|\n");
  for (bool closed_form : {true, false})
    for (int halves : {1, 2})
      for (double eps : {0.0, 0.3, 0.8, 0.93}) {
        JournalBearingParams p = scaled_params(closed_form, halves);
        if (eps > 0.9) {  // contact active (the FD step must stay small against the gap)
          p.eps_max = 0.9;
          p.contact_stiffness = 1e9;
        }
        const JournalBearing jb = make_bearing(p);
        MarkerMotion m[2];
        general_state(m, eps);
        Mat D(12, 24), Dfd(12, 24);
        jb.derivatives(0.1, m, D);
        jb.derivatives_fd(0.1, m, Dfd);
        const double err = (D - Dfd).cwiseAbs().maxCoeff() / D.cwiseAbs().maxCoeff();
        std::printf("  %-10s halves %d eps %.3f: %.2e\n", closed_form ? "ocvirk" : "quadrature",
                    halves, eps, err);
        EXPECT_LT(err, 1e-6);
        // Action and reaction, moment balance about the origin.
        MarkerLoad l[2];
        jb.evaluate(0.1, m, l);
        EXPECT_LT((l[0].F + l[1].F).norm(), 1e-12 * l[1].F.norm());
        const Vec3 Mo = l[0].M + l[1].M + m[0].p.cross(l[0].F) + m[1].p.cross(l[1].F);
        EXPECT_LT(Mo.norm(), 1e-12 * l[1].F.norm());
      }
}

// halves = 2: an aligned journal gets the full-width force, a tilted one a restoring moment.
TEST(JournalBearing, TwoHalvesGiveMoment) {
  const double om = 300.0, c = 50e-6;
  const JournalBearing one = make_bearing(base_params(true, 64, 1));
  const JournalBearing two = make_bearing(base_params(true, 64, 2));
  MarkerMotion m[2];
  m[1].p = Vec3(0.2 * c, -0.5 * c, 0.0);
  m[1].w = Vec3(0, 0, om);
  MarkerLoad l1[2], l2[2];
  one.evaluate(0, m, l1);
  two.evaluate(0, m, l2);
  EXPECT_LT((l1[1].F - l2[1].F).norm(), 1e-12 * l1[1].F.norm());
  EXPECT_LT(l2[1].M.norm(), 1e-12 * l1[1].F.norm() * 0.02);
  // Tilt about x by a small angle: the +z end moves towards -y.
  m[1].psi = Vec3(1e-3, 0.0, 0.0);
  two.evaluate(0, m, l2);
  std::printf("tilted journal: moment (%.4e, %.4e, %.4e) N m\n", l2[1].M.x(), l2[1].M.y(),
              l2[1].M.z());
  EXPECT_LT(l2[1].M.x(), 0.0);  // restoring
  std::vector<double> ch(two.channels().size());
  two.channel_values(0, m, ch.data());
  EXPECT_NEAR(ch[2], l2[1].M.x(), 1e-12 * std::abs(l2[1].M.x()));
}

// (5) Extreme film: named errors with the time, or a continuous contact force.
TEST(JournalBearing, ExtremeFilm) {
  const double om = 300.0;
  JournalBearingParams p = base_params(true);
  const double c = p.clearance;
  const JournalBearing jb = make_bearing(p, "main-3");
  MarkerMotion m[2];
  m[1].w = Vec3(0, 0, om);
  MarkerLoad l[2];
  m[1].p = Vec3(0.0, -0.979 * c, 0.0);
  EXPECT_NO_THROW(jb.evaluate(0.25, m, l));
  EXPECT_TRUE(l[1].F.allFinite());
  m[1].p = Vec3(0.0, -0.985 * c, 0.0);
  try {
    jb.evaluate(0.25, m, l);
    ADD_FAILURE() << "no error above eps_max";
  } catch (const RangeError& e) {  // recoverable: an integrator may cut the step
    const std::string msg = e.what();
    std::printf("eps > eps_max: %s\n", msg.c_str());
    EXPECT_NE(msg.find("'main-3'"), std::string::npos);
    EXPECT_NE(msg.find("t = 0.25 s"), std::string::npos);
    EXPECT_NE(msg.find("0.985"), std::string::npos);
  }
  Mat D(12, 24);
  EXPECT_THROW(jb.derivatives(0.25, m, D), RangeError);

  // With contact: finite everywhere below e = c, continuous at eps_max.
  p.contact_stiffness = 1e12;
  p.contact_exponent = 1.5;
  for (bool closed_form : {true, false}) {
    p.closed_form = closed_form;
    const JournalBearing jc = make_bearing(p, "main-3");
    const double e0 = p.eps_max * c;
    auto force = [&](double e) { return jc.film(0.5, V2(0.0, -e), V2::Zero(), om, 1.0, false).f; };
    const double d = 1e-12;
    const V2 jump = force(e0 + d) - force(e0 - d);
    const V2 slope = (force(e0 - d) - force(e0 - 3 * d)) / (2 * d);
    std::printf("contact onset (%s): jump %.3e N over 2e-12 m, film slope %.3e N/m\n",
                closed_form ? "ocvirk" : "quadrature", jump.norm(), slope.norm());
    EXPECT_LT(jump.norm(), 4 * d * slope.norm() + 1e-9 * force(e0).norm());
    for (double eps : {0.981, 0.99, 0.999, 0.99999, 1 - 1e-9}) {
      const V2 f = force(eps * c),
               fh = jc.hydro(V2(0.0, -eps * c), V2::Zero(), om, 1.0, false, closed_form).f;
      EXPECT_TRUE(f.allFinite()) << eps;
      const double fc_expected = p.contact_stiffness * std::pow((eps - p.eps_max) * c, 1.5);
      // (the film force grows without bound: compare to its rounding level)
      EXPECT_NEAR((f - fh).y(), fc_expected, 1e-9 * fc_expected + 1e-14 * fh.norm());
    }
    m[1].p = Vec3(0.0, -0.99 * c, 0.0);
    EXPECT_NO_THROW(jc.evaluate(0.5, m, l));
    EXPECT_TRUE(l[1].F.allFinite() && l[0].M.allFinite());
    // Film closed: always an error.
    m[1].p = Vec3(0.0, -1.0 * c, 0.0);
    try {
      jc.evaluate(0.5, m, l);
      ADD_FAILURE() << "no error with the film closed";
    } catch (const RunError& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find("'main-3'"), std::string::npos);
      EXPECT_NE(msg.find("film closed"), std::string::npos);
      EXPECT_NE(msg.find("t = 0.5 s"), std::string::npos);
    }
  }
}

// The declaration builds the element from validated parameters.
TEST(JournalBearing, Declaration) {
  const ElementType t = journal_bearing_element_type();
  EXPECT_EQ(t.type, "journal-bearing");
  ParamValues v;
  v.numbers["radius"] = {0.025};
  v.numbers["width"] = {0.02};
  v.numbers["clearance"] = {50e-6};
  v.numbers["viscosity"] = {0.02};
  v.texts["method"] = "quadrature";
  complete_params(t, v, "element 'jb'");
  auto e = t.make("jb", {0, 1}, v);
  auto* jb = dynamic_cast<JournalBearing*>(e.get());
  ASSERT_NE(jb, nullptr);
  EXPECT_FALSE(jb->params().closed_form);
  EXPECT_EQ(jb->params().n_delta, 64);
  EXPECT_EQ(jb->params().halves, 1);
  EXPECT_DOUBLE_EQ(jb->params().eps_max, 0.98);
  v.numbers["halves"] = {1.5};
  EXPECT_THROW(t.make("jb", {0, 1}, v), InputError);
  EXPECT_EQ(jb->channels().size(), 16u);
}

// (6) Rigid rotor on two bearings: static equilibrium below the oil-whirl
// threshold, half-speed whirl above it. The threshold is predicted from the
// linearised bearing coefficients (Lund's method: eigenvalues of the 4 x 4
// linear system as a function of speed).
namespace {
double brute_force_peak(const JournalBearingParams& p, const V2& e, const V2& W, int points) {
  double pmax = 0.0;
  for (int i = 0; i < points; ++i) {
    const double phi = 2 * M_PI * i / points;
    const V2 u(std::cos(phi), std::sin(phi));
    const double h = p.clearance - e.dot(u);
    pmax = std::max(pmax, 1.5 * p.viscosity * p.width * p.width * W.dot(u) / (h * h * h));
  }
  return pmax;
}
}  // namespace

// Output channels: bearing-frame force, eps, attitude, minimum film, peak pressure
// (checked against a brute-force scan of p = 6 eta x (B - x) (W . u) / h^3).
TEST(JournalBearing, Channels) {
  const JournalBearingParams p = base_params(false);
  const JournalBearing jb = make_bearing(p);
  const double c = p.clearance, om = 400.0;
  MarkerMotion m[2];
  m[0].R = rotation_from_vector(Vec3(0.0, 0.0, 0.4));  // bearing axes rotated about z
  m[1].p = m[0].R * Vec3(0.3 * c, -0.6 * c, 0.0);
  m[1].v = m[0].R * Vec3(0.01, 0.02, 0.0);
  m[1].w = Vec3(0, 0, om);
  std::vector<double> ch(jb.channels().size());
  jb.channel_values(0, m, ch.data());
  MarkerLoad l[2];
  jb.evaluate(0, m, l);
  const Vec3 F = m[0].R.transpose() * l[1].F;
  EXPECT_NEAR(ch[0], F.x(), 1e-12 * F.norm());
  EXPECT_NEAR(ch[1], F.y(), 1e-12 * F.norm());
  const double eps = std::sqrt(0.45);
  EXPECT_NEAR(ch[4], eps, 1e-12);
  EXPECT_NEAR(ch[5], std::atan2(-0.6, 0.3), 1e-12);
  EXPECT_NEAR(ch[6], c * (1 - eps), 1e-12 * c);
  const V2 e(0.3 * c, -0.6 * c), W = V2(0.01, 0.02) - 0.5 * om * V2(0.6 * c, 0.3 * c);
  const double pmax = brute_force_peak(p, e, W, 200000);
  std::printf("peak pressure %.6e Pa (scan %.6e Pa)\n", ch[7], pmax);
  EXPECT_NEAR(ch[7], pmax, 1e-6 * pmax);
  EXPECT_GE(ch[7], pmax);
  // the load in the journal's axes: a journal turned by 1.1 rad more than the
  // bearing about the bearing axis since t0 sees the bearing-frame force turned
  // by -1.1 rad (hand rotation of (fx, fy))
  m[0].psi = Vec3(0.0, 0.0, 0.4);
  m[1].psi = m[0].psi + 1.1 * m[0].R.col(2);
  jb.channel_values(0, m, ch.data());
  EXPECT_NEAR(ch[14], std::cos(1.1) * F.x() + std::sin(1.1) * F.y(), 1e-12 * F.norm());
  EXPECT_NEAR(ch[15], -std::sin(1.1) * F.x() + std::cos(1.1) * F.y(), 1e-12 * F.norm());
  EXPECT_NEAR(std::hypot(ch[14], ch[15]), F.norm(), 1e-12 * F.norm());
}

// Friction torque on the journal against an independent integral of the film's
// shear stress: with the film velocity u(y) = (1/2 eta) dp/ds (y^2 - y h) + U y/h
// between the bearing (y = 0) and the journal (y = h, surface speed U = om R),
// the shear on the journal is tau = eta U / h + (h / 2) dp/ds, and
//   T = -R int_0^2pi int_0^B tau R dx dphi,
// with int_0^B p dx = eta B^3 max(g, 0) / h^3 (p = 6 eta x (B - x) g / h^3,
// g = W . u). The Couette part is taken over the whole circumference (Petroff;
// at e = 0 it is Petroff's law T = -2 pi eta R^3 B om / c exactly), the
// pressure part over the loaded half. Trapezoid rule on 400000 angles; the
// element's closed form (the pressure part by parts, -(e x f)/2) must agree to
// 1e-7. Also the channels: ex, ey, the angle of the thinnest film and of the peak
// pressure (where p equals p_max, and a scan's best angle lies), friction power
// = -T om.
TEST(JournalBearing, FrictionTorqueMatchesTheShearIntegral) {
  const JournalBearingParams p = base_params(true);
  const JournalBearing jb = make_bearing(p);
  const double c = p.clearance, R = p.radius, B = p.width, eta = p.viscosity, om = 400.0;
  // Petroff at the centre
  EXPECT_NEAR(jb.friction_torque(V2::Zero(), om, V2::Zero(), 1.0),
              -2.0 * M_PI * eta * R * R * R * B * om / c, 1e-14 * eta * R * R * R * B * om / c);
  const int n = 400000;
  for (double eps : {0.2, 0.6, 0.9})
    for (double sq : {0.0, 0.03, -0.1}) {
      const V2 e = eps * c * V2(std::cos(1.0), std::sin(1.0));
      const V2 ed = sq * V2(std::cos(2.5), std::sin(2.5));
      const V2 W = ed - 0.5 * om * V2(-e.y(), e.x());
      // Couette over the whole (periodic) circumference; the pressure part over the
      // loaded half |phi - phi_W| <= pi/2 (g > 0), whose ends are kinks of p
      double T = 0.0;
      for (int i = 0; i < n; ++i) {
        const double phi = 2.0 * M_PI * i / n;
        const double h = c - e.dot(V2(std::cos(phi), std::sin(phi)));
        T -= R * (eta * om * R / h * B) * R * (2.0 * M_PI / n);  // int_0^B eta U / h dx
      }
      const double phiW = std::atan2(W.y(), W.x());
      for (int k = 0; k <= n; ++k) {
        const double phi = phiW - 0.5 * M_PI + M_PI * k / n, wk = (k == 0 || k == n) ? 0.5 : 1.0;
        const V2 u(std::cos(phi), std::sin(phi)), up(-u.y(), u.x());
        const double h = c - e.dot(u), hp = -e.dot(up), g = W.dot(u), gp = W.dot(up);
        // d/dphi of int_0^B p dx = eta B^3 g / h^3
        const double dP = eta * B * B * B * (gp / (h * h * h) - 3.0 * g * hp / (h * h * h * h));
        T -= R * (0.5 * h * dP / R) * R * wk * (M_PI / n);  // int_0^B (h/2) (1/R) dp/dphi dx
      }
      const V2 f = jb.hydro(e, ed, om, 1.0, false, true).f;
      const double Tc = jb.friction_torque(e, om, f, 1.0);
      std::printf("eps %.1f squeeze %5.2f: friction torque %.9e N m, shear integral %.9e N m\n",
                  eps, sq, Tc, T);
      EXPECT_NEAR(Tc, T, 1e-9 * std::abs(T)) << "eps " << eps << " sq " << sq;

      MarkerMotion m[2];
      m[1].p = Vec3(e.x(), e.y(), 0.0);
      m[1].v = Vec3(ed.x(), ed.y(), 0.0);
      m[1].w = Vec3(0, 0, om);
      std::vector<double> ch(jb.channels().size());
      ASSERT_EQ(ch.size(), 16u);
      jb.channel_values(0, m, ch.data());
      EXPECT_NEAR(ch[8], e.x(), 1e-15);
      EXPECT_NEAR(ch[9], e.y(), 1e-15);
      EXPECT_NEAR(ch[10], 1.0, 1e-12);  // the thinnest film lies along e
      EXPECT_NEAR(ch[12], T, 1e-7 * std::abs(T));
      EXPECT_NEAR(ch[13], -T * om, 1e-7 * std::abs(T * om));
      // the peak pressure's angle: p there is p_max, and a scan finds its maximum there
      const double a = ch[11];
      const V2 ua(std::cos(a), std::sin(a));
      const double ha = c - e.dot(ua);
      EXPECT_NEAR(1.5 * eta * B * B * W.dot(ua) / (ha * ha * ha), ch[7], 1e-9 * ch[7]);
      double best = 0.0, best_phi = 0.0;
      for (int i = 0; i < n; ++i) {
        const double phi = 2.0 * M_PI * i / n;
        const V2 u(std::cos(phi), std::sin(phi));
        const double h = c - e.dot(u), q = W.dot(u) / (h * h * h);
        if (q > best) best = q, best_phi = phi;
      }
      EXPECT_NEAR(std::remainder(a - best_phi, 2.0 * M_PI), 0.0, 1e-4);
    }
}

// The peak pressure (coarse scan, then safeguarded Newton on dq/dphi) against a
// brute-force scan over eccentricities up to 0.97, where the peak is sharp, and
// squeeze velocities that move it around the bearing.
TEST(JournalBearing, PeakPressureMatchesBruteForceScan) {
  const JournalBearingParams p = base_params(false);
  const JournalBearing jb = make_bearing(p);
  const double c = p.clearance, om = 400.0;
  std::vector<double> ch(jb.channels().size());
  int cases = 0;
  for (double eps : {0.05, 0.5, 0.9, 0.97})
    for (double dir : {0.0, 2.0, 4.0})
      for (double sq : {0.0, 0.05, -0.2}) {
        MarkerMotion m[2];
        const V2 e = eps * c * V2(std::cos(dir), std::sin(dir));
        const V2 ed = sq * V2(std::cos(dir + 1.0), std::sin(dir + 1.0));
        m[1].p = Vec3(e.x(), e.y(), 0.0);
        m[1].v = Vec3(ed.x(), ed.y(), 0.0);
        m[1].w = Vec3(0, 0, om);
        jb.channel_values(0, m, ch.data());
        const V2 W = ed - 0.5 * om * V2(-e.y(), e.x());
        const double pmax = brute_force_peak(p, e, W, 400000);
        EXPECT_NEAR(ch[7], pmax, 1e-6 * pmax) << "eps " << eps << " dir " << dir << " sq " << sq;
        EXPECT_GE(ch[7], pmax * (1.0 - 1e-12)) << "eps " << eps << " dir " << dir << " sq " << sq;
        ++cases;
      }
  EXPECT_EQ(cases, 36);
}

// A journal spinning about an axis far from the bearing axis (wrongly oriented
// bearing marker) is an error naming the bearing, not a silently wrong film.
TEST(JournalBearing, MisorientedSpinIsAnError) {
  const JournalBearingParams p = base_params(false);
  const JournalBearing jb = make_bearing(p);
  MarkerMotion m[2];
  m[1].p = Vec3(0.2 * p.clearance, 0.1 * p.clearance, 0.0);
  MarkerLoad l[2];
  for (double deg : {0.0, 20.0, 40.0, 90.0}) {
    const double a = deg * M_PI / 180;
    m[1].w = 300.0 * Vec3(std::sin(a), 0.0, std::cos(a));  // bearing axis = z
    if (deg < 30) {
      EXPECT_NO_THROW(jb.evaluate(0.01, m, l)) << deg;
    } else {
      try {
        jb.evaluate(0.01, m, l);
        ADD_FAILURE() << "spin " << deg << " deg off the axis accepted";
      } catch (const RunError& e) {
        EXPECT_NE(std::string(e.what()).find(jb.name()), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("off the bearing axis"), std::string::npos);
      }
    }
  }
}
