// Joints between markers (solver/joint.h) as the constraints of a System:
//  - every joint type's g' and acceleration term against central differences of
//    g along the motion, and G = dg/dq against differences over q, body-body and
//    body-ground, on resting and spinning frames;
//  - statics: a rigid body welded to the ground carries its weight, so the
//    multipliers are the weight and its moment about the weld (Newton-Euler
//    equilibrium), in every IDA formulation, with the body at rest;
//  - momentum: two free rigid bodies joined by a spherical joint exchange only
//    internal forces (Newton's third law), so their total linear momentum is
//    constant;
//  - the inputs a joint refuses, each with its message.
#include <gtest/gtest.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "integrators/integrator.h"
#include "integrators/settings.h"
#include "model/model.h"
#include "random_body.h"
#include "solver/system.h"

namespace evas {
namespace {

const Vec3 kPoint(0.2, -0.1, 0.05);  // joint point, L components of both bodies at t = 0

Mat3 z_along_x() {
  Mat3 R;
  R.col(0) = Vec3::UnitY();
  R.col(1) = Vec3::UnitZ();
  R.col(2) = Vec3::UnitX();
  return R;
}

struct Rig {
  std::unique_ptr<Model> model;
  std::unique_ptr<System> sys;
};

// Body "a" (6 rigid + 3 elastic modes) joined to body "b" (6 + 2) or the ground
// at kPoint; a's frame spins about x when `spin`.
Rig make_rig(JointType type, bool to_ground, bool spin, double length = 0.0) {
  Rig r;
  r.model = std::make_unique<Model>();
  Model& m = *r.model;
  auto a = std::make_shared<ModalBody>(test_bodies::random_body(14, 3, 7));
  auto b = std::make_shared<ModalBody>(test_bodies::random_body(12, 2, 8));
  const Lof la = spin ? Lof::spin(Vec3::Zero(), Mat3::Identity(), Vec3::UnitX(), 0.0, {0.0}, {40.0})
                      : Lof::fixed(Vec3::Zero(), Mat3::Identity());
  m.add_body("a", a, la);
  m.add_body("b", b, Lof::fixed(Vec3::Zero(), Mat3::Identity()));
  const Vec3 pb = type == JointType::distance ? Vec3(kPoint + Vec3(0.1, 0.05, -0.2)) : kPoint;
  Marker ma = make_set_marker("ma", 0, *a, a->node_sets.at("all"), {}, &kPoint);
  ma.R_LM = z_along_x();
  m.add_marker(ma);
  if (to_ground)
    m.add_marker(make_ground_marker("mb", pb, Mat3::Identity()));
  else
    m.add_marker(make_set_marker("mb", 1, *b, b->node_sets.at("all"), {}, &pb));
  Joint j;
  j.name = "j";
  j.type = type;
  j.marker1 = 0;
  j.marker2 = 1;
  j.length = length;
  m.add_joint(j);
  r.sys = std::make_unique<System>(m);
  return r;
}

Vec random_vec(int n, unsigned seed, double scale) {
  std::srand(seed);
  return scale * Vec::Random(n);
}

void check_derivatives(JointType type, bool to_ground, bool spin) {
  SCOPED_TRACE(joint_type_name(type) + (to_ground ? " to ground" : " body-body") +
               (spin ? ", spinning frame" : ""));
  Rig r = make_rig(type, to_ground, spin);
  System& s = *r.sys;
  const int n = s.size(), m = s.constraint_count();
  ASSERT_EQ(m, static_cast<int>(joint_rows(type).size()));
  const Vec q = random_vec(n, 3, 1e-2), v = random_vec(n, 4, 0.5);
  const double t = 0.013;
  Vec g(m), gv(m), ga(m), gp(m), gm(m), gvp(m), gvm(m);
  s.constraint(t, q.data(), v.data(), g.data(), gv.data(), ga.data());
  SpMat G = s.constraint_pattern();
  s.constraint_jacobian(t, q.data(), G);
  const Mat Gd(G);
  // G against differences over q
  const double h = 1e-6;
  Mat Gfd(m, n);
  for (int c = 0; c < n; ++c) {
    Vec qp = q, qm = q;
    qp(c) += h;
    qm(c) -= h;
    s.constraint(t, qp.data(), v.data(), gp.data(), nullptr, nullptr);
    s.constraint(t, qm.data(), v.data(), gm.data(), nullptr, nullptr);
    Gfd.col(c) = (gp - gm) / (2 * h);
  }
  EXPECT_LT((Gd - Gfd).cwiseAbs().maxCoeff(), 1e-8 * (1.0 + Gd.cwiseAbs().maxCoeff()));
  // g' and the acceleration term along q(t + tau) = q + tau v (qdd = 0)
  const double ht = 1e-6;
  const Vec qp = q + ht * v, qm = q - ht * v;
  s.constraint(t + ht, qp.data(), v.data(), gp.data(), gvp.data(), nullptr);
  s.constraint(t - ht, qm.data(), v.data(), gm.data(), gvm.data(), nullptr);
  const Vec gv_fd = (gp - gm) / (2 * ht), ga_fd = (gvp - gvm) / (2 * ht);
  EXPECT_LT((gv - gv_fd).cwiseAbs().maxCoeff(), 1e-7 * (1.0 + gv.cwiseAbs().maxCoeff()));
  EXPECT_LT((ga - ga_fd).cwiseAbs().maxCoeff(), 1e-6 * (1.0 + ga.cwiseAbs().maxCoeff()));
  // g' = G v + g_t: on frames at rest g_t = 0
  if (!spin) {
    EXPECT_LT((gv - Gd * v).cwiseAbs().maxCoeff(), 1e-12);
  }
}

TEST(Joints, DerivativesMatchDifferences) {
  for (bool ground : {false, true}) {
    for (JointType t : {JointType::fixed, JointType::spherical, JointType::revolute,
                        JointType::cylindrical, JointType::prismatic, JointType::distance})
      check_derivatives(t, ground, false);
    for (JointType t : {JointType::spherical, JointType::revolute, JointType::distance})
      check_derivatives(t, ground, true);
  }
}

TEST(Joints, ReferenceConfigurationMeetsThem) {
  for (JointType t :
       {JointType::fixed, JointType::revolute, JointType::prismatic, JointType::distance}) {
    Rig r = make_rig(t, false, false);
    const int n = r.sys->size(), m = r.sys->constraint_count();
    Vec g(m);
    const Vec z = Vec::Zero(n);
    r.sys->constraint(0.0, z.data(), z.data(), g.data(), nullptr, nullptr);
    EXPECT_LT(g.cwiseAbs().maxCoeff(), 1e-12) << joint_type_name(t);
  }
  // the distance joint's default length is the reference distance
  Rig r = make_rig(JointType::distance, true, false);
  EXPECT_NEAR(r.model->joints()[0].length, Vec3(0.1, 0.05, -0.2).norm(), 1e-15);
  EXPECT_FALSE(r.sys->constraints_linear());
  EXPECT_TRUE(make_rig(JointType::fixed, true, false).sys->constraints_linear());
  EXPECT_EQ(make_rig(JointType::revolute, true, false).sys->constraint_name(4), "j.r.y");
}

// A rigid body welded to the ground under gravity stays at rest, and the weld
// carries the weight: the joint force on the body is -lambda_p (G^T lambda
// enters like -Q), so lambda_p = m gvec, and the moment balance about the weld
// point P gives lambda_r = E^T ((c - P) x m gvec), c the centre of mass.
TEST(Joints, WeldCarriesTheWeight) {
  auto model = std::make_unique<Model>();
  auto a = std::make_shared<ModalBody>(test_bodies::random_body(10, 0, 11));
  model->gravity = Vec3(0.0, 0.0, -9.81);
  model->add_body("a", a, Lof::fixed(Vec3::Zero(), Mat3::Identity()));
  model->add_marker(make_set_marker("ma", 0, *a, a->node_sets.at("all"), {}, &kPoint));
  model->add_marker(make_ground_marker("g", kPoint, Mat3::Identity()));
  model->add_joint({"weld", JointType::fixed, 0, 1, 0.0});
  System sys(*model);
  const MassProperties& mp = model->bodies()[0].mp;
  const Vec3 W = mp.mass * model->gravity;
  const Vec3 Mo = (mp.com - kPoint).cross(W);
  for (const std::string f : {"index-3", "index-2", "ggl", "index-1"}) {
    SCOPED_TRACE(f);
    IntegratorSettings st;
    st.name = "ida";
    st.formulation = f;
    st.rtol = 1e-8;
    st.atol = 1e-10;
    auto integ = make_integrator("ida");
    Vec q0, v0, q, v, lam;
    sys.initial_state(q0, v0);
    integ->init(sys, 0.0, q0, v0, st);
    integ->advance(0.02, true, q, v);
    ASSERT_TRUE(integ->multipliers(lam));
    ASSERT_EQ(lam.size(), 6);
    EXPECT_LT(q.cwiseAbs().maxCoeff(), 1e-10);
    EXPECT_LT((lam.head<3>() - W).norm(), 1e-8 * W.norm());
    EXPECT_LT((lam.tail<3>() - Mo).norm(), 1e-8 * (W.norm() + Mo.norm()));
  }
}

// Two free rigid bodies joined by a spherical joint: internal joint forces leave
// the total linear momentum sum_b m_b v_com,b unchanged (Newton's third law).
TEST(Joints, SphericalJointConservesMomentum) {
  auto model = std::make_unique<Model>();
  auto a = std::make_shared<ModalBody>(test_bodies::random_body(10, 0, 21));
  auto b = std::make_shared<ModalBody>(test_bodies::random_body(9, 0, 22));
  model->add_body("a", a, Lof::fixed(Vec3::Zero(), Mat3::Identity()));
  model->add_body("b", b, Lof::fixed(Vec3::Zero(), Mat3::Identity()));
  model->add_marker(make_set_marker("ma", 0, *a, a->node_sets.at("all"), {}, &kPoint));
  model->add_marker(make_set_marker("mb", 1, *b, b->node_sets.at("all"), {}, &kPoint));
  // com markers: their velocities are the bodies' centre-of-mass velocities
  for (int k = 0; k < 2; ++k) {
    const ModalBody& B = k ? *b : *a;
    const Vec3 c = model->bodies()[k].mp.com;
    model->add_marker(make_set_marker(k ? "cb" : "ca", k, B, B.node_sets.at("all"), {}, &c));
  }
  model->add_joint({"ball", JointType::spherical, 0, 1, 0.0});
  System sys(*model);
  Vec q0, v0;
  sys.initial_state(q0, v0);
  v0.head(6) = random_vec(6, 5, 0.3);  // a moves, b at rest: the joint drags b along
  auto momentum = [&](const Vec& q, const Vec& v) {
    sys.update_markers(0.0, q.data(), v.data());
    return Vec3(model->bodies()[0].mp.mass * sys.motion(2).v +
                model->bodies()[1].mp.mass * sys.motion(3).v);
  };
  IntegratorSettings st;
  st.name = "ida";
  st.formulation = "ggl";
  st.rtol = 1e-9;
  st.atol = 1e-12;
  auto integ = make_integrator("ida");
  integ->init(sys, 0.0, q0, v0, st);
  Vec q, v;
  integ->advance(1e-6, true, q, v);
  const Vec3 P0 = momentum(q, v);  // after the consistent start (v projected)
  integ->advance(0.5, true, q, v);
  const Vec3 P1 = momentum(q, v);
  EXPECT_GT(P0.norm(), 1e-3);
  EXPECT_LT((P1 - P0).norm(), 1e-6 * P0.norm());
  Vec g(3);
  sys.constraint(0.5, q.data(), v.data(), g.data(), nullptr, nullptr);
  EXPECT_LT(g.norm(), 1e-9);
}

void expect_refused(const std::function<void()>& f, const std::string& fragment) {
  try {
    f();
    ADD_FAILURE() << "accepted; expected an error with '" << fragment << "'";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(Joints, RefusedInputs) {
  auto a = std::make_shared<ModalBody>(test_bodies::random_body(10, 2, 31));
  auto base = [&](const Lof& lof) {
    auto m = std::make_unique<Model>();
    m->add_body("a", a, lof);
    m->add_marker(make_set_marker("ma", 0, *a, a->node_sets.at("all"), {}, &kPoint));
    m->add_marker(make_ground_marker("g", kPoint, Mat3::Identity()));
    m->add_marker(make_ground_marker("far", Vec3(1, 2, 3), Mat3::Identity()));
    m->add_marker(make_node_marker("node", 0, *a, a->node_ids[0]));
    return m;
  };
  const Lof fixed = Lof::fixed(Vec3::Zero(), Mat3::Identity());
  auto joint = [](JointType t, int m1, int m2, double len = 0.0) {
    return Joint{"j", t, m1, m2, len};
  };
  auto system_of = [&](const Lof& lof, const std::vector<Joint>& joints) {
    auto m = base(lof);
    for (const Joint& j : joints) m->add_joint(j);
    System s(*m);
  };
  expect_refused([&] { system_of(fixed, {joint(JointType::fixed, 0, 2)}); },
                 "in the reference configuration");
  expect_refused([&] { system_of(fixed, {joint(JointType::spherical, 1, 0)}); },
                 "the first marker must be on a body");
  expect_refused([&] { system_of(fixed, {joint(JointType::revolute, 3, 1)}); }, "which has none");
  expect_refused([&] { system_of(fixed, {joint(JointType::fixed, 0, 3)}); },
                 "both markers are on body 'a'");
  expect_refused([&] { system_of(fixed, {joint(JointType::distance, 0, 2, -1.0)}); },
                 "must be > 0");
  expect_refused([&] { system_of(fixed, {joint(JointType::spherical, 0, 0)}); }, "to itself");
  // 12 equations on 8 modes
  expect_refused(
      [&] {
        auto m = base(fixed);
        m->add_marker(make_set_marker("ma2", 0, *a, a->node_sets.at("first4"), {}, &kPoint));
        m->add_joint(joint(JointType::fixed, 0, 1));
        Joint j2 = joint(JointType::fixed, 4, 1);
        j2.name = "j2";
        m->add_joint(j2);
        System s(*m);
      },
      "dependent");
  const Lof spin = Lof::spin(Vec3::Zero(), Mat3::Identity(), Vec3::UnitX(), 0.0, {0.0}, {40.0});
  expect_refused([&] { system_of(spin, {joint(JointType::fixed, 0, 1)}); }, "spins about");
  expect_refused([&] { system_of(spin, {joint(JointType::cylindrical, 0, 1)}); }, "moving frame");
  const Lof track = Lof::tracking(Vec3::Zero(), Mat3::Identity(), Vec3::Zero(), Vec3::Zero(), 0.1);
  expect_refused([&] { system_of(track, {joint(JointType::spherical, 0, 1)}); }, "tracking frame");
  expect_refused([] { joint_type("hinge"); }, "unknown joint type 'hinge'");
}

}  // namespace
}  // namespace evas
