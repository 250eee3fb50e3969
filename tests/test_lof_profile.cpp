// Spin LOF speed profile: theta' = omega and omega' = alpha everywhere, omega
// and alpha continuous across the knots (a jump in alpha costs second-order
// integrators their order — found in review), monotone between knots.
#include <gtest/gtest.h>

#include "model/lof.h"

using namespace evas;

TEST(LofProfile, DerivativesConsistentAndContinuous) {
  const Lof lof = Lof::spin(Vec3::Zero(), Mat3::Identity(), Vec3::UnitZ(), 0.4,
                            {0.0, 0.1, 0.25, 0.3}, {100.0, 300.0, 310.0, 50.0});
  const double h = 1e-6;
  for (double t = -0.05; t < 0.4; t += 0.00731) {
    const double dth = (lof.spin_angle(t + h) - lof.spin_angle(t - h)) / (2 * h);
    const double dw = (lof.spin_speed(t + h) - lof.spin_speed(t - h)) / (2 * h);
    EXPECT_NEAR(dth, lof.spin_speed(t), 1e-6 * 300) << "t = " << t;
    EXPECT_NEAR(dw, lof.spin_acceleration(t), 1e-5 * 5000) << "t = " << t;
  }
  for (double k : {0.0, 0.1, 0.25, 0.3}) {
    EXPECT_NEAR(lof.spin_speed(k - 1e-9), lof.spin_speed(k + 1e-9), 1e-4);
    EXPECT_NEAR(lof.spin_acceleration(k - 1e-9), lof.spin_acceleration(k + 1e-9), 1e-2);
  }
  EXPECT_NEAR(lof.spin_angle(0.0), 0.4, 1e-15);
  // Monotone between knots: no overshoot beyond the knot values.
  for (double t = 0.1; t < 0.25; t += 1e-3) {
    EXPECT_GE(lof.spin_speed(t), 300.0 - 1e-9);
    EXPECT_LE(lof.spin_speed(t), 310.0 + 1e-9);
  }
  // Constant speed after the last knot.
  EXPECT_NEAR(lof.spin_angle(0.5) - lof.spin_angle(0.4), 5.0, 1e-12);
}

TEST(LofProfile, BadProfilesAreRejected) {
  EXPECT_THROW(Lof::spin(Vec3::Zero(), Mat3::Identity(), Vec3::UnitZ(), 0, {0.0, 0.0}, {1, 2}),
               InputError);
  EXPECT_THROW(Lof::spin(Vec3::Zero(), Mat3::Identity(), Vec3::Zero(), 0, {0.0}, {1}), InputError);
  Lof tr = Lof::tracking(Vec3::Zero(), Mat3::Identity(), Vec3::Zero(), Vec3::Zero(), 1e-3);
  EXPECT_THROW(tr.set_origin_motion(Vec3::Zero(), Vec3::UnitX()), InputError);
}
