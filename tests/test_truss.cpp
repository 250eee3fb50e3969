// Space-truss beam generator: geometry, node sets, mass and stiffness checks.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "bodies/truss.h"

using namespace evas;

namespace {

/// Sum of bar lengths of the truss layout described in solver/truss.cpp, by hand:
/// per section 4 edges (w) + 2 diagonals (sqrt(2) w); per bay 4 longitudinal (b),
/// 4 face diagonals sqrt(b^2 + w^2) and 1 internal diagonal sqrt(b^2 + 2 w^2).
double total_bar_length(const TrussBeamSpec& sp) {
  const double b = sp.length / sp.segments, w = sp.width;
  const double section = 4.0 * w + 2.0 * std::sqrt(2.0) * w;
  const double bay = 4.0 * b + 4.0 * std::hypot(b, w) + std::sqrt(b * b + 2.0 * w * w);
  return (sp.segments + 1) * section + sp.segments * bay;
}

}  // namespace

TEST(Truss, GeometryIdsAndNodeSets) {
  TrussBeamSpec sp;
  sp.segments = 4;
  sp.length = 2.0;
  sp.width = 0.1;
  sp.origin = Vec3(1.0, -2.0, 0.5);
  const FeModel fe = make_truss_beam(sp);
  const int N = 4 * (sp.segments + 1);
  ASSERT_EQ(fe.s.rows(), N);
  ASSERT_EQ(static_cast<int>(fe.node_ids.size()), N);
  for (int i = 0; i < N; ++i) EXPECT_EQ(fe.node_ids[i], i + 1);
  // every cross-section is a square of side `width` centred on the axis through origin
  for (int k = 0; k <= sp.segments; ++k) {
    Vec3 centre = Vec3::Zero();
    for (int c = 0; c < 4; ++c) centre += fe.s.row(4 * k + c).transpose() / 4.0;
    EXPECT_NEAR((centre - (sp.origin + Vec3(k * sp.length / sp.segments, 0, 0))).norm(), 0.0,
                1e-14);
    for (int c = 0; c < 4; ++c) {
      const Vec3 d = fe.s.row(4 * k + c).transpose() - centre;
      EXPECT_NEAR(d.x(), 0.0, 1e-14);
      EXPECT_NEAR(std::abs(d.y()), 0.5 * sp.width, 1e-14);
      EXPECT_NEAR(std::abs(d.z()), 0.5 * sp.width, 1e-14);
    }
  }
  ASSERT_EQ(fe.node_sets.count("end0"), 1u);
  ASSERT_EQ(fe.node_sets.count("end1"), 1u);
  ASSERT_EQ(fe.node_sets.count("all"), 1u);
  EXPECT_EQ(fe.node_sets.at("end0"), (std::vector<long>{1, 2, 3, 4}));
  EXPECT_EQ(fe.node_sets.at("end1"), (std::vector<long>{17, 18, 19, 20}));
  EXPECT_EQ(fe.node_sets.at("section2"), (std::vector<long>{9, 10, 11, 12}));
  EXPECT_EQ(fe.node_sets.at("all").size(), static_cast<std::size_t>(N));
  for (int k = 0; k <= sp.segments; ++k)
    EXPECT_EQ(fe.node_sets.count("section" + std::to_string(k)), 1u);
}

TEST(Truss, MassIsSumOfBarMassesAndDiagonal) {
  TrussBeamSpec sp;
  sp.segments = 7;
  sp.length = 1.3;
  sp.width = 0.07;
  const FeModel fe = make_truss_beam(sp);
  const int N = static_cast<int>(fe.s.rows());
  ASSERT_EQ(fe.Ms.rows(), N);
  ASSERT_EQ(fe.Ms.cols(), N);
  double total = 0.0;
  for (int c = 0; c < fe.Ms.outerSize(); ++c)
    for (SpMat::InnerIterator it(fe.Ms, c); it; ++it) {
      EXPECT_EQ(it.row(), c) << "lumped mass must be diagonal";
      EXPECT_GT(it.value(), 0.0);
      total += it.value();
    }
  const double expected = sp.density * sp.area * total_bar_length(sp);
  EXPECT_NEAR(total, expected, 1e-13 * expected);
  std::cout << "[truss] 7 bays: total mass " << total << " kg, by hand " << expected << " kg\n";
}

TEST(Truss, StiffnessSymmetricWithExactlySixZeroEigenvalues) {
  for (int segments : {1, 2, 3, 10, 25}) {
    TrussBeamSpec sp;
    sp.segments = segments;
    sp.length = 0.1 * segments;
    sp.width = 0.05;
    const FeModel fe = make_truss_beam(sp);
    const int n = 3 * static_cast<int>(fe.s.rows());
    ASSERT_EQ(fe.K.rows(), n);
    ASSERT_EQ(fe.K.cols(), n);
    const Mat K = Mat(fe.K);
    EXPECT_LE((K - K.transpose()).norm(), 1e-14 * K.norm());

    // stiffness spectrum alone ...
    Eigen::SelfAdjointEigenSolver<Mat> es(K);
    const Vec ev = es.eigenvalues();
    const double lmax = ev.cwiseAbs().maxCoeff();
    int zeros = 0;
    for (int i = 0; i < n; ++i) {
      if (std::abs(ev[i]) < 1e-10 * lmax)
        ++zeros;
      else
        EXPECT_GT(ev[i], 0.0) << "segments " << segments << " eigenvalue " << i;
    }
    EXPECT_EQ(zeros, 6) << "segments " << segments;
    EXPECT_GT(ev[6], 1e-8 * lmax) << "segments " << segments;

    // ... and the generalized pencil (K, M), M = Ms (x) I3
    Mat M = Mat::Zero(n, n);
    for (int i = 0; i < fe.s.rows(); ++i)
      M.block<3, 3>(3 * i, 3 * i) = fe.Ms.coeff(i, i) * Mat3::Identity();
    Eigen::GeneralizedSelfAdjointEigenSolver<Mat> gs(K, M);
    const Vec gv = gs.eigenvalues();
    const double gmax = gv.cwiseAbs().maxCoeff();
    int gzeros = 0;
    for (int i = 0; i < n; ++i)
      if (std::abs(gv[i]) < 1e-10 * gmax) ++gzeros;
    EXPECT_EQ(gzeros, 6) << "segments " << segments;
    std::cout << "[truss] " << segments << " bays: lambda_7/lambda_max = " << ev[6] / lmax
              << ", |lambda_6|/lambda_max = " << std::abs(ev[5]) / lmax << "\n";

    // rigid motions are in the null space: translations and small rotations
    for (int a = 0; a < 3; ++a) {
      Vec t = Vec::Zero(n), r = Vec::Zero(n);
      Vec3 axis = Vec3::Zero();
      axis[a] = 1.0;
      for (int i = 0; i < fe.s.rows(); ++i) {
        t[3 * i + a] = 1.0;
        r.segment<3>(3 * i) = axis.cross(fe.s.row(i).transpose());
      }
      EXPECT_LE((K * t).norm(), 1e-12 * K.norm() * t.norm());
      EXPECT_LE((K * r).norm(), 1e-12 * K.norm() * r.norm());
    }
  }
}

TEST(Truss, RejectsBadSpec) {
  TrussBeamSpec sp;
  sp.segments = 0;
  EXPECT_THROW(make_truss_beam(sp), InputError);
  sp.segments = 3;
  sp.width = -1.0;
  EXPECT_THROW(make_truss_beam(sp), InputError);
}
