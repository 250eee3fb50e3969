// Eq. 1 of the paper in invariant form (formulation.md s. 2) against the
// paper's literal sums over the nodes, and the identities the invariants obey.
#include <gtest/gtest.h>

#include "model/invariants.h"
#include "random_body.h"

using namespace evas;

TEST(Invariants, InvariantFormEqualsLiteralNodeSums) {
  const ModalBody b = test_bodies::random_body(40, 7, 3);
  const ModalInvariants inv = compute_invariants(b);
  const int n = b.num_modes();
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int trial = 0; trial < 5; ++trial) {
    const Mat3 A = rotation_from_vector(Vec3(U(gen), U(gen), U(gen)));
    const Vec3 a(U(gen) * 20, U(gen) * 20, U(gen) * 20),
        w(U(gen) * 300, U(gen) * 300, U(gen) * 300), al(U(gen) * 1e4, U(gen) * 1e4, U(gen) * 1e4);
    const Vec q = Vec::Random(n) * 1e-3, qd = Vec::Random(n), qdd = Vec::Random(n) * 100;
    Eigen::Matrix<double, Eigen::Dynamic, 3> F =
        Eigen::Matrix<double, Eigen::Dynamic, 3>::Zero(b.num_nodes(), 3);
    const Vec lit = eq1_literal(b, A, a, w, al, q, qd, qdd, F);
    Vec f0(n);
    Mat KW(n, n), G(n, n);
    frame_terms(inv, A.transpose() * a, A.transpose() * w, A.transpose() * al, f0, KW, G);
    const Vec mine = qdd + f0 + (b.eigenvalues.asDiagonal() * q) + KW * q +
                     (b.damping.asDiagonal() * qd) + G * qd;
    const double scale = lit.cwiseAbs().maxCoeff();
    EXPECT_LT((mine - lit).cwiseAbs().maxCoeff(), 1e-12 * scale) << "trial " << trial;
  }
}

TEST(Invariants, IdentitiesHoldForMassNormalisedModes) {
  for (bool consistent : {false, true}) {
    const ModalBody b = test_bodies::random_body(30, 5, 7, true, consistent);
    const ModalInvariants inv = compute_invariants(b);
    const int n = b.num_modes();
    const Mat sum = inv.M[0][0] + inv.M[1][1] + inv.M[2][2];
    EXPECT_LT((sum - Mat::Identity(n, n)).norm(), 1e-11) << "sum_a M_aa = I";
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c) EXPECT_LT((inv.M[a][c] - inv.M[c][a].transpose()).norm(), 1e-13);
    // Elastic modes of a free-free body carry no rigid motion: S = 0 there.
    EXPECT_LT(inv.S.rightCols(n - 6).cwiseAbs().maxCoeff(), 1e-11);
  }
}

TEST(Invariants, ConsistentMassMatchesDirectQuadraticForms) {
  const ModalBody b = test_bodies::random_body(25, 4, 9, true, true);
  const ModalInvariants inv = compute_invariants(b);
  // M_ab(j, k) = Phi_j^T (Ms (x) e_a e_b^T) Phi_k computed with the full 3N mass.
  const int N = b.num_nodes();
  for (int a = 0; a < 3; ++a)
    for (int c = 0; c < 3; ++c) {
      Mat full = Mat::Zero(3 * N, 3 * N);
      for (int i = 0; i < N; ++i)
        for (int j = 0; j < N; ++j) full(3 * i + a, 3 * j + c) = b.mass.coeff(i, j);
      const Mat ref = b.modes.transpose() * full * b.modes;
      EXPECT_LT((ref - inv.M[a][c]).norm(), 1e-12 * (1 + ref.norm()));
    }
}
