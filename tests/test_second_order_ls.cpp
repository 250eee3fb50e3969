// The second-order linear solver (integrators/second_order_ls.h): the reduced
// n x n solve against a dense LU of the full 2n x 2n iteration matrix, for
// IDA's and CVODE's coefficients, on the dense and the KLU path; Jacobian
// reuse in IDA; refusal of problems it cannot take.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "integrators/integrator.h"
#include "integrators/second_order_ls.h"
#include "sdof_problem.h"

using namespace evas;

namespace {

// A pattern with the full diagonal and `band` off-diagonals on each side.
SpMat band_pattern(int n, int band) {
  std::vector<Triplet> trip;
  for (int c = 0; c < n; ++c)
    for (int r = std::max(0, c - band); r <= std::min(n - 1, c + band); ++r)
      trip.emplace_back(r, c, 0.0);
  SpMat P(n, n);
  P.setFromTriplets(trip.begin(), trip.end());
  P.makeCompressed();
  return P;
}

// Random K (stiff, non-symmetric: 1e4 .. 1e8 on the diagonal) and damping C
// into `so`; returns the full 2n x 2n matrix A(a..e) on them.
Mat fill_random(SecondOrderSolver& so, double a, double b, double c, double d, double e,
                std::mt19937& rng) {
  const int n = so.size();
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int k = 0; k < so.K().nonZeros(); ++k) {
    so.K().valuePtr()[k] = 1e3 * u(rng);
    so.C().valuePtr()[k] = 10.0 * u(rng);
  }
  for (int i = 0; i < n; ++i) {
    so.K().coeffRef(i, i) = std::pow(10.0, 4.0 + 4.0 * i / n);
    so.C().coeffRef(i, i) = 50.0;
  }
  Mat A = Mat::Zero(2 * n, 2 * n);
  A.topLeftCorner(n, n) = a * Mat::Identity(n, n);
  A.topRightCorner(n, n) = b * Mat::Identity(n, n);
  A.bottomLeftCorner(n, n) = c * Mat(so.K());
  A.bottomRightCorner(n, n) = d * Mat::Identity(n, n) + e * Mat(so.C());
  return A;
}

// max |x - x_ref| / max |x_ref| for A(a..e) x = r solved both ways.
double reduced_vs_full(SecondOrderSolver& so, double a, double b, double c, double d, double e,
                       unsigned seed) {
  const int n = so.size();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Mat A = fill_random(so, a, b, c, d, e, rng);
  Vec r(2 * n);
  for (int i = 0; i < 2 * n; ++i) r[i] = u(rng);
  const Vec ref = A.fullPivLu().solve(r);
  so.set_coefficients(a, b, c, d, e);
  EXPECT_TRUE(so.factor());
  Vec x = r;
  so.solve(x.data(), x.data());  // in place, as SUNDIALS calls it
  return (x - ref).cwiseAbs().maxCoeff() / ref.cwiseAbs().maxCoeff();
}

}  // namespace

// Both coefficient sets (IDA at cj, CVODE at gamma) against the full solve.
void expect_matches_full(SecondOrderSolver& so, double cj, double gamma, unsigned seed,
                         const char* what) {
  const double ida = reduced_vs_full(so, cj, -1.0, 1.0, cj, 1.0, seed);
  const double cvode = reduced_vs_full(so, 1.0, -gamma, gamma, 1.0, gamma, seed + 1);
  std::cout << what << ": IDA " << ida << ", CVODE " << cvode << "\n";
  EXPECT_LT(ida, 1e-10);
  EXPECT_LT(cvode, 1e-10);
}

TEST(SecondOrderSolver, DensePathMatchesFullSolve) {
  SecondOrderSolver so(band_pattern(24, 30));  // full 24 x 24
  EXPECT_TRUE(so.dense());
  expect_matches_full(so, 2e5, 1e-5, 1, "dense");
}

