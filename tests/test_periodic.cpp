// The periodic solution (run/periodic.h): against the harmonic response of
// linear modal systems, Floquet multipliers against exp(lambda T), a Duffing
// oscillator against the harmonic-balance frequency response with its
// branches told apart by the multipliers, and the methods' cycle counts.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "run/periodic.h"
#include "sdof_problem.h"

namespace evas {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Three damped modes forced at one frequency W (period T = 2 pi / W).
std::vector<test::Oscillator> forced_modes(double W) {
  std::vector<test::Oscillator> o(3);
  const double f[3] = {1.0, 3.0, 5.0}, z[3] = {0.05, 0.1, 0.2}, F[3] = {10.0, -4.0, 7.0};
  for (int i = 0; i < 3; ++i) {
    o[static_cast<std::size_t>(i)].omega = 2 * kPi * f[i];
    o[static_cast<std::size_t>(i)].zeta = z[i];
    o[static_cast<std::size_t>(i)].force = F[i];
    o[static_cast<std::size_t>(i)].force_freq = W;
  }
  return o;
}

// The harmonic solution (K - W^2 + i W C)^-1 F per mode (S. S. Rao,
// Mechanical Vibrations, the steady-state response of a damped oscillator to
// F cos(W t)), at t.
void harmonic(const test::Oscillator& o, double t, double& q, double& v) {
  const std::complex<double> X =
      o.force / std::complex<double>(o.omega * o.omega - o.force_freq * o.force_freq,
                                     2 * o.zeta * o.omega * o.force_freq);
  const std::complex<double> e = std::exp(std::complex<double>(0.0, o.force_freq * t));
  q = std::real(X * e);
  v = std::real(std::complex<double>(0.0, o.force_freq) * X * e);
}

IntegratorSettings tight_ida() {
  IntegratorSettings s;
  s.name = "ida";
  s.rtol = 1e-10;
  s.atol = 1e-12;
  return s;
}

// Largest |exp(lambda T)| multipliers of the modes, lambda = -zeta w +- i w_d.
std::vector<std::complex<double>> mode_multipliers(const std::vector<test::Oscillator>& osc,
                                                   double T) {
  std::vector<std::complex<double>> mu;
  for (const auto& o : osc) {
    const double wd = o.omega * std::sqrt(1 - o.zeta * o.zeta);
    for (double s : {1.0, -1.0})
      mu.push_back(std::exp(std::complex<double>(-o.zeta * o.omega, s * wd) * T));
  }
  return mu;
}

// Each expected multiplier has a found one within tol.
void expect_multipliers(const std::vector<run::FloquetMultiplier>& found,
                        const std::vector<std::complex<double>>& expected, double tol) {
  for (const auto& e : expected) {
    double best = 1e300;
    for (const auto& f : found) best = std::min(best, std::abs(f.mu - e));
    EXPECT_LT(best, tol) << "multiplier " << e.real() << " + " << e.imag() << "i";
  }
}

TEST(Periodic, NewtonOnLinearModesGivesTheHarmonicSolutionInOneIteration) {
  const double W = 2 * kPi * 2.0, T = 2 * kPi / W, t0 = 0.3;
  const auto osc = forced_modes(W);
  test::SdofProblem p(osc);
  run::PeriodicOptions opt;
  opt.method = run::PeriodicMethod::newton;
  opt.coarse = 1.0;  // every cycle at the settings' tolerances
  opt.tol = 1e-9;
  const Vec q0 = Vec::Zero(3), v0 = Vec::Zero(3);
  const run::PeriodicResult r = run::find_periodic(p, t0, T, q0, v0, tight_ida(), opt);
  ASSERT_TRUE(r.converged) << r.message;
  // the cycle map is affine: the first Newton iteration leaves only the
  // differences' error (the integration error over the step 1e-5 of a
  // coordinate's amplitude), the second the integration error
  ASSERT_EQ(r.iterations.size(), 3u);
  EXPECT_EQ(r.iterations[1].step, "newton");
  EXPECT_LT(r.iterations[1].defect, 1e-4 * r.iterations[0].defect);
  EXPECT_EQ(r.cycles, 1 + 2 * (6 + 1));
  for (int i = 0; i < 3; ++i) {
    double q = 0, v = 0;
    harmonic(osc[static_cast<std::size_t>(i)], t0, q, v);
    const double X =
        std::abs(osc[static_cast<std::size_t>(i)].force) /
        std::abs(std::complex<double>(
            osc[static_cast<std::size_t>(i)].omega * osc[static_cast<std::size_t>(i)].omega - W * W,
            2 * osc[static_cast<std::size_t>(i)].zeta * osc[static_cast<std::size_t>(i)].omega *
                W));
    EXPECT_NEAR(r.q[i], q, 1e-7 * X) << "mode " << i;
    EXPECT_NEAR(r.v[i], v, 1e-7 * X * W) << "mode " << i;
  }
  // the monodromy's eigenvalues are exp(lambda T) of the modes
  ASSERT_EQ(r.multipliers.size(), 6u);
  expect_multipliers(r.multipliers, mode_multipliers(osc, T), 1e-5);
  EXPECT_NE(r.multiplier_source.find("monodromy"), std::string::npos);
}

TEST(Periodic, ProjectedNewtonOnLinearModesConvergesInOneIteration) {
  // the linearization of a linear system is exact: one projected step
  const double W = 2 * kPi * 2.0, T = 2 * kPi / W;
  const auto osc = forced_modes(W);
  test::SdofProblem p(osc);
  run::PeriodicOptions opt;
  opt.method = run::PeriodicMethod::projected;
  opt.linearization = "averaged";  // exact for a linear, time-invariant system
  opt.coarse = 1.0;
  opt.tol = 1e-7;
  opt.slow = 1e-3;
  const run::PeriodicResult r =
      run::find_periodic(p, 0.0, T, Vec::Zero(3), Vec::Zero(3), tight_ida(), opt);
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_EQ(r.cycles, 2);
  EXPECT_EQ(r.slow_dimension, 6);
  for (int i = 0; i < 3; ++i) {
    double q = 0, v = 0;
    harmonic(osc[static_cast<std::size_t>(i)], 0.0, q, v);
    EXPECT_NEAR(
        r.q[i], q,
        1e-6 * std::abs(osc[static_cast<std::size_t>(i)].force) /
            (osc[static_cast<std::size_t>(i)].omega * osc[static_cast<std::size_t>(i)].omega))
        << "mode " << i;
  }
  expect_multipliers(r.multipliers, mode_multipliers(osc, T), 1e-6);
}

TEST(Periodic, CoarseCyclesFirstTheAcceptedOneAtTheSettingsTolerances) {
  const double W = 2 * kPi * 2.0, T = 2 * kPi / W;
  const auto osc = forced_modes(W);
  IntegratorSettings loose;
  loose.rtol = 1e-6;
  loose.atol = 1e-9;
  run::PeriodicOptions opt;
  opt.linearization = "averaged";
  opt.tol = 1e-5;
  opt.slow = 1e-3;
  test::SdofProblem p1(osc), p2(osc);
  opt.coarse = 100.0;
  const run::PeriodicResult c =
      run::find_periodic(p1, 0.0, T, Vec::Zero(3), Vec::Zero(3), loose, opt);
  opt.coarse = 1.0;
  const run::PeriodicResult f =
      run::find_periodic(p2, 0.0, T, Vec::Zero(3), Vec::Zero(3), loose, opt);
  ASSERT_TRUE(c.converged) << c.message;
  ASSERT_TRUE(f.converged) << f.message;
  EXPECT_NE(c.iterations.front().step.find("(coarse)"), std::string::npos);
  EXPECT_EQ(c.iterations.back().step.find("(coarse)"), std::string::npos);  // accepted: fine
  EXPECT_LT(c.stats.steps, f.stats.steps * c.cycles / f.cycles);  // coarse cycles are cheaper
  for (int i = 0; i < 3; ++i) {
    double q = 0, v = 0;
    harmonic(osc[static_cast<std::size_t>(i)], 0.0, q, v);
    const double X = std::abs(q) + std::abs(v) / W;
    EXPECT_NEAR(c.q[i], q, 1e-4 * X) << i;
    EXPECT_NEAR(f.q[i], q, 1e-4 * X) << i;
  }
}

TEST(Periodic, SteppedLinearizationApproachesExpLambdaT) {
  // implicit Euler over the cycle: the multipliers' error falls as 1/steps
  const double W = 2 * kPi * 2.0, T = 2 * kPi / W;
  const auto osc = forced_modes(W);
  test::SdofProblem p(osc);
  std::vector<double> t;
  std::vector<Vec> q, v;
  double err[2];
  int k = 0;
  for (int steps : {200, 800}) {
    t.clear();
    q.assign(static_cast<std::size_t>(steps), Vec::Zero(3));
    v.assign(static_cast<std::size_t>(steps), Vec::Zero(3));
    for (int i = 0; i < steps; ++i) t.push_back(T * i / steps);
    const run::Linearization lin = run::stepped_linearization(p, 0.0, T, t, q, v, steps);
    double worst = 0.0;
    for (const auto& e : mode_multipliers(osc, T)) {
      double best = 1e300;
      for (const auto& m : lin.mu) best = std::min(best, std::abs(m - e));
      worst = std::max(worst, best);
    }
    err[k++] = worst;
  }
  EXPECT_LT(err[0], 0.1) << err[1];
  EXPECT_NEAR(err[0] / err[1], 4.0, 0.5);  // first order in the step
}

TEST(Periodic, AndersonNeedsFewerCyclesThanTheFixedPoint) {
  // mode 1's multiplier is exp(-0.05 * 2 pi * 1 * 0.5) = 0.855: a transient
  // needs about 120 cycles to settle to 1e-8
  const double W = 2 * kPi * 2.0, T = 2 * kPi / W;
  const auto osc = forced_modes(W);
  run::PeriodicOptions opt;
  opt.tol = 1e-8;
  opt.max_cycles = 25;
  test::SdofProblem p1(osc);
  opt.method = run::PeriodicMethod::fixed_point;
  const run::PeriodicResult fp =
      run::find_periodic(p1, 0.0, T, Vec::Zero(3), Vec::Zero(3), tight_ida(), opt);
  EXPECT_FALSE(fp.converged);
  EXPECT_EQ(fp.cycles, 25);
  // the message names the defect and the slowest multiplier (0.855)
  EXPECT_NE(fp.message.find("no periodic solution within 25 cycles"), std::string::npos)
      << fp.message;
  EXPECT_NE(fp.message.find("the slowest multiplier |mu| = "), std::string::npos) << fp.message;
  // the defect falls by the slowest multiplier per cycle
  const auto& it = fp.iterations;
  EXPECT_NEAR(it[20].defect / it[19].defect, std::exp(-0.05 * 2 * kPi * 0.5), 0.01);
  test::SdofProblem p2(osc);
  opt.method = run::PeriodicMethod::anderson;
  const run::PeriodicResult an =
      run::find_periodic(p2, 0.0, T, Vec::Zero(3), Vec::Zero(3), tight_ida(), opt);
  ASSERT_TRUE(an.converged) << an.message;
  EXPECT_LE(an.cycles, 12);
}

// Duffing's oscillator qdd + 2 zeta w qd + w^2 q + beta q^3 = F cos(W t).
class Duffing : public Problem {
 public:
  double w = 1.0, zeta = 0.05, beta = 0.2, F = 0.25, W = 1.2;
  Duffing() {
    std::vector<Triplet> t = {{0, 0, 0.0}};
    pattern_.resize(1, 1);
    pattern_.setFromTriplets(t.begin(), t.end());
  }
  int size() const override { return 1; }
  void initial_state(Vec& q, Vec& v) const override {
    q = Vec::Zero(1);
    v = Vec::Zero(1);
  }
  void force(double t, const double* q, const double* v, double* f) override {
    f[0] = 2 * zeta * w * v[0] + w * w * q[0] + beta * q[0] * q[0] * q[0] - F * std::cos(W * t);
  }
  void force_jacobian(double, const double* q, const double*, SpMat& K, SpMat& C) override {
    K.valuePtr()[0] = w * w + 3 * beta * q[0] * q[0];
    C.valuePtr()[0] = 2 * zeta * w;
  }
  const SpMat& jacobian_pattern() const override { return pattern_; }

