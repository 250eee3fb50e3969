// Rigid rotation in a spinning LOF (solver/invariants.h rigid_rotation_correction).
// Reference: torque-free rigid body spinning about a principal axis (Euler's
// equations; e.g. Goldstein, Classical Mechanics, s. 5.6 / the intermediate-axis
// theorem): spin about the axis of largest or smallest inertia is neutrally
// stable with nutation frequency w sqrt((J_s - J_a)(J_s - J_b)/(J_a J_b)); about
// the intermediate axis perturbations grow at w sqrt((J_2 - J_1)(J_3 - J_2)/(J_1 J_3));
// a rotation about the spin axis itself is neutral (no stiffness).
// Without the correction the linearised modes give the spin-axis rotation a
// stiffness -w^2 J, i.e. a real eigenvalue w: this test fails.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "random_body.h"
#include "solver/system.h"

using namespace evas;

namespace {

Eigen::VectorXcd rotation_eigenvalues(int axis, double w, Vec3& J) {
  auto body = std::make_shared<ModalBody>(test_bodies::random_body(40, 0, 77));
  const MassProperties mp = mass_properties(body->s, body->mass);
  J = mp.principal_moments;
  Model model;
  model.add_body("rigid", body,
                 Lof::spin(mp.com, Mat3::Identity(), mp.principal_axes.col(axis), 0.0, {0.0}, {w}));
  System sys(model);
  const int n = sys.size();
  Vec q = Vec::Zero(n), v = Vec::Zero(n);
  SpMat K = sys.jacobian_pattern(), C = sys.jacobian_pattern();
  sys.force_jacobian(0.3, q.data(), v.data(), K, C);
  // The rotation modes (3..5) decouple from the translations about the centre of
  // mass; the translations' defective zero eigenvalues would only blur the check.
  EXPECT_LT(Mat(K).block(0, 3, 3, 3).norm() + Mat(C).block(0, 3, 3, 3).norm(), 1e-9 * w * w);
  Mat A = Mat::Zero(6, 6);
  A.topRightCorner(3, 3).setIdentity();
  A.bottomLeftCorner(3, 3) = -Mat(K).block(3, 3, 3, 3);
  A.bottomRightCorner(3, 3) = -Mat(C).block(3, 3, 3, 3);
  (void)n;
  return Eigen::EigenSolver<Mat>(A).eigenvalues();
}

}  // namespace

TEST(RotationCorrection, SpinAboutPrincipalAxesMatchesEulerStability) {
  const double w = 300.0;
  Vec3 J;
  // Largest and smallest axis: all eigenvalues on the imaginary axis.
  for (int axis : {0, 2}) {
    const auto ev = rotation_eigenvalues(axis, w, J);
    const int a = (axis + 1) % 3, b = (axis + 2) % 3;
    const double nut = w * std::sqrt((J[axis] - J[a]) * (J[axis] - J[b]) / (J[a] * J[b]));
    double max_re = 0, best = 1e300;
    for (auto e : ev) {
      max_re = std::max(max_re, std::abs(e.real()));
      best = std::min(best, std::abs(std::abs(e.imag()) - nut));
    }
    std::cout << "spin about principal axis " << axis << ": max |Re| = " << max_re << ", nutation "
              << nut << " rad/s found to " << best << "\n";
    EXPECT_LT(max_re, 1e-6 * w);
    EXPECT_LT(best, 1e-8 * nut);
  }
  // Intermediate axis: a real pair +-sigma.
  const auto ev = rotation_eigenvalues(1, w, J);
  const double sigma = w * std::sqrt((J[1] - J[0]) * (J[2] - J[1]) / (J[0] * J[2]));
  double max_re = 0;
  for (auto e : ev) max_re = std::max(max_re, e.real());
  std::cout << "intermediate axis: growth rate " << max_re << " vs Euler " << sigma << "\n";
  EXPECT_NEAR(max_re, sigma, 1e-8 * sigma);
}
