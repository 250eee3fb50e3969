// Oil whirl of a rigid rotor in two short journal bearings: above the threshold
// speed from the linearised coefficients (Lund's stability method; Friswell,
// Penny, Garvey, Lees, "Dynamics of Rotating Machines", CUP 2010) the
// simulated orbit grows at half the spin speed. Helpers:
// journal_bearing_support.h.
#include "journal_bearing_support.h"
#include "run/periodic.h"

namespace {

struct RotorCase {
  double mass = 200.0;  // [kg], carried by two equal bearings
  double g = 9.81;
  double half_span = 0.1;  // bearings at z = +-half_span
  JournalBearingParams bearing = base_params(true);
};

// Linear stability at speed om: equilibrium of one bearing under m g / 2, its
// K = -df/de and C = -df/ded, and the eigenvalues of m xdd + 2 C xd + 2 K x = 0.
struct Linear {
  double eps, growth, whirl;  // eps, max real part [1/s], |imag| of that eigenvalue [rad/s]
  V2 e_eq;
};
Linear linear_rotor(const RotorCase& rc, double om) {
  const JournalBearing jb = make_bearing(rc.bearing);
  const double W = 0.5 * rc.mass * rc.g;
  Linear r;
  r.e_eq = equilibrium(jb, om, W);
  r.eps = r.e_eq.norm() / rc.bearing.clearance;
  const FilmForce f = jb.film(0, r.e_eq, V2::Zero(), om, 1.0, true);
  Eigen::Matrix4d A = Eigen::Matrix4d::Zero();
  A.topRightCorner<2, 2>() = M2::Identity();
  A.bottomLeftCorner<2, 2>() = 2.0 * f.df_de / rc.mass;
  A.bottomRightCorner<2, 2>() = 2.0 * f.df_ded / rc.mass;
  const Eigen::Vector4cd ev = A.eigenvalues();
  r.growth = -1e300;
  for (int i = 0; i < 4; ++i)
    if (ev[i].real() > r.growth) r.growth = ev[i].real(), r.whirl = std::abs(ev[i].imag());
  return r;
}

double onset_speed(const RotorCase& rc, double lo, double hi) {
  EXPECT_LT(linear_rotor(rc, lo).growth, 0.0);
  EXPECT_GT(linear_rotor(rc, hi).growth, 0.0);
  for (int i = 0; i < 80; ++i) {
    const double mid = 0.5 * (lo + hi);
    (linear_rotor(rc, mid).growth < 0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace

namespace {

// Point-mass-like rotor: two rings of 4 nodes at z = +-half_span (centre of mass at
// the origin), only the three rigid translation modes kept.
std::shared_ptr<ModalBody> rotor_body(const RotorCase& rc) {
  auto b = std::make_shared<ModalBody>();
  b->name = "rotor";
  const int N = 8;
  b->s.resize(N, 3);
  std::vector<Triplet> t;
  for (int i = 0; i < N; ++i) {
    const double ang = 0.5 * M_PI * (i % 4), z = i < 4 ? -rc.half_span : rc.half_span;
    b->s.row(i) << 0.05 * std::cos(ang), 0.05 * std::sin(ang), z;
    b->node_ids.push_back(i + 1);
    t.emplace_back(i, i, rc.mass / N);
  }
  b->mass.resize(N, N);
  b->mass.setFromTriplets(t.begin(), t.end());
  b->modes = rigid_basis(b->s, b->mass);
  b->eigenvalues = Vec::Zero(6);
  b->damping = Vec::Zero(6);
  b->kinds.assign(6, ModeKind::Rigid);
  b->node_sets["ring1"] = {1, 2, 3, 4};
  b->node_sets["ring2"] = {5, 6, 7, 8};
  return std::make_shared<ModalBody>(b->select_modes({0, 1, 2}));
}

struct Response {
  std::vector<double> t;
  std::vector<V2> d;  // journal centre of bearing 1 minus the equilibrium (bearing plane)
  V2 e_end;           // final eccentricity vector
};

// Runs the rotor at speed om from e_eq + d0 (at rest in G) with IDA. spin_lof:
// the rotor body rides on a spin LOF (paper's crankshaft set-up); otherwise the
// body is on a fixed LOF and the bearings get the spin as journal_speed.
// The rotor's model at speed om, started from e0 at rest in G (run_rotor).
void build_rotor(Model& model, const RotorCase& rc, double om, const V2& e0, bool spin_lof) {
  model.gravity = Vec3(0.0, -rc.g, 0.0);
  auto body = rotor_body(rc);
  const Lof lof = spin_lof
                      ? Lof::spin(Vec3::Zero(), Mat3::Identity(), Vec3::UnitZ(), 0.0, {0.0}, {om})
                      : Lof::fixed(Vec3::Zero(), Mat3::Identity());
  model.add_body("rotor", body, lof);
  const Vec3 z1(0, 0, -rc.half_span), z2(0, 0, rc.half_span);
  const int j1 =
      model.add_marker(make_set_marker("j1", 0, *body, body->node_sets.at("ring1"), {}, &z1));
  const int j2 =
      model.add_marker(make_set_marker("j2", 0, *body, body->node_sets.at("ring2"), {}, &z2));
  const int b1 = model.add_marker(make_ground_marker("b1", z1, Mat3::Identity()));
  const int b2 = model.add_marker(make_ground_marker("b2", z2, Mat3::Identity()));
  JournalBearingParams p = rc.bearing;
  p.journal_speed = spin_lof ? 0.0 : om;
  p.contact_stiffness = 1e12;  // keep large whirl orbits finite
  model.add_element(std::make_unique<JournalBearing>("jb1", std::vector<int>{b1, j1}, p));
  model.add_element(std::make_unique<JournalBearing>("jb2", std::vector<int>{b2, j2}, p));
  // Translation modes: u = q / sqrt(m) in L components (L = G at t = 0).
  const double sm = std::sqrt(rc.mass);
  Body& B = model.bodies()[0];
  B.q0 = Vec3(sm * e0.x(), sm * e0.y(), 0.0);
  // At rest in G: on the spin LOF the modal velocity cancels the frame's rotation.
  if (spin_lof) B.v0 = -sm * om * Vec3::UnitZ().cross(Vec3(e0.x(), e0.y(), 0.0));
}

Response run_rotor(const RotorCase& rc, double om, const V2& e_eq, const V2& d0, double t_end,
                   double dt_out, bool spin_lof, double stop_amplitude = 1e300) {
  Model model;
  build_rotor(model, rc, om, e_eq + d0, spin_lof);
  const int j1 = 0, b1 = 2;  // markers j1, j2, b1, b2 in that order
  System sys(model);
  auto integ = make_integrator("ida");
  IntegratorSettings st;
  st.rtol = 1e-9;
  st.atol = 1e-13;
  Vec q, v;
  sys.initial_state(q, v);
  integ->init(sys, 0.0, q, v, st);
  Response r;
  for (double t = dt_out; t <= t_end + 1e-12; t += dt_out) {
    integ->advance(t, false, q, v);
    sys.update_markers(t, q.data(), v.data());
    const Vec3 d = sys.motion(j1).p - sys.motion(b1).p;
    r.t.push_back(t);
    r.d.push_back(V2(d.x(), d.y()) - e_eq);
    r.e_end = V2(d.x(), d.y());
    if (r.d.back().norm() > stop_amplitude) break;
  }
  return r;
}

// Growth rate (log-linear fit of the per-period maximum of |d|, after t_skip) and
// whirl frequency (zero crossings of d_x) of a response.
void measure(const Response& r, double period, double t_skip, double& growth, double& whirl) {
  std::vector<double> tm, lm;
  std::size_t i = 0;
  while (i < r.t.size() && r.t[i] < t_skip) ++i;
  while (i < r.t.size()) {
    const double t0 = r.t[i];
    double mx = 0.0;
    std::size_t j = i;
    for (; j < r.t.size() && r.t[j] < t0 + period; ++j) mx = std::max(mx, r.d[j].norm());
    if (j >= r.t.size()) break;
    tm.push_back(t0 + 0.5 * period);
    lm.push_back(std::log(mx));
    i = j;
  }
  double st = 0, sl = 0, stt = 0, stl = 0;
  const double n = static_cast<double>(tm.size());
  for (std::size_t k = 0; k < tm.size(); ++k)
    st += tm[k], sl += lm[k], stt += tm[k] * tm[k], stl += tm[k] * lm[k];
  growth = (n * stl - st * sl) / (n * stt - st * st);
  double first = -1, last = -1;
  int crossings = 0;
  for (std::size_t k = 1; k < r.t.size(); ++k) {
    if (r.t[k] < t_skip) continue;
    if ((r.d[k - 1].x() < 0) != (r.d[k].x() < 0)) {
      const double tc =
          r.t[k - 1] + (r.t[k] - r.t[k - 1]) * r.d[k - 1].x() / (r.d[k - 1].x() - r.d[k].x());
      if (first < 0) first = tc;
      last = tc;
      ++crossings;
    }
  }
  whirl = M_PI * (crossings - 1) / (last - first);
}

}  // namespace

TEST(JournalBearing, RigidRotorWhirl) {
  RotorCase rc;
  const double om_th = onset_speed(rc, 300.0, 3000.0);
  const Linear at_th = linear_rotor(rc, om_th);
  std::printf("(6) predicted whirl onset: %.4f rad/s (eps %.4f, whirl ratio %.4f)\n", om_th,
              at_th.eps, at_th.whirl / om_th);
  const double c = rc.bearing.clearance;

  // Below the threshold: settles at the static equilibrium of the quartic.
  {
    const double om = 0.8 * om_th;
    const Linear l = linear_rotor(rc, om);
    const Response r = run_rotor(rc, om, l.e_eq, V2(0.1 * c, 0.05 * c), 1.0, 1e-3, false);
    const JournalBearingParams& p = rc.bearing;
    const double Ss =
        2 * p.radius * om * p.viscosity * std::pow(p.width, 3) / (8 * c * c * 0.5 * rc.mass * rc.g);
    const double eps_ref = eps_from_quartic(Ss);
    const double phi_ref = std::atan(M_PI * std::sqrt(1 - eps_ref * eps_ref) / (4 * eps_ref));
    const double eps = r.e_end.norm() / c, phi = std::acos(-r.e_end.y() / r.e_end.norm());
    std::printf(
        "  om = %.1f (0.8 onset): settled eps %.9f (quartic %.9f, err %.2e), attitude %.9f "
        "(ref %.9f, err %.2e)\n",
        om, eps, eps_ref, eps - eps_ref, phi, phi_ref, phi - phi_ref);
    EXPECT_NEAR(eps, eps_ref, 1e-6);
    EXPECT_NEAR(phi, phi_ref, 1e-6);
  }

  // Growth rates just below and above the threshold: measured onset by interpolation.
  std::vector<double> oms = {0.95 * om_th, 1.05 * om_th}, gm;
  for (double om : oms) {
    const Linear l = linear_rotor(rc, om);
    const double period = 2 * M_PI / l.whirl;
    const Response r =
        run_rotor(rc, om, l.e_eq, V2(2e-4 * c, 0.0), 60 * period, period / 50, false);
    double g, w;
    measure(r, period, 10 * period, g, w);
    std::printf(
        "  om = %.1f: growth measured %+.4f 1/s, linear %+.4f 1/s; whirl %.3f rad/s "
        "(ratio %.4f), linear %.3f rad/s\n",
        om, g, l.growth, w, w / om, l.whirl);
    EXPECT_NEAR(g, l.growth, 0.02 * std::abs(l.growth) + 0.05);
    EXPECT_NEAR(w, l.whirl, 2e-3 * l.whirl);
    gm.push_back(g);
  }
  const double om_meas = oms[0] - gm[0] * (oms[1] - oms[0]) / (gm[1] - gm[0]);
  std::printf("  whirl onset: measured %.3f rad/s, predicted %.3f rad/s, rel err %+.2e\n", om_meas,
              om_th, om_meas / om_th - 1);
  EXPECT_NEAR(om_meas, om_th, 5e-3 * om_th);

  // Well above the threshold: the orbit grows and whirls at about half speed;
  // the same on a spin LOF (journal spin from the body's frame, not a parameter).
  for (bool spin : {false, true}) {
    const double om = 1.3 * om_th;
    const Linear l = linear_rotor(rc, om);
    const double period = 2 * M_PI / l.whirl;
    const Response r =
        run_rotor(rc, om, l.e_eq, V2(1e-3 * c, 0.0), 80 * period, period / 50, spin, 0.3 * c);
    double g, w;
    measure(r, period, 5 * period, g, w);
    std::printf(
        "  om = %.1f (1.3 onset, %s LOF): growth %+.3f 1/s (linear %+.3f), whirl ratio "
        "%.4f (linear %.4f), final |d|/c %.3f at t = %.3f s\n",
        om, spin ? "spin" : "fixed", g, l.growth, w / om, l.whirl / om, r.d.back().norm() / c,
        r.t.back());
    EXPECT_GT(g, 0.0);
    EXPECT_NEAR(w / om, l.whirl / om, 0.02);
    EXPECT_GT(w / om, 0.4);
    EXPECT_LT(w / om, 0.55);
  }
}

// The Floquet multipliers of the rotor's periodic state on a spin LOF (its
// static equilibrium, turning in the frame: gravity turns once per
// revolution) by evas periodic's shooting Newton: the largest modulus crosses 1
// where the linearized threshold has the growth rate cross 0, and equals
// exp(growth T) (a periodic change of coordinates leaves the multipliers of
// the fixed frame's linear system, exp(lambda T)).
TEST(JournalBearing, FloquetMultiplierCrossesTheUnitCircleAtTheWhirlOnset) {
  RotorCase rc;
  const double om_th = onset_speed(rc, 300.0, 3000.0);
  IntegratorSettings st;
  st.rtol = 1e-10;
  st.atol = 1e-14;
  std::vector<double> oms, mods;
  for (double f : {0.9, 0.97, 1.03, 1.1}) {
    const double om = f * om_th, T = 2 * M_PI / om;
    const Linear l = linear_rotor(rc, om);
    Model model;
    build_rotor(model, rc, om, l.e_eq, true);
    System sys(model);
    Vec q0, v0;
    sys.initial_state(q0, v0);
    run::PeriodicOptions po;
    po.method = run::PeriodicMethod::newton;
    po.tol = 1e-8;
    const run::PeriodicResult r = run::find_periodic(sys, 0.0, T, q0, v0, st, po);
    ASSERT_TRUE(r.converged) << f << ": " << r.message;
    // the largest multiplier but the axial translation's: the bearings hold
    // the rotor in x and y only, and a free translation has multiplier 1
    double mu = 0.0;
    for (const auto& m : r.multipliers)
      if (std::abs(m.mu - 1.0) > 1e-6) mu = std::max(mu, std::abs(m.mu));
    ASSERT_GT(mu, 0.0);
    std::printf("  om = %.1f (%.2f onset): largest |mu| %.6f, exp(growth T) %.6f\n", om, f, mu,
                std::exp(l.growth * T));
    EXPECT_NEAR(mu, std::exp(l.growth * T), 1e-4);
    EXPECT_EQ(mu < 1.0, f < 1.0) << f;
    oms.push_back(om);
    mods.push_back(mu);
  }
  // the crossing of |mu| = 1 between the two nearest speeds, against the onset
  const double om_cross = oms[1] + (1.0 - mods[1]) * (oms[2] - oms[1]) / (mods[2] - mods[1]);
  std::printf("  |mu| = 1 at %.3f rad/s, linearized onset %.3f rad/s\n", om_cross, om_th);
  EXPECT_NEAR(om_cross, om_th, 2e-3 * om_th);
}

// Largest p = 6 eta x (B - x) (W . u) / h^3 at the mid-plane over `points`
// angles around the bearing (short-bearing pressure, the reference of the
// peak-pressure channel).
