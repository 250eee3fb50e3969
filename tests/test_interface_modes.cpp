// Interface (static correction) modes on a slender free-free truss beam.
//
// References: R. R. Craig and M. C. C. Bampton, "Coupling of substructures for
// dynamic analyses", AIAA Journal 6(7), 1968 (static constraint modes of the
// interface); static correction modes with inertia relief for unconstrained
// bodies as in J. M. Dickens and K. V. Pool and W. S. Yoo and E. J. Haug,
// "Dynamics of flexible mechanical systems using vibration and static
// correction modes", J. Mech. Trans. Autom. Des. 108, 1986 (the paper's
// reference 5).
//
// The check: a static load at a "bearing" section near one end of the beam,
// balanced by inertia relief. The exact deflection (dense solve of the full
// model) is compared with the modal (Ritz) solution u = sum_k phi_k phi_k^T f /
// lambda_k using 2, 4, 8, 16 normal modes, with and without the interface
// modes of that section. Without them the error falls slowly as modes are added;
// with them a load in the span of the interface loads is reproduced to
// round-off, and by reciprocity so is the response *at the interface* to any
// load (the error of the Ritz solution is K-orthogonal to the static shapes).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "bodies/body_builder.h"
#include "bodies/interface_modes.h"
#include "bodies/reduce_body.h"

using namespace evas;

namespace {

// M = Ms (x) I3 as a dense matrix.
Mat dense_mass(const SpMat& Ms) {
  return apply_mass(Ms, Mat::Identity(3 * Ms.rows(), 3 * Ms.rows()));
}

TrussBeamSpec slender_truss() {
  TrussBeamSpec sp;
  sp.segments = 40;
  sp.length = 2.0;
  sp.width = 0.08;
  sp.origin = Vec3(0.1, -0.02, 0.03);
  return sp;
}

/// Exact inertia-relief static solution, independent of InertiaReliefSolver:
/// (K + a M R R^T M) u = f - M R R^T f gives R^T M u = 0 and K u = f - M R R^T f
/// (a > 0, chosen of the size of K / M so that the rigid directions do not spoil
/// the conditioning), plus one step of iterative refinement.
struct DenseExact {
  Mat K, M, R, A;
  Eigen::LDLT<Mat> ldlt;
  explicit DenseExact(const FeModel& fe)
      : K(Mat(fe.K)), M(dense_mass(fe.Ms)), R(rigid_basis(fe.s, fe.Ms)) {
    const Mat MR = M * R;
    A = K + (K.trace() / M.trace()) * MR * MR.transpose();
    ldlt.compute(A);
  }
  Vec solve(const Vec& f) const {
    const Vec feq = f - M * (R * (R.transpose() * f));
    Vec u = ldlt.solve(feq);
    u += ldlt.solve(feq - A * u);
    return u;
  }
};

/// Ritz (modal) static solution with the elastic modes of the body.
Vec modal_static(const ModalBody& b, const Vec& f) {
  Vec u = Vec::Zero(b.modes.rows());
  for (int k = 0; k < b.num_modes(); ++k)
    if (b.kinds[k] == ModeKind::Elastic)
      u += b.modes.col(k) * (b.modes.col(k).dot(f) / b.eigenvalues[k]);
  return u;
}

/// Mean displacement of a node set (the translation of its centroid).
Vec3 set_translation(const FeModel& fe, const std::vector<long>& set, const Vec& u) {
  Vec3 t = Vec3::Zero();
  for (long id : set) {
    int i = 0;
    while (fe.node_ids[i] != id) ++i;
    t += u.segment<3>(3 * i);
  }
  return t / static_cast<double>(set.size());
}

double energy_error(const Mat& K, const Vec& u, const Vec& ue) {
  const Vec e = u - ue;
  return std::sqrt(e.dot(K * e) / ue.dot(K * ue));
}

void check_basis(const FeModel& fe, const ModalBody& b, const Mat& K, const Mat& M, const Mat& R) {
  const int n = b.num_modes();
  const Mat& P = b.modes;
  EXPECT_LT((P.transpose() * M * P - Mat::Identity(n, n)).cwiseAbs().maxCoeff(), 1e-10);
  Mat D = P.transpose() * K * P;
  D.diagonal() -= b.eigenvalues;
  EXPECT_LT(D.cwiseAbs().maxCoeff() / b.eigenvalues.maxCoeff(), 1e-10);
  for (int k = 0; k < n; ++k)
    if (b.kinds[k] == ModeKind::Elastic) {
      EXPECT_LT((R.transpose() * M * P.col(k)).norm(), 1e-10) << "mode " << k;
    }
  EXPECT_EQ(b.node_ids, fe.node_ids);
}

}  // namespace

