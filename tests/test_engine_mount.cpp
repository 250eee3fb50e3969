// Engine mount (elements/engine_mount.h).
// References:
//  - analytic derivatives against Element::derivatives_fd (central differences);
//  - preload and action = reaction by hand;
//  - static sag of a rigid block (six rigid modes of a box of lumped masses) on
//    four identical mounts at the bottom corners under gravity: by symmetry a
//    pure vertical translation d with 4 f_z(d) = -m g, f_z the polynomial
//    k1 d + k2 d^2 + k3 d^3, solved by hand as a scalar cubic; the model is
//    solved by Newton on the System's f(q) = 0 with K from force_jacobian;
//  - the six rigid-body mount frequencies: eig of the System's K (M = I) against
//    a hand-assembled rigid-body model (M = diag(m I, J), K = sum T_i^T K_i T_i,
//    T_i = [I, -skew(r_i - c)], K_i = R_i diag(k) R_i^T, J by direct sums), and
//    the damped frequencies from a free-decay simulation (IDA) by the peak of the
//    Hann-windowed DFT of each modal coordinate;
//  - the System's sparse Jacobian (K, C) of a coupled crank/block model with all
//    three elements (mount, thrust bearing in contact, belt with the crank pulley
//    on a spinning LOF) against central differences of the System's f, as in
//    tests/test_system_jacobian.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "elements/belt.h"
#include "elements/engine_mount.h"
#include "elements/thrust_bearing.h"
#include "fd_check.h"
#include "integrators/integrator.h"
#include "random_body.h"
#include "solver/system.h"

using namespace evas;

