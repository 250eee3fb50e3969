// Motor element (paper Fig. 7, Eqs. 4-5; elements/motor.h):
//  - the torque law, action and reaction, analytic derivatives against the
//    finite-difference fallback;
//  - two rigid disks (bodies with one rigid rotation mode) joined by the element
//    with a standing driver: the twist oscillates at the two-inertia natural
//    frequency omega_n = sqrt(K_r (J1 + J2) / (J1 J2)) (e.g. Thomson & Dahleh,
//    "Theory of Vibration with Applications", 5th ed., sec. 5.x, semidefinite
//    two-rotor system);
//  - a disk driven at constant speed against a constant load torque settles at the
//    twist T_load / K_r (static balance of Eq. 5).
// The system runs use IDA through evas::integrate.
#include <gtest/gtest.h>

#include <cmath>

#include "disk_body.h"
#include "elements/motor.h"
#include "integrators/integrator.h"
#include "solver/system.h"

using namespace evas;

namespace {

std::shared_ptr<ModalBody> disk(double J) { return test_bodies::disk("disk", J); }

int disk_marker(Model& m, int body, const std::string& name) {
  const auto& d = *m.bodies()[body].data;
  const Vec3 c = Vec3::Zero();
  return m.add_marker(make_set_marker(name, body, d, d.node_sets.at("all"), {}, &c));
}

// Constant torque about x on one marker (a load such as a brake).
class ConstantTorque : public Element {
 public:
  ConstantTorque(int marker, double T) : Element("load", {marker}), T_(T) {}
  std::string type() const override { return "constant-torque"; }
  void evaluate(double, const MarkerMotion*, MarkerLoad* l) const override {
    l[0].F.setZero();
    l[0].M = T_ * Vec3::UnitX();
  }
  void derivatives(double, const MarkerMotion*, Mat& D) const override { D.setZero(); }
  bool state_dependent() const override { return false; }
  std::vector<Channel> channels() const override { return {}; }
  void channel_values(double, const MarkerMotion*, double*) const override {}

 private:
  double T_;
};

IntegratorSettings ida(double rtol) {
  IntegratorSettings s;
  s.name = "ida";
  s.rtol = rtol;
  s.atol = rtol * 1e-3;
  return s;
}

// Runs the model and returns (t, twist) at n_out points on (0, t_end].
std::vector<std::pair<double, double>> run_twist(Model& model, int motor, double t_end, int n_out) {
  System sys(model);
  auto integ = make_integrator("ida");
  Vec q, v;
  sys.initial_state(q, v);
  integ->init(sys, 0.0, q, v, ida(1e-9));
  std::vector<double> outs;
  for (int k = 1; k <= n_out; ++k) outs.push_back(t_end * k / n_out);
  const Element& e = *model.elements()[motor];
  std::vector<std::pair<double, double>> out;
  integrate(*integ, sys, 0.0, outs, [&](double t, const Vec& qq, const Vec& vv) {
    sys.update_markers(t, qq.data(), vv.data());
    MarkerMotion mm[2] = {sys.motion(e.markers()[0]), sys.motion(e.markers()[1])};
    double val[2];
    e.channel_values(t, mm, val);
    out.emplace_back(t, val[1]);
  });
  return out;
}

}  // namespace