TEST(InterfaceModes, LoadsAreRbe3Spreading) {
  const FeModel fe = make_truss_beam(slender_truss());
  const auto& set = fe.node_sets.at("section2");
  const Mat F = interface_loads(fe, set, true);
  ASSERT_EQ(F.cols(), 6);  // a 4-node square section carries 3 forces and 3 moments
  Vec3 c = Vec3::Zero();
  for (long id : set) c += fe.s.row(id - 1).transpose() / 4.0;
  for (int j = 0; j < 6; ++j) {
    Vec3 force = Vec3::Zero(), moment = Vec3::Zero();
    for (int i = 0; i < fe.s.rows(); ++i) {
      const Vec3 fi = F.block<3, 1>(3 * i, j);
      force += fi;
      moment += (fe.s.row(i).transpose() - c).cross(fi);
    }
    if (j < 3) {
      EXPECT_NEAR((force - Vec3::Unit(j)).norm(), 0.0, 1e-14);
      EXPECT_NEAR(moment.norm(), 0.0, 1e-14);
    } else {
      EXPECT_NEAR(force.norm(), 0.0, 1e-12);
      EXPECT_NEAR(moment.norm(), 1.0, 1e-12);  // unit moment about a principal axis
    }
  }
  // A single node carries forces only; unknown nodes are an input error.
  EXPECT_EQ(interface_loads(fe, {7}, true).cols(), 3);
  EXPECT_THROW(interface_loads(fe, {99999}, true), InputError);
}

TEST(InterfaceModes, InertiaReliefSolverIsExact) {
  const FeModel fe = make_truss_beam(slender_truss());
  const DenseExact ex(fe);
  const InertiaReliefSolver irs(fe);
  const Mat F = interface_loads(fe, fe.node_sets.at("section2"), true);
  const Mat U = irs.solve(F);
  const Mat Feq = irs.relieve(F);
  for (int j = 0; j < F.cols(); ++j) {
    const Vec ue = ex.solve(F.col(j));
    EXPECT_LT((U.col(j) - ue).norm() / ue.norm(), 1e-9) << "load " << j;
    EXPECT_LT((ex.K * U.col(j) - Feq.col(j)).norm() / Feq.col(j).norm(), 1e-9);
    EXPECT_LT((ex.R.transpose() * ex.M * U.col(j)).norm(), 1e-12 * U.col(j).norm());
  }
}

