// Every integrator against the closed-form solution of damped, partly forced,
// uncoupled oscillators (tests/sdof_problem.h: damped harmonic oscillator, free
// plus steady-state harmonic response).
//   fixed-step methods: observed order log2(e(h)/e(h/2)) in [1.8, 2.2]
//   ida / cvode: the error falls with rtol and stays below a bound ~ rtol
//   linear-acceleration: RunError naming the balance error when h is far too big
//   all: landing on stops (with a state change) inside integrate()
#include <gtest/gtest.h>

#include <cmath>
#include <iomanip>
#include <iostream>
#include <string>
#include <vector>

#include "integrators/integrator.h"
#include "integrators/newmark.h"
#include "sdof_problem.h"
#include "sdof_run.h"

namespace evas {
namespace {

using test::Oscillator;
using test::SdofProblem;
using test::Stop;

constexpr double kPi = 3.14159265358979323846;

using test::oscillators;

using test::Errors;
using test::run_sdof;

void print_stats(const std::string& label, const IntegratorStats& s) {
  std::cout << "  stats " << label << ": steps " << s.steps << ", residual evals "
            << s.residual_evals << ", jacobian evals " << s.jacobian_evals << ", linear setups "
            << s.linear_setups << ", linear solves " << s.linear_solves << ", nonlinear iters "
            << s.nonlinear_iterations << ", err test fails " << s.error_test_failures
            << ", conv fails " << s.convergence_failures << ", restarts " << s.restarts
            << ", last step " << s.last_step << ", min/max step " << s.min_step << "/" << s.max_step
            << ", last order " << s.last_order << ", wall " << s.wall_seconds << " s\n";
}

// ---------------------------------------------------------------- fixed step

struct FixedCase {
  std::string label;
  std::string name;
  double rho_inf;
  bool body_part;
};

void PrintTo(const FixedCase& c, std::ostream* os) { *os << c.label; }

class SdofFixedStepOrder : public ::testing::TestWithParam<FixedCase> {};

TEST_P(SdofFixedStepOrder, SecondOrderAtOneSecond) {
  const FixedCase& c = GetParam();
  IntegratorSettings s;
  s.name = c.name;
  s.rho_inf = c.rho_inf;
  s.rtol = 1e-12;  // Newton tolerance (generalized-alpha): far below the truncation error
  s.atol = 1e-14;
  s.balance_tol = 1e-12;  // linear-acceleration: likewise
  // rho_inf = 0 is still pre-asymptotic at h = 0.01 (orders 1.57, 1.66 there, -> 2 as h -> 0)
  const double h0 = 0.002;
  double e[3], ev[3];
  IntegratorStats st;
  for (int k = 0; k < 3; ++k) {
    s.step = h0 / std::pow(2.0, k);
    SdofProblem p(oscillators(), c.body_part);
    const Errors err = run_sdof(s, p, {1.0}, &st);
    e[k] = err.q;
    ev[k] = err.v;
  }
  const double order1 = std::log2(e[0] / e[1]), order2 = std::log2(e[1] / e[2]);
  const double vorder2 = std::log2(ev[1] / ev[2]);
  std::cout << std::setprecision(4) << c.label
            << ": |q err|(t=1) for h = 0.002, 0.001, 0.0005: " << e[0] << ", " << e[1] << ", "
            << e[2] << "; orders " << order1 << ", " << order2 << "; |v err| " << ev[0] << ", "
            << ev[1] << ", " << ev[2] << " (order " << vorder2 << ")\n";
  print_stats(c.label + " h=0.0005", st);
  RecordProperty("order_q", std::to_string(order2));
  EXPECT_GE(order1, 1.8);
  EXPECT_LE(order1, 2.2);
  EXPECT_GE(order2, 1.8);
  EXPECT_LE(order2, 2.2);
  EXPECT_GE(vorder2, 1.8);
  EXPECT_LE(vorder2, 2.2);
}

INSTANTIATE_TEST_SUITE_P(
    All, SdofFixedStepOrder,
    ::testing::Values(FixedCase{"generalized-alpha rho=0.0", "generalized-alpha", 0.0, true},
                      FixedCase{"generalized-alpha rho=0.5", "generalized-alpha", 0.5, true},
                      FixedCase{"generalized-alpha rho=1.0", "generalized-alpha", 1.0, true},
                      FixedCase{"linear-acceleration body", "linear-acceleration", 0.0, true},
                      FixedCase{"linear-acceleration fixed-point", "linear-acceleration", 0.0,
                                false},
                      // the rho_inf-Bathe composite method (Noh & Bathe 2019): second order
                      FixedCase{"bathe rho=0.0", "bathe", 0.0, true},
                      FixedCase{"bathe rho=0.6", "bathe", 0.6, true},
                      FixedCase{"bathe rho=1.0", "bathe", 1.0, true}),
    [](const ::testing::TestParamInfo<FixedCase>& info) {
      std::string n = info.param.label;
      for (char& ch : n)
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
      return n;
    });

TEST(SdofLinearAcceleration, DefaultBalanceTolerance) {
  // The paper's 0.1 % balance on the fixed-point path: report the error it gives.
  IntegratorSettings s;
  s.name = "linear-acceleration";
  s.step = 0.0025;
  IntegratorStats st;
  SdofProblem p(oscillators(), false);
  const Errors e = run_sdof(s, p, {1.0}, &st);
  std::cout << "linear-acceleration fixed-point, balance_tol 1e-3, h = 0.0025: |q err|(t=1) = "
            << e.q << "\n";
  print_stats("linear-acceleration balance 1e-3", st);
  EXPECT_LT(e.q, 1e-4);  // measured 2.3e-5 (6.7e-6 with a tight balance)
}

TEST(SdofLinearAcceleration, ThrowsWhenFixedPointCannotBalance) {
  Oscillator o;
  o.omega = 2 * kPi * 3.0;  // h w = 3.8: the fixed-point map a -> -f(q(a), v(a)) expands
  o.zeta = 0.02;
  o.q0 = 1.0;
  SdofProblem p({o}, false);
  IntegratorSettings s;
  s.name = "linear-acceleration";
  s.step = 0.2;
  s.step_control = StepControl::fixed;  // no sub-steps: the failed step ends the run
  try {
    run_sdof(s, p, {1.0});
    FAIL() << "expected RunError";
  } catch (const RunError& e) {
    const std::string msg = e.what();
    std::cout << "message: " << msg << "\n";
    EXPECT_NE(msg.find("balance"), std::string::npos);
    EXPECT_NE(msg.find("per iteration"), std::string::npos);   // the contraction rate
    EXPECT_NE(msg.find("would converge"), std::string::npos);  // and the step that would
    EXPECT_NE(msg.find("t = 0.2"), std::string::npos);
    EXPECT_NE(msg.find("sdof problem"), std::string::npos);
  }
}

// ---------------------------------------------------------------- adaptive

struct AdaptiveCase {
  std::string label;
  std::string name, linear_solver, method;
  int jacobian_age = 0;
};

void PrintTo(const AdaptiveCase& c, std::ostream* os) { *os << c.label; }

class SdofAdaptiveAccuracy : public ::testing::TestWithParam<AdaptiveCase> {};

TEST_P(SdofAdaptiveAccuracy, ErrorFollowsTolerance) {
  const AdaptiveCase& c = GetParam();
  const std::vector<double> outputs = test::tenth_outputs();
  const double rtols[3] = {1e-4, 1e-6, 1e-8};
  double e[3];
  for (int k = 0; k < 3; ++k) {
    IntegratorSettings s;
    s.name = c.name;
    s.linear_solver = c.linear_solver;
    s.method = c.method;
    s.jacobian_age = c.jacobian_age;
    s.rtol = rtols[k];
    s.atol = 1e-2 * rtols[k];
    SdofProblem p(oscillators());
    IntegratorStats st;
    e[k] = run_sdof(s, p, outputs, &st).q;
    std::cout << std::setprecision(4) << c.label << " rtol " << rtols[k]
              << ": max |q err| over t = 0.1..1 = " << e[k] << " (" << e[k] / rtols[k]
              << " rtol)\n";
    print_stats(c.label, st);
    EXPECT_GT(st.steps, 0);
    EXPECT_GT(st.residual_evals, 0);
  }
  EXPECT_LT(e[1], e[0]);
  EXPECT_LT(e[2], e[1]);
  // measured: 0.2 .. 0.8 rtol for every case; 5 rtol leaves room for platform noise
  for (int k = 0; k < 3; ++k) EXPECT_LT(e[k], 5 * rtols[k]) << "rtol " << rtols[k];
}

INSTANTIATE_TEST_SUITE_P(
    All, SdofAdaptiveAccuracy,
    ::testing::Values(AdaptiveCase{"ida klu", "ida", "klu", "bdf"},
                      AdaptiveCase{"ida dense", "ida", "dense", "bdf"},
                      AdaptiveCase{"cvode bdf klu", "cvode", "klu", "bdf"},
                      AdaptiveCase{"cvode bdf dense", "cvode", "dense", "bdf"},
                      AdaptiveCase{"cvode adams", "cvode", "klu", "adams"},
                      AdaptiveCase{"ida second-order", "ida", "second-order", "bdf"},
                      AdaptiveCase{"ida second-order reuse", "ida", "second-order", "bdf", 20},
                      AdaptiveCase{"cvode bdf second-order", "cvode", "second-order", "bdf"}),
    [](const ::testing::TestParamInfo<AdaptiveCase>& info) {
      std::string n = info.param.label;
      for (char& ch : n)
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
      return n;
    });

// ---------------------------------------------------------------- stops

struct StopCase {
  std::string label;
  IntegratorSettings s;
  double bound;  // on the q error over all outputs
};

IntegratorSettings settings(const std::string& name, const std::string& ls = "klu",
                            const std::string& method = "bdf", double rho = 0.8) {
  IntegratorSettings s;
  s.name = name;
  s.linear_solver = ls;
  s.method = method;
  s.rho_inf = rho;
  s.rtol = 1e-8;
  s.atol = 1e-10;
  s.step = 7e-4;  // outputs and stops fall between steps
  s.balance_tol = 1e-10;
  return s;
}

void PrintTo(const StopCase& c, std::ostream* os) { *os << c.label; }

class SdofStops : public ::testing::TestWithParam<StopCase> {};

TEST_P(SdofStops, LandsExactlyAndRestarts) {
  const StopCase& c = GetParam();
  // a kicked stop between outputs, a kicked stop on an output, a quiet stop
  const std::vector<Stop> stops = test::kicked_stops();
  SdofProblem p(oscillators(), true, stops);
  const std::vector<double> outputs = test::tenth_outputs();
  IntegratorStats st;
  const Errors e = run_sdof(c.s, p, outputs, &st);
  std::cout << c.label << ": max |q err| with stops = " << e.q << ", |v err| = " << e.v << "\n";
  print_stats(c.label, st);
  ASSERT_EQ(p.landed.size(), 3u);
  EXPECT_EQ(p.landed[0], 0.3137);  // exactly, not approximately
  EXPECT_EQ(p.landed[1], 0.5);
  EXPECT_EQ(p.landed[2], 0.6502);
  EXPECT_EQ(st.restarts, 2);
  EXPECT_LT(e.q, c.bound);
}

INSTANTIATE_TEST_SUITE_P(
    All, SdofStops,
    ::testing::Values(StopCase{"ida klu", settings("ida"), 1e-6},
                      StopCase{"ida dense", settings("ida", "dense"), 1e-6},
                      StopCase{"cvode bdf klu", settings("cvode"), 1e-6},
                      StopCase{"cvode bdf dense", settings("cvode", "dense"), 1e-6},
                      StopCase{"ida second-order", settings("ida", "second-order"), 1e-6},
                      StopCase{"cvode bdf second-order", settings("cvode", "second-order"), 1e-6},
                      StopCase{"cvode adams", settings("cvode", "klu", "adams"), 1e-6},
                      StopCase{"generalized-alpha rho=0.0",
                               settings("generalized-alpha", "klu", "bdf", 0.0), 1e-3},
                      StopCase{"generalized-alpha rho=1.0",
                               settings("generalized-alpha", "klu", "bdf", 1.0), 1e-3},
                      StopCase{"linear-acceleration", settings("linear-acceleration"), 1e-3},
                      StopCase{"bathe rho=0.0", settings("bathe", "klu", "bdf", 0.0), 1e-3}),
    [](const ::testing::TestParamInfo<StopCase>& info) {
      std::string n = info.param.label;
      for (char& ch : n)
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
      return n;
    });

// ---------------------------------------------------------------- failures

// A model that fails at t > 0.3 s (as an element would, with its own message).
class FailingProblem : public SdofProblem {
 public:
  FailingProblem() : SdofProblem(oscillators()) {}
  void force(double t, const double* q, const double* v, double* f) override {
    if (t > 0.3) throw RunError("element 'bearing 3' left its table");
    SdofProblem::force(t, q, v, f);
  }
};

std::string failure_message(const IntegratorSettings& s, Problem& p) {
  auto integ = make_integrator(s.name);
  Vec q0, v0;
  p.initial_state(q0, v0);
  integ->init(p, 0.0, q0, v0, s);
  try {
    integrate(*integ, p, 0.0, {0.5, 1.0}, [](double, const Vec&, const Vec&) {});
  } catch (const RunError& e) {
    std::cout << "message: " << e.what() << "\n";
    return e.what();
  }
  return "";
}

TEST(SdofFailures, SundialsFailuresNameIntegratorFlagTimeAndState) {
  for (const std::string& name : {std::string("ida"), std::string("cvode")}) {
    IntegratorSettings s;
    s.name = name;
    FailingProblem p;
    const std::string msg = failure_message(s, p);
    ASSERT_FALSE(msg.empty()) << name;
    EXPECT_EQ(msg.rfind(name, 0), 0u) << msg;
    EXPECT_NE(msg.find(name == "ida" ? "IDA_RES_FAIL" : "CV_RHSFUNC_FAIL"), std::string::npos)
        << msg;
    EXPECT_NE(msg.find("at t = 0.29"), std::string::npos) << msg;  // last accepted step
    EXPECT_NE(msg.find("bearing 3"), std::string::npos) << msg;
    EXPECT_NE(msg.find("sdof problem at t"), std::string::npos) << msg;

    s.max_steps = 5;  // far too few for an output interval of 0.5 s
    SdofProblem p2(oscillators());
    const std::string msg2 = failure_message(s, p2);
    EXPECT_NE(msg2.find("max_steps"), std::string::npos) << msg2;
    EXPECT_NE(msg2.find("sdof problem at t"), std::string::npos) << msg2;
  }
}

TEST(SdofFailures, GeneralizedAlphaNewtonLimit) {
  IntegratorSettings s;
  s.name = "generalized-alpha";
  s.step = 1e-3;
  s.max_iterations = 1;                 // the first Newton update is never below the tolerance
  s.step_control = StepControl::fixed;  // no sub-steps: the failed step ends the run
  SdofProblem p(oscillators());
  const std::string msg = failure_message(s, p);
  EXPECT_NE(msg.find("did not converge"), std::string::npos) << msg;
  EXPECT_NE(msg.find("after 1 iterations"), std::string::npos) << msg;
  EXPECT_NE(msg.find("t = 0.001 s, step h = 0.001 s"), std::string::npos) << msg;
}

// ---------------------------------------------------------------- registry

// The Newmark predictor extrapolates the acceleration from the last two steps;
// when an element refuses the predicted state, the step starts again from the
// constant-acceleration predictor instead of failing (integrators/newmark.h).
TEST(SdofNewmark, RefusedPredictorFallsBackToConstantAcceleration) {
  for (const char* name : {"generalized-alpha", "linear-acceleration"}) {
    IntegratorSettings s;
    s.name = name;
    s.step = 0.01;
    s.step_control = StepControl::fixed;  // a failed step would end the run
    s.iteration = Iteration::effective_mass;
    IntegratorStats plain, refused;
    SdofProblem p(oscillators());
    const Errors e0 = run_sdof(s, p, {0.25, 0.5, 0.75, 1.0}, &plain);
    test::RefusingSdof r(oscillators(), 0.505);
    const Errors e1 = run_sdof(s, r, {0.25, 0.5, 0.75, 1.0}, &refused);
    EXPECT_TRUE(r.refused) << name;
    EXPECT_EQ(refused.steps, plain.steps) << name;
    EXPECT_EQ(refused.convergence_failures, 0) << name;
    EXPECT_EQ(refused.substeps, 0) << name;
    // the same step solved from another starting point: equal to the iteration tolerance
    EXPECT_NEAR(e1.q, e0.q, 1e-6) << name;
  }
}

// An adaptive step grows again after it shrinks, also after a refused state
// cut it by 4 three times: a step whose end was only rounded (t_end - t_ a bit
// below the planned step) is not "cut for an output", which kept the planned
// step from growing.
TEST(SdofNewmark, AdaptiveStepGrowsBackAfterACut) {
  for (const char* name : {"generalized-alpha", "linear-acceleration"}) {
    IntegratorSettings s;
    s.name = name;
    s.step = 1e-3;
    s.step_control = StepControl::adaptive;
    s.iteration = Iteration::effective_mass;
    s.rtol = 1e-5;
    s.atol = 1e-7;
    std::vector<double> outputs;
    for (int k = 1; k <= 1000; ++k) outputs.push_back(k * 1e-3 * 0.9137);
    IntegratorStats one, plain, refused;
    SdofProblem p0(oscillators());
    run_sdof(s, p0, {outputs.back()}, &one);
    SdofProblem p(oscillators());
    run_sdof(s, p, outputs, &plain);
    test::RefusingSdof r(oscillators(), 0.3, 6);  // three failed steps: h / 64
    run_sdof(s, r, outputs, &refused);
    EXPECT_GE(refused.refused_states, 2) << name;
    EXPECT_TRUE(r.refused) << name;
    std::cout << name << ": " << one.steps << " steps with one output, " << plain.steps
              << " with 1000, " << refused.steps << " with 1000 and a refused state; "
              << one.error_test_failures << " rejected steps with one output\n";
    // measured with the PI controller 329 / 329 / 342 (generalized-alpha),
    // 271 / 271 / 283 (linear acceleration), 0 and 1 rejected; with the I
    // controller 258 / 258 / 262 and 213 / 213 / 218, 11 and 15 rejected; with the round-off taken
    // for a cut 476 / 476 / 5090 and 475 / 475 / 447: the step stopped growing after the first
    // change
    EXPECT_LT(one.steps, 400) << name;
    EXPECT_LE(one.error_test_failures, one.steps / 50) << name;
    EXPECT_LT(plain.steps, one.steps + 20) << name;
    EXPECT_LT(refused.steps, one.steps + 20) << name;
  }
}

// The coefficient c_v of the local velocity error c_v h^3 q'''' that the
// adaptive step control of the Newmark family uses (integrators/newmark.h),
// against the error the methods make: on q'' = F cos(W t) (f independent of
// q), the velocity increment of a step after the start-up transient has
// died out, minus the exact one, divided by h^3 q''''(t_n) = -h^3 F W^2 cos(W t_n).
// Parameters from rho_inf as Chung & Hulbert, J. Appl. Mech. 60 (1993) 371.
TEST(SdofNewmark, VelocityErrorCoefficientMatchesTheMethod) {
  Oscillator o;
  o.omega = 0.0;
  o.force = 2.0;
  o.force_freq = 3.0;
  const double h = 1e-3, F = o.force, W = o.force_freq;
  for (double rho : {0.8, 0.5, 1.0, -1.0}) {  // -1: linear acceleration
    IntegratorSettings s;
    s.name = rho < 0 ? "linear-acceleration" : "generalized-alpha";
    s.step = h;
    s.step_control = StepControl::fixed;
    s.iteration = Iteration::effective_mass;
    s.rtol = 1e-14;
    s.atol = 1e-14;
    s.balance_tol = 1e-14;
    NewmarkIntegrator::Parameters par;
    if (rho >= 0) {
      s.rho_inf = rho;
      par.alpha_m = (2 * rho - 1) / (rho + 1);
      par.alpha_f = rho / (rho + 1);
      par.gamma = 0.5 - par.alpha_m + par.alpha_f;
      par.beta = 0.25 * (1 - par.alpha_m + par.alpha_f) * (1 - par.alpha_m + par.alpha_f);
    }
    const double cv = NewmarkIntegrator::velocity_error_coefficient(par);
    SdofProblem p({o});
    auto integ = make_integrator(s.name);
    Vec q0, v0;
    p.initial_state(q0, v0);
    integ->init(p, 0.0, q0, v0, s);
    std::vector<double> outputs, vs;
    for (int k = 1; k <= 1000; ++k) outputs.push_back(k * h);
    integrate(*integ, p, 0.0, outputs,
              [&](double, const Vec&, const Vec& v) { vs.push_back(v[0]); });
    ASSERT_EQ(vs.size(), outputs.size());
    double worst = 0.0;
    int checked = 0;
    for (int k = 300; k < 999; ++k) {
      const double t0 = outputs[k], t1 = outputs[k + 1];
      const double q4 = -F * W * W * std::cos(W * t0);
      if (std::abs(std::cos(W * t0)) < 0.3) continue;
      const double dv = (vs[k + 1] - vs[k]) - F / W * (std::sin(W * t1) - std::sin(W * t0));
      worst = std::max(worst, std::abs(dv / (h * h * h * q4) / cv - 1.0));
      ++checked;
    }
    std::cout << s.name << " rho_inf " << rho << ": c_v " << cv << ", largest relative deviation "
              << worst << " over " << checked << " steps\n";
    EXPECT_GT(checked, 300);
    EXPECT_LT(worst, 0.02) << s.name << " rho_inf " << rho;
  }
}

TEST(SdofRegistry, NamesAndUnknown) {
  const auto names = integrator_names();
  ASSERT_EQ(names.size(), 10u);
  for (const auto& n : names) EXPECT_EQ(make_integrator(n)->name(), n);
  EXPECT_THROW(make_integrator("rk4"), InputError);
}

}  // namespace
}  // namespace evas
