// The DAE formulations (dae/formulation.h), the penalty ODE (dae/penalty.h),
// the consistent start (dae/consistent.h) and the pendulum's exact solution
// (problems/pendulum.h).
//
// Iteration matrices: J = dF/dy + cj dF/dy' is the derivative of
// F(y + s e_j, y' + cj s e_j) in s, compared with its central difference
// column by column (SUNDIALS IDA user guide, "Mathematical considerations":
// the Newton matrix of the BDF corrector).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "dae/consistent.h"
#include "dae/formulation.h"
#include "dae/penalty.h"
#include "fd_check.h"
#include "model/types.h"
#include "problems/pendulum.h"

namespace evas {
namespace {

using dae::Formulation;

constexpr double kG = 9.81;

// Largest deviation of J from central differences, relative to 1 + max|column|.
// The analytic iteration matrix of `form` against central differences of the
// residual of `truth` (default: the same form).
double iteration_matrix_error(dae::DaeForm& form, double t, const Vec& y, const Vec& yd, double cj,
                              dae::DaeForm* truth = nullptr) {
  const int N = form.size();
  SpMat J = form.residual_pattern();
  form.residual_jacobian(t, y.data(), yd.data(), cj, J);
  dae::DaeForm& ref = truth ? *truth : form;
  const Mat Jd(J);
  double worst = 0.0;
  Vec Fp(N), Fm(N);
  for (int j = 0; j < N; ++j) {
    const double h = 1e-6;
    Vec yp = y, ym = y, ydp = yd, ydm = yd;
    yp[j] += h;
    ym[j] -= h;
    ydp[j] += cj * h;
    ydm[j] -= cj * h;
    ref.residual(t, yp.data(), ydp.data(), Fp.data());
    ref.residual(t, ym.data(), ydm.data(), Fm.data());
    const Vec col = (Fp - Fm) / (2 * h);
    const double e = (col - Jd.col(j)).cwiseAbs().maxCoeff() / (1.0 + col.cwiseAbs().maxCoeff());
    worst = std::max(worst, e);
  }
  return worst;
}

// A state off the manifold with all multipliers and derivatives non-zero, so
// that every second-derivative term is exercised.
void test_state(int N, Vec& y, Vec& yd) {
  y = Vec(N);
  yd = Vec(N);
  for (int i = 0; i < N; ++i) {
    y[i] = 0.3 + 0.17 * i - 0.05 * i * i;
    yd[i] = -0.4 + 0.23 * i;
  }
}

class FormulationJacobian : public ::testing::TestWithParam<std::string> {};

TEST_P(FormulationJacobian, MatchesFiniteDifferences) {
  const Formulation f = dae::parse_formulation(GetParam(), Formulation::ggl);
  for (double mass : {1.0, 2.5}) {  // without and with a mass matrix
    problems::Pendulum p(mass, 1.3, kG, 0.7);
    dae::DaeForm form(p, f, 3.0, 5.0);
    Vec y, yd;
    test_state(form.size(), y, yd);
    for (double cj : {1.0, 250.0}) {
      const double e = iteration_matrix_error(form, 0.2, y, yd, cj);
      EXPECT_LT(e, 1e-6) << GetParam() << " mass " << mass << " cj " << cj;
    }
  }
}

// The second-derivative terms are needed: the iteration matrix of a pendulum
// that claims linear constraints (so they are skipped, and G is evaluated
// once) fails the comparison with the differences of the true residual.
class LinearClaim : public problems::Pendulum {
 public:
  using problems::Pendulum::Pendulum;
  bool constraints_linear() const override { return true; }
};

TEST_P(FormulationJacobian, SecondDerivativeTermsMatter) {
  const Formulation f = dae::parse_formulation(GetParam(), Formulation::ggl);
  LinearClaim p(2.5, 1.3, kG, 0.7);
  problems::Pendulum truth(2.5, 1.3, kG, 0.7);
  dae::DaeForm form(p, f, 3.0, 5.0), ref(truth, f, 3.0, 5.0);
  Vec y, yd;
  test_state(form.size(), y, yd);
  EXPECT_GT(iteration_matrix_error(form, 0.2, y, yd, 1.0, &ref), 1e-3) << GetParam();
}

INSTANTIATE_TEST_SUITE_P(Dae, FormulationJacobian,
                         ::testing::Values("index-3", "index-2", "ggl", "index-1"));

// The residual of each formulation at the exact solution (consistent values):
// zero up to rounding (Hairer & Wanner 1996, ch. VII.1: the exact solution
// satisfies every formulation, with mu = 0 for GGL).
TEST(DaeFormulations, ResidualVanishesOnExactSolution) {
  problems::Pendulum p(2.0, 1.5, kG, 1.2);
  for (const char* name : {"index-3", "index-2", "ggl", "index-1"}) {
    dae::DaeForm form(p, dae::parse_formulation(name, Formulation::ggl), 4.0, 6.0);
    const double t = 0.37;
    Vec q, v;
    double lambda = 0.0;
    p.exact(t, q, v, lambda);
    // accelerations: d/dt (L cos th th', L sin th th') with th'' = -(g0/L) sin th
    double th = 0.0, thd = 0.0;
    p.exact_angle(t, th, thd);
    const double thdd = -kG / 1.5 * std::sin(th);
    Vec a(2);
    a << 1.5 * (std::cos(th) * thdd - std::sin(th) * thd * thd),
        1.5 * (std::sin(th) * thdd + std::cos(th) * thd * thd);
    Vec y = Vec::Zero(form.size()), yd = Vec::Zero(form.size());
    y << q, v, Vec::Constant(form.size() - 4, 0.0);
    y[4] = lambda;
    yd.head(2) = v;
    yd.segment(2, 2) = a;
    Vec F(form.size());
    form.residual(t, y.data(), yd.data(), F.data());
    EXPECT_LT(F.cwiseAbs().maxCoeff(), 1e-12) << name << ": " << F.transpose();
  }
}

TEST(DaeFormulations, IdsPerFormulation) {
  problems::Pendulum p(2.0, 1.0, kG, 0.5);
  dae::DaeForm i3(p, Formulation::index3, 0, 0), ggl(p, Formulation::ggl, 0, 0);
  EXPECT_EQ(i3.size(), 5);
  EXPECT_EQ(ggl.size(), 6);
  Vec d3(5), e3(5), eg(6);
  d3 << 1, 1, 1, 1, 0;
  e3 << 1, 1, 0, 0, 0;  // index-3: velocities out of the error test too
  eg << 1, 1, 1, 1, 0, 0;
  EXPECT_EQ(i3.differential_id(), d3);
  EXPECT_EQ(i3.error_test_id(), e3);
  EXPECT_EQ(ggl.error_test_id(), eg);
  EXPECT_EQ(ggl.differential_id(), eg);
}

TEST(DaeFormulations, NamesRoundTripAndUnknownIsRefused) {
  for (const char* name : {"index-3", "index-2", "ggl", "index-1", "penalty"})
    EXPECT_EQ(dae::formulation_name(dae::parse_formulation(name, Formulation::ggl)), name);
  EXPECT_EQ(dae::parse_formulation("default", Formulation::index3), Formulation::index3);
  try {
    dae::parse_formulation("index-4", Formulation::ggl);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'index-4' is unknown"), std::string::npos) << e.what();
  }
}

// Penalty forces f + G^T (k g + c g') against central differences of f.
TEST(DaePenalty, JacobianMatchesFiniteDifferences) {
  problems::Pendulum p(2.0, 1.2, kG, 0.8);
  dae::PenaltyProblem pen(p, 1e4, 30.0);
  Vec q(2), v(2);
  q << 0.9, -0.85;  // off the circle: g != 0, so the Hessian term counts
  v << 0.7, 0.4;
  const test_fd::JacobianError e = test_fd::jacobian_fd_error(pen, 0.0, q, v, 1e-6, 1e-6, true);
  EXPECT_LT(e.K, 1e-7);
  EXPECT_LT(e.C, 1e-7);
  // the force itself: f + G^T (k g + c g')
  Vec f(2);
  pen.force(0.0, q.data(), v.data(), f.data());
  const double g = q.squaredNorm() - 1.44, gv = 2 * q.dot(v);
  const double w = 1e4 * g + 30.0 * gv;
  EXPECT_NEAR(f[0], 2 * q[0] * w, 1e-9 * std::abs(w));
  EXPECT_NEAR(f[1], 2.0 * kG + 2 * q[1] * w, 1e-9 * std::abs(w));
  EXPECT_EQ(pen.constraint_count(), 0);
  EXPECT_THROW(dae::PenaltyProblem(p, 0.0, 0.0), InputError);
}

// Projection from an inconsistent start (q 1 % off the circle, v with a
// radial part) onto g = 0, G v = 0; then a and lambda from the saddle-point
// system, against the exact values at release (Hairer & Wanner 1996, VII.1).
TEST(DaeConsistent, ProjectsAndSolvesForMultipliers) {
  const double m = 2.0, L = 1.5, th0 = 1.1;
  problems::Pendulum p(m, L, kG, th0);
  Vec q, v;
  p.initial_state(q, v);
  Vec qi = 1.01 * q, vi = 0.05 * q;  // 1 % off, purely radial velocity
  const dae::ConsistentState s = dae::consistent_state(p, 0.0, qi, vi);
  EXPECT_LT(s.g_norm, 1e-13);
  EXPECT_LT(s.gv_norm, 1e-13);
  EXPECT_GE(s.iterations, 2);
  // minimum-norm: the radial error is removed along the rod
  EXPECT_LT((s.q - q).norm(), 1e-12);
  EXPECT_LT(s.v.norm(), 1e-13);
  // at rest at theta0: lambda = m g0 cos(theta0) / (2 L), a tangential of
  // size g0 sin(theta0) towards the bottom
  EXPECT_NEAR(s.lambda[0], m * kG * std::cos(th0) / (2 * L), 1e-12);
  EXPECT_NEAR(s.a[0], -kG * std::sin(th0) * std::cos(th0), 1e-12);
  EXPECT_NEAR(s.a[1], -kG * std::sin(th0) * std::sin(th0), 1e-12);
}

// The exact solution satisfies theta'' = -(g0/L) sin theta, the constraint,
// and the period formula (Lawden, Elliptic Functions and Applications, 1989).
TEST(Pendulum, ExactSolutionSolvesTheEquation) {
  const double L = 1.5, th0 = 2.0;
  problems::Pendulum p(1.0, L, kG, th0);
  double th = 0, thd = 0;
  p.exact_angle(0.0, th, thd);
  EXPECT_NEAR(th, th0, 1e-14);
  EXPECT_NEAR(thd, 0.0, 1e-14);
  const double T = p.period();
  EXPECT_GT(T, 2 * M_PI * std::sqrt(L / kG));  // longer than the small-swing period
  p.exact_angle(0.5 * T, th, thd);
  EXPECT_NEAR(th, -th0, 1e-10);
  p.exact_angle(T, th, thd);
  EXPECT_NEAR(th, th0, 1e-10);
  for (double t : {0.1, 0.77, 1.9}) {
    const double h = 1e-4;
    double a, ad, b, bd, c, cd;
    p.exact_angle(t - h, a, ad);
    p.exact_angle(t, b, bd);
    p.exact_angle(t + h, c, cd);
    EXPECT_NEAR((c - a) / (2 * h), bd, 1e-6);
    EXPECT_NEAR((cd - ad) / (2 * h), -kG / L * std::sin(b), 1e-6);
    Vec q, v;
    double lam;
    p.exact(t, q, v, lam);
    EXPECT_NEAR(q.squaredNorm(), L * L, 1e-13);
    EXPECT_NEAR(q.dot(v), 0.0, 1e-13);
  }
  EXPECT_THROW(problems::Pendulum(1.0, 1.0, kG, 4.0), InputError);
}

}  // namespace
}  // namespace evas