namespace {

constexpr double kPi = 3.14159265358979323846;

// Rigid box: 8 corner masses of m/8, x in {-a, a}, y in {-b, b}, z in {0, h}.
std::shared_ptr<ModalBody> box_body(double m, double a, double b, double h) {
  auto body = std::make_shared<ModalBody>();
  body->name = "block";
  body->s.resize(8, 3);
  std::vector<Triplet> t;
  int i = 0;
  for (double z : {0.0, h})
    for (double y : {-b, b})
      for (double x : {-a, a}) {
        body->s.row(i) << x, y, z;
        body->node_ids.push_back(1 + i);
        t.emplace_back(i, i, m / 8);
        ++i;
      }
  body->mass.resize(8, 8);
  body->mass.setFromTriplets(t.begin(), t.end());
  body->modes = rigid_basis(body->s, body->mass);
  body->eigenvalues = Vec::Zero(6);
  body->damping = Vec::Zero(6);
  body->kinds.assign(6, ModeKind::Rigid);
  return body;
}

struct MountSetup {
  std::unique_ptr<Model> model;
  std::vector<int> block_markers;
  std::vector<Mat3> axes;  // mount axes in G
  std::vector<Vec3> points;
};

// Four mounts at the bottom corners (nodes 1..4), mount axes tilted about x by
// +/- tilt (a V arrangement), the same law on each.
MountSetup mounted_block(double m, const std::array<ForceLaw, 3>& laws, const Vec3& damping,
                         double tilt, bool preload) {
  MountSetup S;
  S.model = std::make_unique<Model>();
  S.model->gravity = Vec3(0, 0, -9.81);
  auto body = box_body(m, 0.3, 0.2, 0.35);
  S.model->add_body("block", body, Lof::fixed(Vec3::Zero(), Mat3::Identity()));
  for (int c = 0; c < 4; ++c) {
    const long id = 1 + c;
    const Vec3 p = body->s.row(c).transpose();
    const int mb =
        S.model->add_marker(make_node_marker("block." + std::to_string(c), 0, *body, id));
    const int mg =
        S.model->add_marker(make_ground_marker("ground." + std::to_string(c), p, Mat3::Identity()));
    const double sgn = p.y() > 0 ? 1.0 : -1.0;
    const Vec3 orient(sgn * tilt, 0, 0);
    const Mat3 R = rotation_from_vector(orient);
    // Preload: each mount carries m g / 4 vertically at zero deflection (mount axes).
    const Vec3 pre = preload ? Vec3(R.transpose() * Vec3(0, 0, m * 9.81 / 4)) : Vec3::Zero();
    S.model->add_element(std::make_unique<EngineMount>("mount" + std::to_string(c),
                                                       std::vector<int>{mg, mb}, laws, damping, pre,
                                                       Vec3::Zero(), Vec3::Zero(), orient));
    S.block_markers.push_back(mb);
    S.axes.push_back(R);
    S.points.push_back(p);
  }
  return S;
}

// Newton on f(q) = 0 (v = 0) with the System's K; returns iterations used.
int newton_static(System& sys, Vec& q, double tol) {
  const int n = sys.size();
  Vec v = Vec::Zero(n), f(n);
  SpMat K = sys.jacobian_pattern(), C = sys.jacobian_pattern();
  for (int it = 0; it < 50; ++it) {
    sys.force(0.0, q.data(), v.data(), f.data());
    if (f.norm() < tol) return it;
    sys.force_jacobian(0.0, q.data(), v.data(), K, C);
    q -= Mat(K).partialPivLu().solve(f);
  }
  return -1;
}

MarkerMotion generic_pair(MarkerMotion* m) {
  m[0].p = Vec3(0.1, 0.2, 0.3);
  m[1].p = Vec3(0.102, 0.197, 0.304);
  m[0].v = Vec3(0.1, 0.2, -0.1);
  m[1].v = Vec3(-0.2, 0.05, 0.2);
  m[0].psi = Vec3(0.01, 0.02, 0.05);
  m[1].psi = Vec3(0.0, -0.01, 0.07);
  m[0].w = Vec3(3, 2, 1);
  m[1].w = Vec3(0, 1, 2);
  m[0].R = rotation_from_vector(Vec3(0.3, -0.2, 0.5));
  return m[0];
}

// |X(f)| of the Hann-windowed samples y_n at t_n = n dt.
double dft_mag(const std::vector<double>& y, double dt, double f) {
  const std::size_t N = y.size();
  std::complex<double> X = 0;
  for (std::size_t n = 0; n < N; ++n) {
    const double w = 0.5 * (1 - std::cos(2 * kPi * n / (N - 1)));
    X += w * y[n] * std::polar(1.0, -2 * kPi * f * n * dt);
  }
  return std::abs(X);
}

// Frequency of the spectral peak: coarse scan then golden-section refinement.
double peak_frequency(const std::vector<double>& y, double dt, double fmin, double fmax) {
  const double T = dt * (y.size() - 1), df = 0.25 / T;
  double best = fmin, bestv = -1;
  for (double f = fmin; f <= fmax; f += df) {
    const double v = dft_mag(y, dt, f);
    if (v > bestv) bestv = v, best = f;
  }
  double lo = best - df, hi = best + df;
  const double g = (std::sqrt(5.0) - 1) / 2;
  double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
  double f1 = dft_mag(y, dt, x1), f2 = dft_mag(y, dt, x2);
  for (int it = 0; it < 60; ++it) {
    if (f1 > f2) {
      hi = x2, x2 = x1, f2 = f1;
      x1 = hi - g * (hi - lo), f1 = dft_mag(y, dt, x1);
    } else {
      lo = x1, x1 = x2, f1 = f2;
      x2 = lo + g * (hi - lo), f2 = dft_mag(y, dt, x2);
    }
  }
  return 0.5 * (lo + hi);
}

}  // namespace

TEST(engine_mount, DerivativesMatchFiniteDifferences) {
  std::array<ForceLaw, 3> poly = {ForceLaw::polynomial({2e5, 3e7, 4e9}),
                                  ForceLaw::polynomial({1.5e5, 0.0, 8e9}),
                                  ForceLaw::polynomial({4e5, -5e7, 2e10})};
  const std::vector<double> d = {-6e-3, -3e-3, -1e-3, 0.0, 1e-3, 3e-3, 6e-3};
  const std::vector<double> F = {-5000, -1200, -300, 0, 300, 1200, 5000};
  std::array<ForceLaw, 3> tab = {ForceLaw::table(d, F, ForceLaw::Interp::Pchip),
                                 ForceLaw::table(d, F, ForceLaw::Interp::Linear),
                                 ForceLaw::table(d, F, ForceLaw::Interp::Pchip)};
  double worst = 0;
  for (const auto* laws : {&poly, &tab}) {
    EngineMount em("m", {0, 1}, *laws, Vec3(100, 200, 300), Vec3(10, -20, 500), Vec3(1e3, 2e3, 3e3),
                   Vec3(1, 2, 3), Vec3(0.1, -0.3, 0.2), Vec3(0.001, 0, -0.0005));
    MarkerMotion m[2];
    generic_pair(m);
    Mat D(12, 24), Dfd(12, 24);
    em.derivatives(0.0, m, D);
    em.derivatives_fd(0.0, m, Dfd);
    const double e = (D - Dfd).cwiseAbs().maxCoeff() / D.cwiseAbs().maxCoeff();
    worst = std::max(worst, e);
    // Balance: forces and moments about the origin.
    MarkerLoad l[2];
    em.evaluate(0.0, m, l);
    EXPECT_LT((l[0].F + l[1].F).norm(), 1e-9);
    const Vec3 Mo = l[0].M + l[1].M + m[0].p.cross(l[0].F) + m[1].p.cross(l[1].F);
    EXPECT_LT(Mo.norm(), 1e-9 * l[1].F.norm());
  }
  std::cout << "engine mount D vs derivatives_fd: max rel. error " << worst << "\n";
  EXPECT_LT(worst, 1e-6);
}

