// A free body at rest in G, observed from a spinning LOF (speed profile, so
// the Euler term is active) and from an accelerating LOF, must satisfy Eq. 1
// with no force: the Coriolis, centrifugal and Euler terms are checked by
// putting the exact modal motion into the residual qdd + f(t, q, v) = 0.
// With the three translation modes the centre-of-mass motion is represented
// exactly, so the residual is zero to round-off (no linearisation involved).
#include <gtest/gtest.h>

#include <functional>
#include <memory>

#include "random_body.h"
#include "solver/system.h"

using namespace evas;

namespace {

struct Case {
  std::string what;
  Lof lof;
};

// q_T(t) = sqrt(m) (R^T (x_c - p_GL) - c) keeps the centre of mass at x_c in G.
Vec exact_q(const Lof& lof, double t, const Vec3& x_c, const Vec3& c, double m) {
  const LofState L = lof.at(t);
  return std::sqrt(m) * (L.R_GL.transpose() * (x_c - L.p_GL) - c);
}

void check(const Case& k) {
  ModalBody full = test_bodies::random_body(30, 0, 5);
  auto body = std::make_shared<ModalBody>(full.select_modes({0, 1, 2}));
  Model model;
  model.add_body("b", body, k.lof);
  System sys(model);
  const MassProperties mp = mass_properties(body->s, body->mass);
  const LofState L0 = k.lof.at(0.0);
  const Vec3 x_c = L0.p_GL + L0.R_GL * mp.com + Vec3(0.01, -0.02, 0.03);
  const double h = 2e-4;
  double worst = 0.0, scale = 0.0;
  for (double t : {0.013, 0.2, 0.37, 0.61, 0.9}) {
    auto q = [&](double s) { return exact_q(k.lof, s, x_c, mp.com, mp.mass); };
    // 5-point stencils (error O(h^4)).
    const Vec qd = (q(t - 2 * h) - 8 * q(t - h) + 8 * q(t + h) - q(t + 2 * h)) / (12 * h);
    const Vec qdd =
        (-q(t - 2 * h) + 16 * q(t - h) - 30 * q(t) + 16 * q(t + h) - q(t + 2 * h)) / (12 * h * h);
    Vec f(3);
    const Vec q0 = q(t);
    sys.force(t, q0.data(), qd.data(), f.data());
    worst = std::max(worst, (qdd + f).cwiseAbs().maxCoeff());
    scale = std::max(scale, qdd.cwiseAbs().maxCoeff() + f.cwiseAbs().maxCoeff());
  }
  ::testing::Test::RecordProperty("relative_residual_" + k.what, std::to_string(worst / scale));
  std::cout << k.what << ": max |qdd + f| / scale = " << worst / scale << "\n";
  EXPECT_LT(worst, 1e-7 * scale) << k.what;
  EXPECT_GT(scale, 1.0) << k.what << ": the test must exercise non-trivial frame terms";
}

}  // namespace

TEST(LofFrames, BodyAtRestSeenFromSpinningFrameWithSpeedProfile) {
  // Axis off the centre of mass and tilted; speed ramps so alpha != 0.
  const Vec3 axis = Vec3(0.2, 0.3, 1.0).normalized();
  check({"spin", Lof::spin(Vec3(0.1, -0.05, 0.0), Mat3::Identity(), axis, 0.3, {0.0, 0.5, 1.0},
                           {5.0, 40.0, 10.0})});
}

TEST(LofFrames, BodyAtRestSeenFromAcceleratingFrame) {
  Lof lof = Lof::fixed(Vec3(0.0, 0.1, 0.0), rotation_from_vector(Vec3(0.1, 0.2, -0.3)));
  lof.set_origin_motion(Vec3(1.0, -2.0, 0.5), Vec3(3.0, 9.81, -4.0));
  check({"accelerating", lof});
}

TEST(LofFrames, SpinningAndAcceleratingTogether) {
  Lof lof = Lof::spin(Vec3::Zero(), Mat3::Identity(), Vec3::UnitX(), 0.0, {0.0, 1.0}, {20.0, 60.0});
  lof.set_origin_motion(Vec3(0.5, 0.0, 0.0), Vec3(0.0, -2.0, 7.0));
  check({"spin+accel", lof});
}

TEST(LofFrames, GravityActsLikeFrameAcceleration) {
  // A body in a fixed frame under gravity g has qdd_T = sqrt(m) R^T g.
  auto body =
      std::make_shared<ModalBody>(test_bodies::random_body(10, 0, 8).select_modes({0, 1, 2}));
  Model model;
  model.gravity = Vec3(0, 0, -9.81);
  const Mat3 R = rotation_from_vector(Vec3(0.3, 0.0, 0.4));
  model.add_body("b", body, Lof::fixed(Vec3::Zero(), R));
  System sys(model);
  Vec q = Vec::Zero(3), v = Vec::Zero(3), f(3);
  sys.force(0.0, q.data(), v.data(), f.data());
  const double m = mass_properties(body->s, body->mass).mass;
  EXPECT_LT((-f - std::sqrt(m) * R.transpose() * model.gravity).norm(), 1e-12);
}