// A dense factorization that serves many solves is inverted after a number of
// them (second_order_ls.cpp, kInvertAfter = 40), and one that follows such a
// factorization on its first solve: every solve meets the full solve, over 120
// solves on one factorization (inverted after 40), 120 on the next (inverted at
// once: the inverse of the old matrix is not used), 10 on the next (inverted at
// once) and 10 on the last (the triangular solves again).
TEST(SecondOrderSolver, DensePathManySolvesOnOneFactorization) {
  SecondOrderSolver so(band_pattern(30, 40));
  ASSERT_TRUE(so.dense());
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (auto [cj, solves] : {std::pair{2e5, 120}, {7e4, 120}, {3e4, 10}, {1e4, 10}}) {
    const Mat A = fill_random(so, cj, -1.0, 1.0, cj, 1.0, rng);
    const auto lu = A.fullPivLu();
    so.set_coefficients(cj, -1.0, 1.0, cj, 1.0);
    ASSERT_TRUE(so.factor());
    double worst = 0.0;
    for (int k = 0; k < solves; ++k) {
      Vec r(60);
      for (int i = 0; i < 60; ++i) r[i] = u(rng);
      const Vec ref = lu.solve(r);
      Vec x = r;
      so.solve(x.data(), x.data());
      const double err = (x - ref).cwiseAbs().maxCoeff() / ref.cwiseAbs().maxCoeff();
      worst = std::max(worst, err);
      EXPECT_LT(err, 1e-10) << "cj " << cj << ", solve " << k;
    }
    std::cout << "cj " << cj << ": worst of " << solves << " solves " << worst << "\n";
  }
}

TEST(SecondOrderSolver, KluPathMatchesFullSolve) {
  SecondOrderSolver so(band_pattern(400, 2));  // n > 200 and sparse: KLU
  EXPECT_FALSE(so.dense());
  expect_matches_full(so, 3e4, 2e-5, 3, "KLU");
}

// Above 200 a pattern at least a quarter full (modal bodies with static
// correction modes) takes the dense path too, up to 800; a banded one does not.
TEST(SecondOrderSolver, FullPatternAbove200IsDense) {
  SecondOrderSolver so(band_pattern(300, 60));  // (2 * 60 + 1) / 300: 37 % full
  EXPECT_TRUE(so.dense());
  expect_matches_full(so, 3e4, 2e-5, 3, "dense, n = 300");
  EXPECT_FALSE(SecondOrderSolver(band_pattern(300, 20)).dense());   // 14 % full
  EXPECT_FALSE(SecondOrderSolver(band_pattern(900, 450)).dense());  // above 800
}

TEST(SecondOrderSolver, SingularMatrixIsAFailedFactorization) {
  SecondOrderSolver so(band_pattern(5, 5));
  // K = -cj^2 I, C = 0: K + cj C + cj^2 I = 0
  so.C().coeffs().setZero();
  so.K().coeffs().setZero();
  for (int i = 0; i < 5; ++i) so.K().coeffRef(i, i) = -4.0;
  so.set_coefficients(2.0, -1.0, 1.0, 2.0, 1.0);
  EXPECT_FALSE(so.factor());
}

// IDA: with jacobian_age = 0 every factorization evaluates K and C; with
// reuse, fewer evaluations than factorizations, and the closed-form solution
// (S. S. Rao, Mechanical Vibrations: damped, forced oscillators) is still
// met to the tolerance.
TEST(SecondOrderSolver, IdaJacobianReuse) {
  for (int age : {0, 20}) {
    test::SdofProblem p(test::oscillators());
    IntegratorSettings s;
    s.name = "ida";
    s.linear_solver = "second-order";
    s.jacobian_age = age;
    s.rtol = 1e-8;
    s.atol = 1e-10;
    auto integ = make_integrator("ida");
    Vec q0, v0;
    p.initial_state(q0, v0);
    integ->init(p, 0.0, q0, v0, s);
    double err = 0.0;
    std::vector<double> outputs;
    for (int k = 1; k <= 20; ++k) outputs.push_back(0.1 * k);
    integrate(*integ, p, 0.0, outputs, [&](double t, const Vec& q, const Vec&) {
      Vec qe, ve;
      p.exact(t, qe, ve);
      err = std::max(err, (q - qe).lpNorm<Eigen::Infinity>());
    });
    const IntegratorStats st = integ->stats();
    std::cout << "jacobian_age " << age << ": " << st.jacobian_evals << " Jacobians, "
              << st.linear_setups << " factorizations, " << st.steps << " steps, error " << err
              << "\n";
    EXPECT_EQ(st.jacobian_evals, p.counters.jac_evals);
    if (age == 0)
      EXPECT_EQ(st.jacobian_evals, st.linear_setups);
    else
      EXPECT_LT(st.jacobian_evals, st.linear_setups);
    EXPECT_LT(err, 5e-8);
  }
}