TEST(engine_mount, PreloadAndDeclaration) {
  const ElementType t = engine_mount_element_type();
  ParamValues v;
  v.numbers["k_x"] = {1e5};
  v.numbers["k_y"] = {1e5};
  v.numbers["k_z"] = {2e5, 0, 1e9};
  v.numbers["preload"] = {0, 0, 490.5};
  v.numbers["orientation"] = {0, 0, 0.5};
  complete_params(t, v, "test");
  for (const auto& p : t.params)
    if (p.kind != ParamSpec::Kind::Text && !p.default_value.empty())
      check_param(p, p.default_value, "defaults");
  auto el = t.make("m", {0, 1}, v);
  MarkerMotion m[2];
  m[0].p = m[1].p = Vec3(0.3, 0.2, 0.0);
  m[0].R = rotation_from_vector(Vec3(0, 0.1, 0));
  MarkerLoad l[2];
  el->evaluate(0.0, m, l);
  // Zero deflection: the mount pushes the block with the preload (mount axes).
  const Mat3 R = m[0].R * rotation_from_vector(Vec3(0, 0, 0.5));
  EXPECT_LT((l[1].F - R * Vec3(0, 0, 490.5)).norm(), 1e-9);
  // Deflection of 2 mm down along the mount z: F_z = 490.5 - (2e5 (-2e-3) + 1e9 (-8e-9)).
  m[1].p = m[0].p + R * Vec3(0, 0, -2e-3);
  std::vector<double> out(el->channels().size());
  el->channel_values(0.0, m, out.data());
  EXPECT_NEAR(out[2], 490.5 + 400.0 + 8.0, 1e-9);
  EXPECT_NEAR(out[8], -2e-3, 1e-15);
  // Table law with a bad table names the element and the axis.
  ParamValues tv;
  tv.texts["law"] = "table";
  tv.numbers["table_x"] = {0, 0, 1e-3, 100};
  tv.numbers["table_y"] = {0, 0, 1e-3, 100};
  tv.numbers["table_z"] = {0, 0, 0, 100};
  complete_params(t, tv, "test");
  try {
    t.make("front", {0, 1}, tv);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("front"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("table_z"), std::string::npos);
  }
}

TEST(engine_mount, StaticSagOfRigidBlockNewton) {
  const double m = 200.0, g = 9.81, k1 = 2e5, k2 = -2e7, k3 = 5e9;
  const std::array<ForceLaw, 3> laws = {ForceLaw::polynomial({1e5}), ForceLaw::polynomial({1.5e5}),
                                        ForceLaw::polynomial({k1, k2, k3})};
  MountSetup S = mounted_block(m, laws, Vec3::Zero(), 0.0, false);
  System sys(*S.model);
  Vec q = Vec::Zero(sys.size());
  const int its = newton_static(sys, q, 1e-10);
  ASSERT_GE(its, 0);
  // Hand: 4 (k1 d + k2 d^2 + k3 d^3) = -m g, scalar Newton from the linear sag.
  double d = -m * g / (4 * k1);
  for (int i = 0; i < 50; ++i)
    d -= (k1 * d + k2 * d * d + k3 * d * d * d + m * g / 4) / (k1 + 2 * k2 * d + 3 * k3 * d * d);
  Vec v = Vec::Zero(sys.size());
  sys.update_markers(0.0, q.data(), v.data());
  double err = 0, side = 0;
  for (int c = 0; c < 4; ++c) {
    const int mk = S.block_markers[c];
    const Vec3 u = sys.motion(mk).p - S.model->markers()[mk].c;
    err = std::max(err, std::abs(u.z() - d));
    side = std::max(side, u.head<2>().norm());
  }
  std::cout << "static sag: Newton " << its << " iterations, sag " << -d * 1e3
            << " mm (linear would be " << m * g / (4 * k1) * 1e3 << " mm), max |sag - hand| " << err
            << " m, max horizontal " << side << " m\n";
  EXPECT_LT(err, 1e-12);
  EXPECT_LT(side, 1e-12);
  // With preload m g / 4 the block sits at its reference position: f(0) = 0.
  MountSetup P = mounted_block(m, laws, Vec3::Zero(), 0.3, true);
  System sp(*P.model);
  Vec q0 = Vec::Zero(sp.size()), f(sp.size());
  sp.force(0.0, q0.data(), q0.data(), f.data());
  std::cout << "preloaded (inclined mounts): |f(0)| = " << f.norm() << "\n";
  EXPECT_LT(f.norm(), 1e-9);
}