TEST(InterfaceModes, StaticDeflectionConvergence) {
  const FeModel fe = make_truss_beam(slender_truss());
  const DenseExact ex(fe);
  BuildOptions bo;
  bo.num_elastic = 16;
  bo.solver = "dense";
  const ModalBody full = build_modal_body("beam", fe, bo);
  const std::vector<long>& bearing = fe.node_sets.at("section2");

  // Load 1 (in the span of the interface loads): a bearing force (0, 1000, 300) N
  // and a 20 N m torque about the beam axis, spread over the section's corners.
  Vec f1 = Vec::Zero(3 * fe.s.rows());
  {
    Vec3 c = Vec3::Zero();
    for (long id : bearing) c += fe.s.row(id - 1).transpose() / 4.0;
    double j = 0.0;
    for (long id : bearing) {
      const Vec3 d = fe.s.row(id - 1).transpose() - c;
      j += d.y() * d.y() + d.z() * d.z();
    }
    for (long id : bearing) {
      const Vec3 d = fe.s.row(id - 1).transpose() - c;
      f1.segment<3>(3 * (id - 1)) += Vec3(0.0, 1000.0, 300.0) / 4.0;
      f1.segment<3>(3 * (id - 1)) += 20.0 / j * Vec3::UnitX().cross(d);
    }
  }
  // Load 2 (outside the span): a 1000 N point force on one corner node at the far
  // end (section 38), measured at the bearing.
  Vec f2 = Vec::Zero(3 * fe.s.rows());
  const long far_node = fe.node_sets.at("section38").front();
  f2.segment<3>(3 * (far_node - 1)) = Vec3(0.0, 0.0, 1000.0);

  const Vec ue1 = ex.solve(f1), ue2 = ex.solve(f2);
  const Vec3 pe1 = set_translation(fe, bearing, ue1), pe2 = set_translation(fe, bearing, ue2);

  std::printf(
      "\n| normal modes n | load at bearing: rel. error at load point, normal | + interface | "
      "energy error, normal | + interface | far load, error at bearing, normal | + interface "
      "|\n|---|---|---|---|---|---|---|\n");
  double prev_energy = 2.0, first_point = 0.0, last_point = 0.0;
  for (int n : {2, 4, 8, 16}) {
    std::vector<int> keep;
    for (int k = 0; k < 6 + n; ++k) keep.push_back(k);
    const ModalBody b = full.select_modes(keep);
    const ModalBody bi = add_interface_modes(fe, b, {bearing}, InterfaceOptions{});
    ASSERT_EQ(bi.num_modes(), b.num_modes() + 6);
    check_basis(fe, bi, ex.K, ex.M, ex.R);
    // The correction modes lie above the kept normal modes.
    for (int k = b.num_modes(); k < bi.num_modes(); ++k)
      EXPECT_GT(bi.eigenvalues[k], b.eigenvalues.maxCoeff());

    const Vec u1 = modal_static(b, f1), u1i = modal_static(bi, f1);
    const Vec u2 = modal_static(b, f2), u2i = modal_static(bi, f2);
    const double p1 = (set_translation(fe, bearing, u1) - pe1).norm() / pe1.norm();
    const double p1i = (set_translation(fe, bearing, u1i) - pe1).norm() / pe1.norm();
    const double e1 = energy_error(ex.K, u1, ue1), e1i = energy_error(ex.K, u1i, ue1);
    const double p2 = (set_translation(fe, bearing, u2) - pe2).norm() / pe2.norm();
    const double p2i = (set_translation(fe, bearing, u2i) - pe2).norm() / pe2.norm();
    std::printf("| %d | %.3e | %.3e | %.3e | %.3e | %.3e | %.3e |\n", n, p1, p1i, e1, e1i, p2, p2i);

    EXPECT_LT(e1, prev_energy);  // Ritz: the energy error falls as modes are added
    prev_energy = e1;
    if (n == 2) first_point = p1;
    last_point = p1;
    EXPECT_LT(p1i, 1e-8);
    EXPECT_LT(e1i, 1e-8);
    EXPECT_LT(p2i, 1e-8);  // reciprocity: exact at the interface for any load
    EXPECT_LT(p1i, 1e-4 * p1);
  }
  EXPECT_LT(last_point, first_point);
}

TEST(InterfaceModes, SeveralSetsAndRedundancy) {
  const FeModel fe = make_truss_beam(slender_truss());
  const DenseExact ex(fe);
  BuildOptions bo;
  bo.num_elastic = 6;
  bo.solver = "dense";
  bo.damping_ratio = 0.01;
  const ModalBody b = build_modal_body("beam", fe, bo);
  InterfaceOptions io;
  io.damping_ratio = 0.02;
  // The same set twice adds its shapes once; a second set and a single node add theirs.
  const auto& s2 = fe.node_sets.at("section2");
  const ModalBody bi = add_interface_modes(fe, b, {s2, s2, fe.node_sets.at("section38"), {1}}, io);
  EXPECT_EQ(bi.num_modes(), b.num_modes() + 6 + 6 + 3);
  check_basis(fe, bi, ex.K, ex.M, ex.R);
  for (int k = b.num_modes(); k < bi.num_modes(); ++k) {
    EXPECT_EQ(bi.kinds[k], ModeKind::Elastic);
    EXPECT_NEAR(bi.damping[k], 2.0 * 0.02 * std::sqrt(bi.eigenvalues[k]), 1e-12 * bi.damping[k]);
    if (k > b.num_modes()) {
      EXPECT_GE(bi.eigenvalues[k], bi.eigenvalues[k - 1]);
    }
  }
  // Forces only: 3 per set.
  io.moments = false;
  EXPECT_EQ(add_interface_modes_by_name(fe, b, {"section2"}, io).num_modes(), b.num_modes() + 3);
  EXPECT_THROW(add_interface_modes_by_name(fe, b, {"nope"}, io), InputError);
  // Adding the modes again adds nothing: they are already in the basis.
  EXPECT_EQ(add_interface_modes(fe, bi, {s2}, InterfaceOptions{}).num_modes(), bi.num_modes());
  // A body that carries stored invariants (format v2) gets a valid body back, whose
  // invariants are those of the new mode set once stored again.
  ModalBody bs = b;
  store_full_body_data(bs);
  ASSERT_TRUE(bs.invariants);
  ModalBody bsi = add_interface_modes(fe, bs, {s2}, io);
  EXPECT_FALSE(bsi.invariants);
  EXPECT_NO_THROW(bsi.validate());
  store_full_body_data(bsi);
  EXPECT_NO_THROW(bsi.validate());
}