TEST(Motor, TorqueLawReactionAndDerivatives) {
  const Vec3 axis(0.3, -1.0, 0.2);
  const double K = 4e3, C = 12.0, w = 150.0, th0 = 0.4;
  Motor mot("m", {0, 1}, axis, w, th0, K, C);
  EXPECT_TRUE(mot.state_dependent());
  MarkerMotion m[2];
  const Vec3 a = axis.normalized();
  m[0].psi = 2.0 * a + Vec3(0.01, 0.02, -0.03);
  m[1].psi = Vec3(0.001, -0.002, 0.003);
  m[0].w = 149.0 * a + Vec3(0.5, 0.1, 0.0);
  m[1].w = Vec3(0.1, 0.2, 0.3);
  m[0].p = Vec3(0.1, 0.2, 0.3);
  m[1].p = Vec3(-0.1, 0.0, 0.3);
  const double t = 0.011;
  MarkerLoad l[2];
  mot.evaluate(t, m, l);
  const double th2 = a.dot(m[0].psi - m[1].psi), th2d = a.dot(m[0].w - m[1].w);
  const double T = -K * (th2 - (w * t + th0)) - C * (th2d - w);
  EXPECT_NEAR(l[0].M.dot(a), T, 1e-9 * std::abs(T));
  EXPECT_LT((l[0].M - T * a).norm(), 1e-9 * std::abs(T));
  EXPECT_LT((l[0].M + l[1].M).norm(), 1e-12);
  EXPECT_EQ(l[0].F.norm() + l[1].F.norm(), 0.0);
  double ch[2];
  mot.channel_values(t, m, ch);
  EXPECT_NEAR(ch[0], T, 1e-9 * std::abs(T));
  EXPECT_NEAR(ch[1], th2 - (w * t + th0), 1e-12);
  Mat D(12, 24), Dfd(12, 24);
  mot.derivatives(t, m, D);
  mot.derivatives_fd(t, m, Dfd);
  const double err = (D - Dfd).cwiseAbs().maxCoeff() / D.cwiseAbs().maxCoeff();
  std::cout << "motor D vs finite differences: max rel error " << err << "\n";
  EXPECT_LT(err, 1e-7);
}

TEST(Motor, DeclarationAndFactory) {
  const ElementType t = motor_element_type();
  EXPECT_EQ(t.type, "motor");
  EXPECT_EQ(t.num_markers, 2);
  ParamValues v;
  v.numbers["speed"] = {314.159};
  v.numbers["stiffness"] = {1e4};
  v.numbers["initial_angle"] = {90.0};
  complete_params(t, v, "test");
  auto e = t.make("dyno", {0, 1}, v);
  MarkerMotion m[2];
  double ch[2];
  e->channel_values(0.0, m, ch);
  EXPECT_NEAR(ch[1], -M_PI / 2, 1e-12);  // initial angle in degrees
  EXPECT_EQ(e->channels()[0].unit, "N m");
  v.numbers["axis"] = {0, 0, 0};
  EXPECT_THROW(t.make("dyno", {0, 1}, v), InputError);
  ParamValues missing;
  EXPECT_THROW(complete_params(t, missing, "test"), InputError);  // stiffness, speed required
}

// Two free disks (J1 on the stator marker, J2 on the clutch marker), standing
// driver (w = 0, theta_0 = 0): the element is a torsional spring K_r between
// them. Start from a twist; with no initial speed the twist is
// theta_init cos(omega_n t), omega_n = sqrt(K_r (J1 + J2) / (J1 J2)).
TEST(Motor, TwoInertiaNaturalFrequency) {
  const double J1 = 0.3, J2 = 0.1, K = 5e3, th_init = 0.02;
  Model model;
  const int b1 = model.add_body("disk1", disk(J1), Lof::fixed(Vec3::Zero(), Mat3::Identity()));
  const int b2 = model.add_body("disk2", disk(J2), Lof::fixed(Vec3(0.2, 0, 0), Mat3::Identity()));
  const int m1 = disk_marker(model, b1, "d1"), m2 = disk_marker(model, b2, "d2");
  const int mot = model.add_element(
      std::make_unique<Motor>("motor", std::vector<int>{m2, m1}, Vec3::UnitX(), 0.0, 0.0, K, 0.0));
  // Twist split so that the angular momentum stays zero: J1 th1 + J2 th2 = 0.
  model.bodies()[b2].q0 = Vec::Constant(1, th_init * J1 / (J1 + J2) * std::sqrt(J2));
  model.bodies()[b1].q0 = Vec::Constant(1, -th_init * J2 / (J1 + J2) * std::sqrt(J1));
  const double wn = std::sqrt(K * (J1 + J2) / (J1 * J2));
  const double T = 2 * M_PI / wn;
  const auto r = run_twist(model, mot, 5 * T, 2000);
  double err = 0;
  std::vector<double> crossings;  // upward zero crossings
  for (std::size_t k = 0; k < r.size(); ++k) {
    err = std::max(err, std::abs(r[k].second - th_init * std::cos(wn * r[k].first)));
    if (k > 0 && r[k - 1].second < 0 && r[k].second >= 0) {
      const double f = r[k - 1].second / (r[k - 1].second - r[k].second);
      crossings.push_back(r[k - 1].first + f * (r[k].first - r[k - 1].first));
    }
  }
  ASSERT_GE(crossings.size(), 4u);
  const double period = (crossings.back() - crossings.front()) / (crossings.size() - 1);
  const double ferr = std::abs(2 * M_PI / period / wn - 1);
  std::cout << "two-inertia: omega_n = " << wn << " rad/s; measured from " << crossings.size()
            << " zero crossings: " << 2 * M_PI / period << " rad/s (rel err " << ferr
            << "); max |twist - th0 cos(wn t)| / th0 = " << err / th_init << "\n";
  EXPECT_LT(ferr, 1e-5);
  EXPECT_LT(err / th_init, 1e-4);
}