TEST(engine_mount, RigidBodyFrequenciesEigAndSimulation) {
  const double m = 200.0, beta = 2e-4, tilt = 0.35;
  const Vec3 k(1.2e5, 1.8e5, 3e5);
  const std::array<ForceLaw, 3> laws = {
      ForceLaw::polynomial({k.x()}), ForceLaw::polynomial({k.y()}), ForceLaw::polynomial({k.z()})};
  MountSetup S = mounted_block(m, laws, beta * k, tilt, true);
  System sys(*S.model);
  const int n = sys.size();
  ASSERT_EQ(n, 6);
  Vec q = Vec::Zero(n), v = Vec::Zero(n);
  SpMat Ks = sys.jacobian_pattern(), Cs = sys.jacobian_pattern();
  sys.force_jacobian(0.0, q.data(), v.data(), Ks, Cs);
  const Mat K = Mat(Ks);
  Eigen::SelfAdjointEigenSolver<Mat> es(0.5 * (K + K.transpose()));
  const Vec lam = es.eigenvalues();
  const Mat Phi = es.eigenvectors();

  // Hand-assembled rigid-body model.
  const auto& body = *S.model->bodies()[0].data;
  Vec3 c = Vec3::Zero();
  double mt = 0;
  for (int i = 0; i < 8; ++i) {
    mt += body.mass.coeff(i, i);
    c += body.mass.coeff(i, i) * body.s.row(i).transpose();
  }
  c /= mt;
  Mat3 J = Mat3::Zero();
  for (int i = 0; i < 8; ++i) {
    const Vec3 r = body.s.row(i).transpose() - c;
    J += body.mass.coeff(i, i) * (r.squaredNorm() * Mat3::Identity() - r * r.transpose());
  }
  Mat Mh = Mat::Zero(6, 6), Kh = Mat::Zero(6, 6);
  Mh.topLeftCorner(3, 3) = mt * Mat3::Identity();
  Mh.bottomRightCorner(3, 3) = J;
  for (int i = 0; i < 4; ++i) {
    Eigen::Matrix<double, 3, 6> T;
    T << Mat3::Identity(), -skew(S.points[i] - c);
    const Mat3 Ki = S.axes[i] * k.asDiagonal() * S.axes[i].transpose();
    Kh += T.transpose() * Ki * T;
  }
  Eigen::GeneralizedSelfAdjointEigenSolver<Mat> gs(Kh, Mh);
  const Vec lamh = gs.eigenvalues();
  double eig_err = 0;
  std::cout << "mount frequencies [Hz]: system eig / hand rigid-body eig\n";
  for (int i = 0; i < 6; ++i) {
    eig_err = std::max(eig_err, std::abs(lam[i] - lamh[i]) / lamh[i]);
    std::cout << "  " << std::sqrt(lam[i]) / (2 * kPi) << " / " << std::sqrt(lamh[i]) / (2 * kPi)
              << "\n";
  }
  std::cout << "max relative eigenvalue difference " << eig_err << "\n";
  EXPECT_LT(eig_err, 1e-10);
  // The damping is proportional (C = beta K): check, then zeta_k = beta omega_k / 2.
  EXPECT_LT((Mat(Cs) - beta * K).norm(), 1e-9 * beta * K.norm());

  // Free decay after an impulse: initial velocity exciting all six modes.
  S.model->bodies()[0].v0 = Phi * Vec::Constant(n, 0.05);
  auto integ = make_integrator("ida");
  IntegratorSettings set;
  set.rtol = 1e-9;
  set.atol = 1e-12;
  Vec q0, v0;
  sys.initial_state(q0, v0);
  integ->init(sys, 0.0, q0, v0, set);
  const double dt = 1e-3, Tend = 4.0;
  std::vector<double> outs;
  for (int i = 1; i * dt <= Tend + 1e-12; ++i) outs.push_back(i * dt);
  std::vector<std::vector<double>> eta(n);
  for (int k2 = 0; k2 < n; ++k2) eta[k2].push_back(0.0);  // q(0) = 0
  integrate(*integ, sys, 0.0, outs, [&](double, const Vec& qq, const Vec&) {
    const Vec e = Phi.transpose() * qq;
    for (int k2 = 0; k2 < n; ++k2) eta[k2].push_back(e[k2]);
  });
  const IntegratorStats st = integ->stats();
  double sim_err = 0;
  std::cout << "free decay (IDA, " << st.steps << " steps): mode, f_sim [Hz], f_d from eig [Hz]\n";
  for (int i = 0; i < n; ++i) {
    const double w = std::sqrt(lam[i]), zeta = beta * w / 2;
    const double fd = w * std::sqrt(1 - zeta * zeta) / (2 * kPi);
    const double fs = peak_frequency(eta[i], dt, 0.5, 60.0);
    sim_err = std::max(sim_err, std::abs(fs - fd) / fd);
    std::cout << "  " << i << "  " << fs << "  " << fd << "\n";
  }
  std::cout << "max relative frequency error (simulation vs eig) " << sim_err << "\n";
  EXPECT_LT(sim_err, 1e-3);
}

