// FirstOrderForm: residual / rhs and their Jacobians against central finite
// differences on a small coupled nonlinear problem, patterns, and no allocation
// when filling.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <new>
#include <random>

#include "solver/first_order.h"

// Count heap allocations while a flag is set (replaces the global operator new
// of this test executable only).
static std::atomic<bool> g_count_allocations{false};
static std::atomic<long> g_allocations{0};

// gcc at -O1 sees the replaced operator delete inlined next to the replaced
// operator new and takes free() for a mismatch: they are this pair
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif
void* operator new(std::size_t size) {
  if (g_count_allocations) ++g_allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace evas {
namespace {

// 3 DOF, cubic springs, coupling through stiffness and velocity-dependent terms:
//   f0 = k1 q0 + c1 q0^3 + kc (q0 - q1) + d0 v0 + e v0 q1 - sin(t)
//   f1 = k2 q1 + kc (q1 - q0) + kc2 (q1 - q2)^3 + d1 v1 + 0.3 v0^2
//   f2 = k3 q2 + kc2 (q2 - q1)^3 + d2 v2^3 + 0.1 q0 v2
// Pattern of K and C (shared): all entries but (0, 2).
class CoupledProblem : public Problem {
 public:
  CoupledProblem() {
    std::vector<Triplet> trip;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        if (!(r == 0 && c == 2)) trip.emplace_back(r, c, 0.0);
    pattern_.resize(3, 3);
    pattern_.setFromTriplets(trip.begin(), trip.end());
    pattern_.makeCompressed();
  }
  int size() const override { return 3; }
  void initial_state(Vec& q, Vec& v) const override {
    q = Vec::Zero(3);
    v = Vec::Zero(3);
  }
  void force(double t, const double* q, const double* v, double* f) override {
    f[0] = k1 * q[0] + c1 * q[0] * q[0] * q[0] + kc * (q[0] - q[1]) + d0 * v[0] + e * v[0] * q[1] -
           std::sin(t);
    const double d12 = q[1] - q[2];
    f[1] = k2 * q[1] + kc * (q[1] - q[0]) + kc2 * d12 * d12 * d12 + d1 * v[1] + 0.3 * v[0] * v[0];
    f[2] = k3 * q[2] - kc2 * d12 * d12 * d12 + d2 * v[2] * v[2] * v[2] + 0.1 * q[0] * v[2];
  }
  void force_jacobian(double, const double* q, const double* v, SpMat& K, SpMat& C) override {
    K.coeffs().setZero();
    C.coeffs().setZero();
    const double d12 = q[1] - q[2];
    K.coeffRef(0, 0) = k1 + 3 * c1 * q[0] * q[0] + kc;
    K.coeffRef(0, 1) = -kc + e * v[0];
    K.coeffRef(1, 0) = -kc;
    K.coeffRef(1, 1) = k2 + kc + 3 * kc2 * d12 * d12;
    K.coeffRef(1, 2) = -3 * kc2 * d12 * d12;
    K.coeffRef(2, 0) = 0.1 * v[2];
    K.coeffRef(2, 1) = -3 * kc2 * d12 * d12;
    K.coeffRef(2, 2) = k3 + 3 * kc2 * d12 * d12;
    C.coeffRef(0, 0) = d0 + e * q[1];
    C.coeffRef(1, 0) = 0.6 * v[0];
    C.coeffRef(1, 1) = d1;
    C.coeffRef(2, 2) = 3 * d2 * v[2] * v[2] + 0.1 * q[0];
  }
  const SpMat& jacobian_pattern() const override { return pattern_; }
  std::string describe_state(double, const double*, const double*) const override {
    return "coupled test problem";
  }

 private:
  const double k1 = 40.0, c1 = 15.0, kc = 7.0, d0 = 0.4, e = 1.3;
  const double k2 = 25.0, kc2 = 30.0, d1 = 0.2;
  const double k3 = 60.0, d2 = 0.9;
  SpMat pattern_;
};

double max_rel_diff(const Mat& A, const Mat& B) {
  return (A - B).cwiseAbs().maxCoeff() / std::max(1.0, B.cwiseAbs().maxCoeff());
}

struct Fixture {
  CoupledProblem p;
  FirstOrderForm form{p};
  Vec y = Vec::Zero(6), yd = Vec::Zero(6);
  double t = 0.37;
  Fixture() {
    std::mt19937 rng(12345);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int i = 0; i < 6; ++i) {
      y[i] = u(rng);
      yd[i] = u(rng);
    }
  }
};

TEST(FirstOrderForm, PatternsAreFixedAndContainDiagonals) {
  Fixture fx;
  const SpMat& J = fx.form.residual_pattern();
  const SpMat& G = fx.form.rhs_pattern();
  EXPECT_EQ(J.rows(), 6);
  EXPECT_TRUE(J.isCompressed());
  EXPECT_TRUE(G.isCompressed());
  // 3 (q,q) diag + 3 (q,v) identity + 8 K entries + (8 C entries + 3 diag - 3 shared) = 22
  EXPECT_EQ(J.nonZeros(), 22);
  EXPECT_EQ(G.nonZeros(), 22);
  for (int i = 0; i < 6; ++i) {
    bool found = false;
    for (SpMat::InnerIterator it(G, i); it; ++it) found = found || it.row() == i;
    EXPECT_TRUE(found) << "rhs pattern lacks diagonal " << i;
  }
}

TEST(FirstOrderForm, ResidualAndRhsValues) {
  Fixture fx;
  Vec F(6), g(6), f(3);
  fx.form.residual(fx.t, fx.y.data(), fx.yd.data(), F.data());
  fx.form.rhs(fx.t, fx.y.data(), g.data());
  fx.p.force(fx.t, fx.y.data(), fx.y.data() + 3, f.data());
  for (int i = 0; i < 3; ++i) {
    EXPECT_DOUBLE_EQ(F[i], fx.yd[i] - fx.y[3 + i]);
    EXPECT_DOUBLE_EQ(F[3 + i], fx.yd[3 + i] + f[i]);
    EXPECT_DOUBLE_EQ(g[i], fx.y[3 + i]);
    EXPECT_DOUBLE_EQ(g[3 + i], -f[i]);
  }
}

TEST(FirstOrderForm, ResidualJacobianMatchesFiniteDifferences) {
  Fixture fx;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.1, 1e3);
  for (int trial = 0; trial < 3; ++trial) {
    const double cj = u(rng);
    SpMat J = fx.form.residual_pattern();
    fx.form.residual_jacobian(fx.t, fx.y.data(), cj, J);
    Mat Jfd(6, 6);
    const double eps = 1e-6;
    Vec Fp(6), Fm(6), Gp(6), Gm(6);
    for (int j = 0; j < 6; ++j) {
      Vec yp = fx.y, ym = fx.y, ydp = fx.yd, ydm = fx.yd;
      yp[j] += eps;
      ym[j] -= eps;
      ydp[j] += eps;
      ydm[j] -= eps;
      fx.form.residual(fx.t, yp.data(), fx.yd.data(), Fp.data());
      fx.form.residual(fx.t, ym.data(), fx.yd.data(), Fm.data());
      fx.form.residual(fx.t, fx.y.data(), ydp.data(), Gp.data());
      fx.form.residual(fx.t, fx.y.data(), ydm.data(), Gm.data());
      Jfd.col(j) = (Fp - Fm) / (2 * eps) + cj * (Gp - Gm) / (2 * eps);
    }
    const double err = max_rel_diff(Mat(J), Jfd);
    std::cout << "residual Jacobian, cj = " << cj << ": max rel. diff. vs FD = " << err << "\n";
    EXPECT_LT(err, 1e-6);
  }
}

TEST(FirstOrderForm, RhsJacobianMatchesFiniteDifferences) {
  Fixture fx;
  SpMat J = fx.form.rhs_pattern();
  fx.form.rhs_jacobian(fx.t, fx.y.data(), J);
  Mat Jfd(6, 6);
  const double eps = 1e-6;
  Vec gp(6), gm(6);
  for (int j = 0; j < 6; ++j) {
    Vec yp = fx.y, ym = fx.y;
    yp[j] += eps;
    ym[j] -= eps;
    fx.form.rhs(fx.t, yp.data(), gp.data());
    fx.form.rhs(fx.t, ym.data(), gm.data());
    Jfd.col(j) = (gp - gm) / (2 * eps);
  }
  const double err = max_rel_diff(Mat(J), Jfd);
  std::cout << "rhs Jacobian: max rel. diff. vs FD = " << err << "\n";
  EXPECT_LT(err, 1e-6);
}

TEST(FirstOrderForm, FillingDoesNotAllocate) {
  Fixture fx;
  SpMat J = fx.form.residual_pattern();
  SpMat G = fx.form.rhs_pattern();
  Vec F(6), g(6);
  g_allocations = 0;
  g_count_allocations = true;
  fx.form.residual(fx.t, fx.y.data(), fx.yd.data(), F.data());
  fx.form.residual_jacobian(fx.t, fx.y.data(), 3.0, J);
  fx.form.rhs(fx.t, fx.y.data(), g.data());
  fx.form.rhs_jacobian(fx.t, fx.y.data(), G);
  g_count_allocations = false;
  EXPECT_EQ(g_allocations.load(), 0);
  EXPECT_EQ(J.nonZeros(), fx.form.residual_pattern().nonZeros());
}

}  // namespace
}  // namespace evas
