// Six rigid modes reproduce the body's mass, centre of mass and inertia
// (formulation.md s. 2: explicit mass-orthonormal rigid basis).
#include <gtest/gtest.h>

#include "model/invariants.h"
#include "random_body.h"

using namespace evas;

namespace {
// Mass properties by direct sums over lumped masses, independent of mass_properties().
void direct_sums(const ModalBody& b, double& m, Vec3& c, Mat3& J) {
  m = 0;
  c.setZero();
  for (int i = 0; i < b.num_nodes(); ++i) {
    m += b.mass.coeff(i, i);
    c += b.mass.coeff(i, i) * b.s.row(i).transpose();
  }
  c /= m;
  J.setZero();
  for (int i = 0; i < b.num_nodes(); ++i) {
    const Vec3 d = b.s.row(i).transpose() - c;
    J += b.mass.coeff(i, i) * (d.squaredNorm() * Mat3::Identity() - d * d.transpose());
  }
}
}  // namespace

TEST(RigidModes, ReproduceMassCentreAndInertia) {
  const ModalBody b = test_bodies::random_body(60, 0, 21);
  double m;
  Vec3 c;
  Mat3 J;
  direct_sums(b, m, c, J);
  const MassProperties mp = mass_properties(b.s, b.mass);
  EXPECT_NEAR(mp.mass, m, 1e-12 * m);
  EXPECT_LT((mp.com - c).norm(), 1e-12);
  EXPECT_LT((mp.inertia - J).norm(), 1e-12 * J.norm());

  // Kinetic energy of a rigid motion (V, W about the centre of mass) equals the
  // energy of its projection on the six modes: q_dot = Phi^T M u_dot, T = |q_dot|^2/2.
  const Mat R = b.modes;  // the six rigid modes
  const Vec3 V(0.3, -1.2, 0.7), W(2.0, -0.5, 1.5);
  Vec ud(3 * b.num_nodes());
  for (int i = 0; i < b.num_nodes(); ++i)
    ud.segment<3>(3 * i) = V + W.cross(b.s.row(i).transpose() - c);
  const Vec qd = R.transpose() * apply_mass(b.mass, ud);
  const double T_modes = 0.5 * qd.squaredNorm();
  const double T_exact = 0.5 * m * V.squaredNorm() + 0.5 * W.dot(J * W);
  EXPECT_NEAR(T_modes, T_exact, 1e-12 * T_exact);
  // And the modes represent that motion exactly: R qd == ud.
  EXPECT_LT((R * qd - ud).cwiseAbs().maxCoeff(), 1e-12);

  // Invariants: S = [sqrt(m) I | 0]; M_aa of rotation modes give J via p.
  const ModalInvariants inv = compute_invariants(b);
  EXPECT_LT((inv.S.leftCols(3) - std::sqrt(m) * Mat3::Identity()).norm(), 1e-10);
  EXPECT_LT(inv.S.rightCols(3).norm(), 1e-10);
  // Mass orthonormality.
  EXPECT_LT((R.transpose() * apply_mass(b.mass, R) - Mat::Identity(6, 6)).norm(), 1e-12);
}
