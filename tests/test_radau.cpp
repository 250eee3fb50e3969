// Radau IIA (integrators/radau.cpp) against its definition and the closed-form
// oscillators of tests/sdof_problem.h:
//   tableau: the collocation conditions C(3), the quadrature conditions B(5)
//     (order 5), the eigenvalues of A^-1 against their closed forms and the
//     embedded estimate's coefficients against Hairer & Wanner's (Solving ODEs
//     II, 2nd ed., section IV.8);
//   fixed steps: observed order 5 in q and v;
//   adaptive steps: the error follows rtol, each step's estimate is O(h^4);
//   stops: landed exactly, restarts after a kick.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <iostream>

#include "integrators/integrator.h"
#include "integrators/radau.h"
#include "sdof_problem.h"
#include "sdof_run.h"

namespace evas {
namespace {

using test::oscillators;
using test::SdofProblem;
using test::Stop;

using test::Errors;
using test::run_sdof;

TEST(RadauTableau, CollocationAndQuadratureConditions) {
  const RadauTableau T = radau_iia5_tableau();
  // c_1, c_2: the roots of 10 x^2 - 8 x + 1 (zeros of the Radau right polynomial
  // d^2/dx^2 [x^2 (x - 1)^3] besides x = 1), c_3 = 1
  for (int i = 0; i < 2; ++i) {
    const double c = T.c[static_cast<std::size_t>(i)];
    EXPECT_NEAR(10 * c * c - 8 * c + 1, 0.0, 1e-14);
  }
  EXPECT_EQ(T.c[2], 1.0);
  // C(3): sum_j a_ij c_j^(k-1) = c_i^k / k, k = 1..3 (stage order 3)
  for (int i = 0; i < 3; ++i)
    for (int k = 1; k <= 3; ++k) {
      double s = 0.0;
      for (int j = 0; j < 3; ++j)
        s += T.A(i, j) * std::pow(T.c[static_cast<std::size_t>(j)], k - 1);
      EXPECT_NEAR(s, std::pow(T.c[static_cast<std::size_t>(i)], k) / k, 1e-15) << i << " " << k;
    }
  // B(5) with b = the last row of A (stiffly accurate): order 5
  for (int k = 1; k <= 5; ++k) {
    double s = 0.0;
    for (int j = 0; j < 3; ++j) s += T.A(2, j) * std::pow(T.c[static_cast<std::size_t>(j)], k - 1);
    EXPECT_NEAR(s, 1.0 / k, 1e-15) << k;
  }
}

TEST(RadauTableau, TransformationAndEmbeddedEstimate) {
  const RadauTableau T = radau_iia5_tableau();
  // eigenvalues of A^-1 in closed form (Hairer & Wanner IV.8; the constants of RADAU5)
  const double c81 = std::cbrt(81.0), c9 = std::cbrt(9.0);
  const double g = 30.0 / (6.0 + c81 - c9);
  double alpha = (12.0 - c81 + c9) / 60.0, beta = (c81 + c9) * std::sqrt(3.0) / 60.0;
  const double cno = alpha * alpha + beta * beta;
  alpha /= cno;
  beta /= cno;
  EXPECT_NEAR(T.g, g, 1e-13);
  EXPECT_NEAR(T.l.real(), alpha, 1e-13);
  EXPECT_NEAR(T.l.imag(), beta, 1e-13);
  // the value RADAU5 (Hairer & Wanner) carries, 30 / (6 + 81^(1/3) - 9^(1/3)) to 16 digits
  EXPECT_NEAR(T.g, 3.637834252744496, 1e-12);
  // V diag V^-1 = D = A^-1, the real eigenvector real
  Eigen::Matrix3cd L = Eigen::Matrix3cd::Zero();
  L(0, 0) = T.g;
  L(1, 1) = T.l;
  L(2, 2) = std::conj(T.l);
  const Eigen::Matrix3cd D = T.V * L * T.Vinv;
  EXPECT_LT((D.real() - T.A.inverse()).norm(), 1e-12);
  EXPECT_LT(D.imag().norm(), 1e-12);
  EXPECT_LT(T.V.col(0).imag().norm(), 1e-14);
  // embedded estimate: e = gamma0 (-13 - 7 sqrt 6, -13 + 7 sqrt 6, -1) / 3, gamma0 = 1/g
  const double s6 = std::sqrt(6.0), g0 = 1.0 / g;
  EXPECT_NEAR(T.b0, g0, 1e-14);
  EXPECT_NEAR(T.e[0], g0 * (-13.0 - 7.0 * s6) / 3.0, 1e-13);
  EXPECT_NEAR(T.e[1], g0 * (-13.0 + 7.0 * s6) / 3.0, 1e-13);
  EXPECT_NEAR(T.e[2], -g0 / 3.0, 1e-13);
}

TEST(RadauTableau, SplitComplexLUSolvesLikeEigen) {
  // a random complex matrix, some rows scaled so that pivoting matters
  const int n = 9;
  std::srand(7);
  Eigen::MatrixXcd A = Eigen::MatrixXcd::Random(n, n);
  A.row(0) *= 1e-6;
  A.row(4) *= 1e3;
  const Eigen::VectorXcd b = Eigen::VectorXcd::Random(n);
  SplitComplexLU lu;
  lu.resize(n);
  lu.re() = A.real();
  lu.im() = A.imag();
  ASSERT_TRUE(lu.factor());
  Vec xr = b.real(), xi = b.imag();
  lu.solve(xr, xi);
  const Eigen::VectorXcd x = A.partialPivLu().solve(b);
  Eigen::VectorXcd y(n);
  y.real() = xr;
  y.imag() = xi;
  EXPECT_LT((y - x).norm() / x.norm(), 1e-12);
  EXPECT_LT((A * y - b).norm() / (A.norm() * y.norm()), 1e-14);
  // singular: a zero column
  lu.re().col(3).setZero();
  lu.im().col(3).setZero();
  EXPECT_FALSE(lu.factor());
}

TEST(Radau, FifthOrderWithFixedSteps) {
  IntegratorSettings s;
  s.name = "radau";
  s.step_control = StepControl::fixed;
  s.rtol = 1e-13;  // Newton tolerance: far below the truncation error
  s.atol = 1e-15;
  const double h0 = 0.04;
  double e[3], ev[3];
  IntegratorStats st;
  for (int k = 0; k < 3; ++k) {
    s.step = h0 / std::pow(2.0, k);
    SdofProblem p(oscillators());
    // outputs on the step grid (t = 1 is a multiple of every h): the step's
    // end values, not the dense output
    const Errors err = run_sdof(s, p, {0.4, 1.0}, &st);
    e[k] = err.q;
    ev[k] = err.v;
  }
  const double o1 = std::log2(e[0] / e[1]), o2 = std::log2(e[1] / e[2]);
  const double v2 = std::log2(ev[1] / ev[2]);
  std::cout << std::setprecision(4) << "radau |q err| for h = 0.04, 0.02, 0.01: " << e[0] << ", "
            << e[1] << ", " << e[2] << "; orders " << o1 << ", " << o2 << "; |v err| order " << v2
            << "; last run " << st.steps << " steps, " << st.nonlinear_iterations << " iterations, "
            << st.jacobian_evals << " Jacobians\n";
  EXPECT_GE(o1, 4.6);
  EXPECT_LE(o1, 5.4);
  EXPECT_GE(o2, 4.6);
  EXPECT_LE(o2, 5.4);
  EXPECT_GE(v2, 4.6);
  EXPECT_LE(v2, 5.4);
  // a linear problem: one Jacobian for the whole run
  EXPECT_EQ(st.jacobian_evals, 1);
}

TEST(Radau, DenseOutputIsFourthOrder) {
  // between steps: the collocation polynomial, O(h^4) in the middle of a step
  IntegratorSettings s;
  s.name = "radau";
  s.step_control = StepControl::fixed;
  s.rtol = 1e-13;
  s.atol = 1e-15;
  std::vector<double> outputs;
  for (int k = 0; k < 20; ++k) outputs.push_back(0.0137 + 0.0493 * k);  // off the step grid
  double e[3];
  for (int k = 0; k < 3; ++k) {
    s.step = 0.04 / std::pow(2.0, k);
    SdofProblem p(oscillators());
    e[k] = run_sdof(s, p, outputs).q;
  }
  const double o1 = std::log2(e[0] / e[1]), o2 = std::log2(e[1] / e[2]);
  std::cout << "radau dense output |q err| h = 0.04, 0.02, 0.01: " << e[0] << ", " << e[1] << ", "
            << e[2] << " (orders " << o1 << ", " << o2 << ")\n";
  EXPECT_GE(o2, 3.6);
  EXPECT_LE(o2, 4.6);
}

TEST(Radau, AdaptiveErrorFollowsTolerance) {
  const std::vector<double> outputs = test::tenth_outputs();
  const double rtols[3] = {1e-4, 1e-6, 1e-8};
  double e[3];
  long steps[3];
  for (int k = 0; k < 3; ++k) {
    IntegratorSettings s;
    s.name = "radau";
    s.step_control = StepControl::adaptive;
    s.step = 1e-3;
    s.rtol = rtols[k];
    s.atol = 1e-2 * rtols[k];
    SdofProblem p(oscillators());
    IntegratorStats st;
    e[k] = run_sdof(s, p, outputs, &st).q;
    steps[k] = st.steps;
    std::cout << "radau adaptive rtol " << rtols[k] << ": max |q err| " << e[k] << " ("
              << e[k] / rtols[k] << " rtol), " << st.steps << " steps, " << st.error_test_failures
              << " rejected, " << st.linear_setups << " factorizations\n";
  }
  EXPECT_LT(e[1], e[0]);
  EXPECT_LT(e[2], e[1]);
  for (int k = 0; k < 3; ++k) EXPECT_LT(e[k], 5 * rtols[k]) << "rtol " << rtols[k];
  // an O(h^4) estimate: 100x tighter rtol, about 100^(1/4) = 3.2x the steps
  for (int k = 0; k < 2; ++k) {
    const double ratio = static_cast<double>(steps[k + 1]) / static_cast<double>(steps[k]);
    EXPECT_GT(ratio, 2.0) << k;
    EXPECT_LT(ratio, 5.0) << k;
  }
}

TEST(Radau, LandsOnStopsAndRestarts) {
  const std::vector<Stop> stops = test::kicked_stops();
  SdofProblem p(oscillators(), true, stops);
  const std::vector<double> outputs = test::tenth_outputs();
  IntegratorSettings s;
  s.name = "radau";
  s.rtol = 1e-10;
  s.atol = 1e-12;
  s.step = 7e-3;  // outputs and stops fall between steps
  IntegratorStats st;
  const Errors e = run_sdof(s, p, outputs, &st);
  ASSERT_EQ(p.landed.size(), 3u);
  EXPECT_EQ(p.landed[0], 0.3137);
  EXPECT_EQ(p.landed[1], 0.5);
  EXPECT_EQ(p.landed[2], 0.6502);
  EXPECT_EQ(st.restarts, 2);
  std::cout << "radau with stops: |q err| " << e.q << "\n";
  EXPECT_LT(e.q, 3e-8);  // measured 5.9e-9
}

TEST(Radau, RefusesInvalidSettings) {
  IntegratorSettings s;
  s.name = "radau";
  s.rtol = 0.0;
  SdofProblem p(oscillators());
  Vec q0, v0;
  p.initial_state(q0, v0);
  auto integ = make_integrator("radau");
  EXPECT_THROW(integ->init(p, 0.0, q0, v0, s), InputError);
}

}  // namespace
}  // namespace evas