TEST(SecondOrderSolver, RefusesProblemsWithAMassMatrix) {
  test::MassSdof p(test::oscillators());
  IntegratorSettings s;
  s.linear_solver = "second-order";
  auto integ = make_integrator("ida");
  Vec q, v;
  p.initial_state(q, v);
  try {
    integ->init(p, 0.0, q, v, s);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("second-order"), std::string::npos) << msg;
    EXPECT_NE(msg.find("mass matrix"), std::string::npos) << msg;
    EXPECT_NE(msg.find("use klu"), std::string::npos) << msg;
  }
}

// Gauss-Jordan inverse (integrators/dense_inverse.h): A A^-1 = I to round-off
// (Higham 2002, section 14.4: |A X - I| of order cond(A) eps for partial
// pivoting), and the pivots are the LU's with partial pivoting (Golub & Van
// Loan 2013, section 3.4), whose |diag U| Eigen's PartialPivLU gives.
TEST(DenseInverse, InverseAndPivotsMatchTheLu) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  DenseInverseWork w;
  for (int n : {1, 2, 7, 72}) {
    for (double diag : {0.0, 3.0, 5e9}) {  // 5e9: pivots of 1/d ~ 2e-10 (a stiff S)
      Mat A = Mat::NullaryExpr(n, n, [&] { return u(rng); });
      A.diagonal().array() += diag;
      if (n > 1) A.row(0).swap(A.row(n - 1));  // a zero-ish diagonal: pivoting needed
      Mat X = A;
      double pmin = 0.0, pmax = 0.0;
      ASSERT_TRUE(invert_in_place(X, w, pmin, pmax)) << n;
      const Eigen::PartialPivLU<Mat> lu(A);
      const double cond = A.lpNorm<Eigen::Infinity>() * X.lpNorm<Eigen::Infinity>();
      EXPECT_LT((A * X - Mat::Identity(n, n)).lpNorm<Eigen::Infinity>(), 50 * cond * 1e-16)
          << "n = " << n << ", cond " << cond;
      const auto d = lu.matrixLU().diagonal().cwiseAbs();
      EXPECT_NEAR(pmin, d.minCoeff(), 1e-12 * d.maxCoeff()) << n;
      EXPECT_NEAR(pmax, d.maxCoeff(), 1e-12 * d.maxCoeff()) << n;
    }
  }
  // a permutation matrix: every step exchanges rows, the inverse is its transpose
  Mat P = Mat::Zero(5, 5);
  for (int i = 0; i < 5; ++i) P(i, (i + 2) % 5) = 1.0;
  Mat X = P;
  double pmin = 0.0, pmax = 0.0;
  ASSERT_TRUE(invert_in_place(X, w, pmin, pmax));
  EXPECT_EQ((X - P.transpose()).lpNorm<Eigen::Infinity>(), 0.0);
}

TEST(DenseInverse, ZeroPivotIsRefused) {
  DenseInverseWork w;
  Mat A = Mat::Identity(4, 4);
  A(2, 2) = 0.0;  // column 2 zero below and on the diagonal after steps 0, 1
  double pmin = 0.0, pmax = 0.0;
  EXPECT_FALSE(invert_in_place(A, w, pmin, pmax));
  Mat B = Mat::Identity(3, 3);
  B(1, 1) = std::nan("");
  EXPECT_FALSE(invert_in_place(B, w, pmin, pmax));
}