 private:
  SpMat pattern_;
};

// The one-term harmonic balance of Duffing's oscillator, q = a cos(W t - phi)
// (Nayfeh & Mook, Nonlinear Oscillations, 1979, section 4.1; Kovacic &
// Brennan, The Duffing Equation, 2011, chapter 2):
//   a^2 [(w^2 - W^2 + 3/4 beta a^2)^2 + (2 zeta w W)^2] = F^2,
//   tan(phi) = 2 zeta w W / (w^2 - W^2 + 3/4 beta a^2).
// The amplitudes a at W (one or three), by bisection on a sign change grid.
std::vector<double> hb_amplitudes(const Duffing& d) {
  auto g = [&](double a) {
    const double k = d.w * d.w - d.W * d.W + 0.75 * d.beta * a * a;
    const double c = 2 * d.zeta * d.w * d.W;
    return a * a * (k * k + c * c) - d.F * d.F;
  };
  std::vector<double> roots;
  const int m = 20000;
  const double amax = 10.0;
  for (int i = 0; i < m; ++i) {
    double lo = amax * i / m, hi = amax * (i + 1) / m;
    if (g(lo) * g(hi) > 0) continue;
    for (int k = 0; k < 100; ++k) {
      const double mid = 0.5 * (lo + hi);
      (g(lo) * g(mid) <= 0 ? hi : lo) = mid;
    }
    roots.push_back(0.5 * (lo + hi));
  }
  return roots;
}

TEST(Periodic, DuffingBranchesAgainstHarmonicBalanceAndTheirStability) {
  Duffing d;
  const double T = 2 * kPi / d.W;
  const std::vector<double> a = hb_amplitudes(d);
  ASSERT_EQ(a.size(), 3u) << "W = 1.2 lies in the hardening branch's overhang";
  int stable = 0, unstable = 0;
  for (std::size_t b = 0; b < a.size(); ++b) {
    // start at the harmonic-balance orbit: q(0) = a cos(phi), v(0) = a W sin(phi)
    const double k = d.w * d.w - d.W * d.W + 0.75 * d.beta * a[b] * a[b];
    const double phi = std::atan2(2 * d.zeta * d.w * d.W, k);
    Vec q0(1), v0(1);
    q0[0] = a[b] * std::cos(phi);
    v0[0] = a[b] * d.W * std::sin(phi);
    run::PeriodicOptions opt;
    opt.method = run::PeriodicMethod::newton;
    opt.coarse = 1.0;
    opt.tol = 1e-9;
    const run::PeriodicResult r = run::find_periodic(d, 0.0, T, q0, v0, tight_ida(), opt);
    ASSERT_TRUE(r.converged) << "branch " << b << ": " << r.message;
    // the first harmonic of the periodic solution against a: one term of
    // harmonic balance neglects the third harmonic, here 1-3 % of a
    struct Fourier : run::CycleObserver {
      double W = 0, c = 0, s = 0;
      int n = 0;
      void state(double t, const Vec& q, const Vec&) override {
        c += q[0] * std::cos(W * t);
        s += q[0] * std::sin(W * t);
        ++n;
      }
    } fourier;
    fourier.W = d.W;
    std::vector<double> samples;
    for (int i = 0; i < 256; ++i) samples.push_back(T * i / 256);
    run::PeriodicOptions once = opt;
    once.max_cycles = 2;
    const run::PeriodicResult again =
        run::find_periodic(d, 0.0, T, r.q, r.v, tight_ida(), once, samples, &fourier);
    ASSERT_TRUE(again.converged);
    const double a1 = 2.0 / fourier.n * std::hypot(fourier.c, fourier.s);
    EXPECT_NEAR(a1, a[b], 0.04 * a[b]) << "branch " << b;
    const double mu = std::abs(r.multipliers.front().mu);
    if (b == 1) {
      EXPECT_GT(mu, 1.0) << "the middle branch is unstable";
      ++unstable;
    } else {
      EXPECT_LT(mu, 1.0) << "branch " << b << " is stable";
      ++stable;
    }
  }
  EXPECT_EQ(stable, 2);
  EXPECT_EQ(unstable, 1);
}

TEST(Periodic, RefusesBadOptionsAndProblems) {
  const double W = 2 * kPi * 2.0, T = 2 * kPi / W;
  test::SdofProblem p(forced_modes(W));
  run::PeriodicOptions opt;
  EXPECT_THROW(run::find_periodic(p, 0.0, -1.0, Vec::Zero(3), Vec::Zero(3), tight_ida(), opt),
               InputError);
  opt.tol = 0.0;
  EXPECT_THROW(run::find_periodic(p, 0.0, T, Vec::Zero(3), Vec::Zero(3), tight_ida(), opt),
               InputError);
  EXPECT_THROW(run::periodic_method("shooting"), InputError);
  EXPECT_EQ(run::periodic_method("anderson"), run::PeriodicMethod::anderson);
  // the projected method linearizes qdd = -f: no mass matrix
  test::MassSdof m(forced_modes(W));
  run::PeriodicOptions proj;
  EXPECT_THROW(run::find_periodic(m, 0.0, T, Vec::Zero(3), Vec::Zero(3), tight_ida(), proj),
               InputError);
}

}  // namespace
}  // namespace evas