namespace {

/// Residual compliance of a body at the loads F: F^T (U_exact - U_modal), the
/// static compliance its elastic modes miss (symmetric positive semidefinite,
/// since a Ritz basis under-estimates compliance).
Mat missing_compliance(const DenseExact& ex, const ModalBody& b, const Mat& F) {
  Mat E(F.cols(), F.cols());
  Mat D(F.rows(), F.cols());
  for (int j = 0; j < F.cols(); ++j) D.col(j) = ex.solve(F.col(j)) - modal_static(b, F.col(j));
  E = F.transpose() * D;
  return 0.5 * (E + E.transpose());
}

double largest_eigenvalue(const Mat& A) {
  return Eigen::SelfAdjointEigenSolver<Mat>(A).eigenvalues().maxCoeff();
}

ModalBody six_mode_beam(const FeModel& fe) {
  BuildOptions bo;
  bo.num_elastic = 6;
  bo.solver = "dense";
  return build_modal_body("beam", fe, bo);
}

}  // namespace

// A journal loads its set radially: two forces, not six loads. With the mask the
// set adds two shapes, a load in their span is exact and an axial one is not.
TEST(InterfaceModes, LoadMaskKeepsTheLoadedDirections) {
  const FeModel fe = make_truss_beam(slender_truss());
  const DenseExact ex(fe);
  const ModalBody b = six_mode_beam(fe);
  const auto& s2 = fe.node_sets.at("section2");
  InterfaceOptions io;
  io.loads = {InterfaceLoadMask{{false, true, true}, false}};
  const ModalBody bi = add_interface_modes(fe, b, {s2}, io);
  ASSERT_EQ(bi.num_modes(), b.num_modes() + 2);
  check_basis(fe, bi, ex.K, ex.M, ex.R);
  const Mat F = interface_loads(fe, s2, false);
  const Vec fy = 700.0 * F.col(1) - 200.0 * F.col(2);
  const Vec uy = ex.solve(fy);
  EXPECT_LT((modal_static(bi, fy) - uy).norm(), 1e-8 * uy.norm());
  const Vec ux = ex.solve(F.col(0));
  EXPECT_GT((modal_static(bi, F.col(0)) - ux).norm(), 1e-3 * ux.norm());
  // Bad masks are refused.
  io.loads = {InterfaceLoadMask{{false, false, false}, false}};
  EXPECT_THROW(add_interface_modes(fe, b, {s2}, io), InputError);
  try {
    add_interface_modes_by_name(fe, b, {"section2"}, io);
    ADD_FAILURE() << "a set without loads was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("set 'section2' has no loads"), std::string::npos)
        << e.what();
  }
  io.loads = {InterfaceLoadMask{}, InterfaceLoadMask{}};
  EXPECT_THROW(add_interface_modes(fe, b, {s2}, io), InputError);
}