TEST(engine_mount, SystemJacobianWithThrustBearingAndBelt) {
  Model model;
  model.gravity = Vec3(0, 0, -9.81);
  auto a = std::make_shared<ModalBody>(test_bodies::random_body(20, 3, 11));
  auto b = std::make_shared<ModalBody>(test_bodies::random_body(25, 4, 12));
  model.add_body("crank", a,
                 Lof::spin(Vec3::Zero(), Mat3::Identity(), Vec3::UnitX(), 0.3, {0.0}, {314.0}));
  model.add_body("block", b, Lof::fixed(Vec3(0, 0.01, 0), Mat3::Identity()));
  const int pc =
      model.add_marker(make_set_marker("crank.pulley", 0, *a, a->node_sets.at("first4"), {}));
  const int pb1 = model.add_marker(make_node_marker("block.alt", 1, *b, b->node_ids[7]));
  const int pb2 = model.add_marker(make_node_marker("block.pump", 1, *b, b->node_ids[12]));
  const int th =
      model.add_marker(make_set_marker("block.thrust", 1, *b, b->node_sets.at("first4"), {}));
  const int mb =
      model.add_marker(make_set_marker("block.mount", 1, *b, b->node_sets.at("all"), {}));
  const int g =
      model.add_marker(make_ground_marker("ground", Vec3(0.2, -0.1, 0.05), Mat3::Identity()));
  model.add_element(std::make_unique<EngineMount>(
      "mount", std::vector<int>{g, mb},
      std::array<ForceLaw, 3>{ForceLaw::polynomial({2e5, 1e7, 3e9}), ForceLaw::polynomial({3e5}),
                              ForceLaw::polynomial({4e5, -2e7})},
      Vec3(50, 60, 70), Vec3(0, 0, 300), Vec3(1e4, 2e4, 3e4), Vec3(1, 2, 3), Vec3(0.1, 0, 0.2),
      Vec3::Zero()));
  // Thrust bearing in contact: axial offset so that the shaft sits 3 mm from centre.
  const double d0 = model.markers()[pc].c.x() - model.markers()[th].c.x();
  model.add_element(std::make_unique<ThrustBearing>(
      "thrust", std::vector<int>{th, pc},
      ClearanceLaw(ForceLaw::polynomial({1e7, 0, 1e11}), 1e-3, 5e-4), 200.0, false, Vec3::UnitX(),
      d0 - 3e-3));
  model.add_element(std::make_unique<Belt>("belt", std::vector<int>{pc, pb1, pb2}, 900.0,
                                           std::vector<double>{0.015, 0.01, -0.005},
                                           Vec3::UnitX()));
  System sys(model);
  const int n = sys.size();
  Vec q = Vec::Random(n) * 1e-4, v = Vec::Random(n) * 0.05;
  const double t = 0.013;
  const auto err = test_fd::jacobian_fd_error(sys, t, q, v, 1e-7, 1e-4, true);
  std::cout << "System Jacobian with mount + thrust bearing + belt vs FD: K " << err.K << ", C "
            << err.C << "\n";
  EXPECT_LT(err.K, 1e-6);
  EXPECT_LT(err.C, 1e-6);
}