// One disk (J2) driven at w through the clutch spring, stator on the ground, a
// constant load torque T_load on the disk: Eq. 5 balances when the twist is
// T_load / K_r (negative for a braking load); damping makes the transient decay.
TEST(Motor, SteadyTwistUnderConstantLoad) {
  const double J2 = 0.1, K = 5e3, w = 10.0, zeta = 0.3;
  const double C = 2 * zeta * std::sqrt(K * J2);
  const double T_load = -150.0;
  Model model;
  const int b = model.add_body("disk", disk(J2), Lof::fixed(Vec3::Zero(), Mat3::Identity()));
  const int md = disk_marker(model, b, "clutch");
  const int g = model.add_marker(make_ground_marker("stator", Vec3::Zero(), Mat3::Identity()));
  const int mot = model.add_element(
      std::make_unique<Motor>("motor", std::vector<int>{md, g}, Vec3::UnitX(), w, 0.0, K, C));
  model.add_element(std::make_unique<ConstantTorque>(md, T_load));
  model.bodies()[b].v0 = Vec::Constant(1, w * std::sqrt(J2));       // start at the driver's speed
  const double wn = std::sqrt(K / J2), t_end = 30.0 / (zeta * wn);  // e^-30 of the transient
  const auto r = run_twist(model, mot, t_end, 200);
  const double twist = r.back().second, ref = T_load / K;
  std::cout << "steady twist " << twist << " rad vs T_load/K_r = " << ref << " (rel err "
            << std::abs(twist / ref - 1) << ") after " << r.back().first << " s, driver angle "
            << w * r.back().first << " rad\n";
  EXPECT_NEAR(twist / ref, 1.0, 1e-6);
}

// The element's derivatives chained through the marker maps (System Jacobian)
// agree with finite differences of the system force.
TEST(Motor, SystemJacobianMatchesFiniteDifferences) {
  Model model;
  const int b1 = model.add_body("disk1", disk(0.3), Lof::fixed(Vec3::Zero(), Mat3::Identity()));
  const int b2 = model.add_body("disk2", disk(0.1), Lof::fixed(Vec3(0.2, 0, 0), Mat3::Identity()));
  const int m1 = disk_marker(model, b1, "d1"), m2 = disk_marker(model, b2, "d2");
  model.add_element(std::make_unique<Motor>("motor", std::vector<int>{m2, m1}, Vec3::UnitX(), 50.0,
                                            0.1, 5e3, 7.0));
  System sys(model);
  const int n = sys.size();
  Vec q = Vec::Constant(n, 0.01), v = Vec::Constant(n, 3.0);
  q[1] = -0.02;
  SpMat K = sys.jacobian_pattern(), C = sys.jacobian_pattern();
  sys.force_jacobian(0.02, q.data(), v.data(), K, C);
  const Mat Kd(K), Cd(C);
  Vec fp(n), fm(n);
  double err = 0;
  for (int j = 0; j < n; ++j)
    for (int which = 0; which < 2; ++which) {
      Vec& x = which == 0 ? q : v;
      const double x0 = x[j], h = 1e-6;
      x[j] = x0 + h;
      sys.force(0.02, q.data(), v.data(), fp.data());
      x[j] = x0 - h;
      sys.force(0.02, q.data(), v.data(), fm.data());
      x[j] = x0;
      const Mat& J = which == 0 ? Kd : Cd;
      err = std::max(err, ((fp - fm) / (2 * h) - J.col(j)).cwiseAbs().maxCoeff() /
                              (1.0 + J.col(j).cwiseAbs().maxCoeff()));
    }
  std::cout << "system Jacobian with the motor: max rel FD error " << err << "\n";
  EXPECT_LT(err, 1e-7);
}