// Ranked by residual flexibility (MacNeal 1971; Rubin 1975): keeping the k
// principal load combinations with the largest residual compliance leaves
// exactly the others' compliance missing, the (k+1)-th largest as its largest.
TEST(InterfaceModes, RankingKeepsTheLargestResidualFlexibility) {
  const FeModel fe = make_truss_beam(slender_truss());
  const DenseExact ex(fe);
  const ModalBody b = six_mode_beam(fe);
  const std::vector<std::vector<long>> sets = {
      fe.node_sets.at("section2"), fe.node_sets.at("section20"), fe.node_sets.at("section38")};
  Mat F(3 * fe.s.rows(), 9);
  for (int k = 0; k < 3; ++k) F.middleCols(3 * k, 3) = interface_loads(fe, sets[k], false);
  const Vec s0 = Eigen::SelfAdjointEigenSolver<Mat>(missing_compliance(ex, b, F)).eigenvalues();
  ASSERT_GT(s0[8], 0.0);
  InterfaceOptions io;
  io.moments = false;
  for (int k : {1, 3, 5}) {
    io.max_count = k;
    io.rank_tolerance = 0.0;
    const ModalBody bk = add_interface_modes(fe, b, sets, io);
    ASSERT_EQ(bk.num_modes(), b.num_modes() + k);
    check_basis(fe, bk, ex.K, ex.M, ex.R);
    // s0 ascending: the largest left is s0[8 - k].
    EXPECT_NEAR(largest_eigenvalue(missing_compliance(ex, bk, F)), s0[8 - k], 1e-6 * s0[8])
        << "k = " << k;
  }
  // By tolerance: every combination whose residual compliance is >= tol * max is kept.
  io.max_count = 0;
  io.rank_tolerance = 0.5 * (s0[5] + s0[6]) / s0[8];
  const ModalBody bt = add_interface_modes(fe, b, sets, io);
  EXPECT_EQ(bt.num_modes(), b.num_modes() + 3);
  EXPECT_LT(largest_eigenvalue(missing_compliance(ex, bt, F)), io.rank_tolerance * s0[8]);
  // A body that already carries every load gets nothing (its residual
  // flexibility is round-off, whose shapes are in the span of its modes).
  io.max_count = 0;
  io.rank_tolerance = 1e-3;
  InterfaceOptions all;
  all.moments = false;
  const ModalBody full = add_interface_modes(fe, b, sets, all);
  EXPECT_EQ(add_interface_modes(fe, full, sets, io).num_modes(), full.num_modes());
  io.rank_tolerance = 1.5;
  EXPECT_THROW(add_interface_modes(fe, b, sets, io), InputError);
}

// Load-dependent Ritz vectors (E. L. Wilson, M.-W. Yuan and J. M. Dickens,
// "Dynamic analysis by direct superposition of Ritz vectors", Earthquake Eng.
// Struct. Dyn. 10, 1982): the blocks K^+ M X span the Krylov sequence of the
// load, and the forced response to the load below the first resonance converges
// with each block.
TEST(InterfaceModes, RitzBlocksConvergeTheForcedResponse) {
  const FeModel fe = make_truss_beam(slender_truss());
  const DenseExact ex(fe);
  BuildOptions bo;
  bo.num_elastic = 2;
  bo.solver = "dense";
  const ModalBody b = build_modal_body("beam", fe, bo);
  const auto& s38 = fe.node_sets.at("section38");
  const Mat F = interface_loads(fe, s38, false);
  const Vec f = F.col(1) + 0.5 * F.col(2);
  const Vec feq = f - ex.M * (ex.R * (ex.R.transpose() * f));
  // Between the 2nd and 3rd elastic eigenvalue of the full model (a basis of two
  // eigenmodes misses the resonances above).
  const double w2 = 0.5 * b.eigenvalues[b.num_modes() - 1];
  const Vec exact = Eigen::PartialPivLU<Mat>(ex.K - w2 * ex.M).solve(feq);
  InterfaceOptions io;
  io.moments = false;
  io.loads = {InterfaceLoadMask{{false, true, true}, false}};
  double last = 1e300;
  for (int blocks = 0; blocks <= 3; ++blocks) {
    io.krylov_blocks = blocks;
    const ModalBody br = add_interface_modes(fe, b, {s38}, io);
    EXPECT_EQ(br.num_modes(), b.num_modes() + 2 * (blocks + 1));
    check_basis(fe, br, ex.K, ex.M, ex.R);
    Vec u = Vec::Zero(feq.size());
    for (int k = 0; k < br.num_modes(); ++k)
      if (br.kinds[k] == ModeKind::Elastic)
        u += br.modes.col(k) * (br.modes.col(k).dot(feq) / (br.eigenvalues[k] - w2));
    const double err = (u - exact).norm() / exact.norm();
    std::printf("Ritz blocks %d: forced response error %.3e\n", blocks, err);
    EXPECT_LT(err, 0.2 * last) << "blocks " << blocks;
    last = err;
    if (blocks == 1) {
      // The second block holds K^+ M K^+ f (inertia relief), up to round-off.
      const Vec x = ex.solve(ex.M * ex.solve(feq));
      const Vec r = x - br.modes * (br.modes.transpose() * (ex.M * x));
      EXPECT_LT(std::sqrt(r.dot(ex.M * r) / x.dot(ex.M * x)), 1e-8);
    }
  }
  EXPECT_LT(last, 1e-4);
}
