// Every integrator and every iteration runs the paper's engine
// (validation/engine/engine.yaml, Case 1: two FE bodies, five journal bearings,
// four pistons, dynamometer, soft mounts) and agrees with IDA at a tight
// tolerance; the two fixed-step methods show their order 2 on it.
//
// Error: the largest deviation of the ten main-bearing load channels
// (main*.fx, main*.fy) over the output grid (1 deg of crank angle) relative to
// each channel's amplitude (largest |y - mean y| of the reference). Reference:
// IDA at rtol 1e-8 for the runs, 1e-10 for the orders. Bounds are about 3x the
// values measured when the test was written (in the comments), so a regression
// of the method shows while round-off and platform noise do not.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "integrators/integrator.h"
#include "integrators/settings.h"
#include "io/outputs.h"
#include "io/scene.h"
#include "solver/system.h"

using namespace evas;

namespace {

const std::string kScene = std::string(EVAS_SOURCE_DIR) + "/validation/engine/engine.yaml";

struct Channels {
  std::vector<std::vector<double>> y;  // per output, the main-bearing loads
  IntegratorStats stats;
};

Channels run(const std::string& spec, double t_end) {
  Scene scene = read_scene(kScene);
  scene.t_end = t_end;
  IntegratorSettings s = scene.integrator;
  std::string word;
  std::istringstream is(spec);
  is >> word;
  set_integrator_setting(s, "name", word);
  while (is >> word) apply_setting_assignment(s, word);
  System sys(*scene.model);
  OutputSet out(scene.output, sys, scene.t_start, scene.t_end);
  std::vector<int> cols;
  for (int c = 0; c < out.size(); ++c) {
    const std::string& n = out.channels()[static_cast<std::size_t>(c)].name;
    const auto dot = n.rfind('.');  // main<k>.fx and .fy exactly (not .fx_journal)
    if (n.rfind("main", 0) == 0 && dot != std::string::npos &&
        (n.substr(dot) == ".fx" || n.substr(dot) == ".fy"))
      cols.push_back(c);
  }
  EXPECT_EQ(cols.size(), 10u);
  auto integ = make_integrator(s.name);
  Vec q, v;
  sys.initial_state(q, v);
  integ->init(sys, scene.t_start, q, v, s);
  std::vector<double> times = out.times(), row(out.size());
  if (times.front() <= scene.t_start) times.erase(times.begin());
  Channels r;
  integrate(*integ, sys, scene.t_start, times, [&](double t, const Vec& qq, const Vec& vv) {
    out.values(t, qq.data(), vv.data(), row.data());
    std::vector<double> y;
    for (int c : cols) y.push_back(row[static_cast<std::size_t>(c)]);
    r.y.push_back(y);
  });
  r.stats = integ->stats();
  return r;
}

double error(const Channels& r, const Channels& ref) {
  EXPECT_EQ(r.y.size(), ref.y.size());
  double e = 0.0;
  for (std::size_t c = 0; c < ref.y.front().size(); ++c) {
    double mean = 0.0, amp = 0.0;
    for (const auto& row : ref.y) mean += row[c] / static_cast<double>(ref.y.size());
    for (const auto& row : ref.y) amp = std::max(amp, std::abs(row[c] - mean));
    for (std::size_t k = 0; k < std::min(r.y.size(), ref.y.size()); ++k)
      e = std::max(e, std::abs(r.y[k][c] - ref.y[k][c]) / amp);
  }
  return e;
}

const double kRevolution = 2 * M_PI / 314.159;

}  // namespace

TEST(EngineIntegrators, EveryMethodRunsOneRevolutionAndAgreesWithIda) {
  const Channels ref = run("ida rtol=1e-8 atol=1e-12", kRevolution);
  struct Case {
    std::string spec;
    double bound;
  };
  const std::vector<Case> cases = {
      // measured: 9.5e-5, 4.9e-4
      {"ida rtol=1e-5", 1.5e-3},
      {"cvode rtol=1e-5", 1.5e-3},
      // measured: 1.2e-2, 1.2e-2, 1.1e-2
      {"generalized-alpha step=1e-5", 4e-2},
      {"generalized-alpha step=1e-5 iteration=newton", 4e-2},
      {"generalized-alpha step=1e-5 step_control=adaptive rtol=1e-4", 4e-2},
      // the paper's fixed point contracts only for h below ~ 5e-7 on this engine
      // (the films' damping), and some steps near firing need sub-steps;
      // then anderson / effective-mass / newton at 1e-5
      {"linear-acceleration step=5e-7", 2e-3},
      {"linear-acceleration step=1e-5 iteration=anderson", 5e-3},
      {"linear-acceleration step=1e-5 iteration=effective-mass", 5e-3},
      {"linear-acceleration step=1e-5 iteration=newton", 5e-3},
      {"linear-acceleration step=1e-5 iteration=effective-mass step_control=adaptive rtol=1e-4",
       3e-2},
      // Radau IIA (order 5); measured: 4.7e-3 at twice generalized-alpha's step
      // (14 sub-steps in the start), 3.4e-4 adaptive (1,107 steps)
      {"radau step=2e-5 rtol=1e-4 atol=1e-8", 1.5e-2},
      {"radau step=1e-5 step_control=adaptive rtol=1e-4 atol=1e-8", 1e-3},
  };
  for (const Case& c : cases) {
    const Channels r = run(c.spec, kRevolution);
    const double e = error(r, ref);
    const IntegratorStats& st = r.stats;
    std::cout << c.spec << ": error " << e << ", " << st.steps << " steps, " << st.residual_evals
              << " residuals, " << st.jacobian_evals << " Jacobians, " << st.nonlinear_iterations
              << " iterations, " << st.substeps << " substeps, " << st.error_test_failures
              << " rejected, " << st.wall_seconds << " s\n";
    EXPECT_LT(e, c.bound) << c.spec;
    if (c.spec == "generalized-alpha step=1e-5") {
      // the extrapolating predictor and the rate test of the increment
      // iteration (integrators/newmark.h): measured 2.2 residuals per step
      // (4.9 with the constant predictor and the last-update test alone)
      EXPECT_LT(static_cast<double>(st.residual_evals) / static_cast<double>(st.steps), 2.8);
    }
  }
}

TEST(EngineIntegrators, FixedStepMethodsAreSecondOrderOnTheEngine) {
  // A quarter revolution through cylinder 1's firing (peak near 10 deg after TDC),
  // tight iterations so that the truncation error shows.
  const double t_end = 0.25 * kRevolution;
  const Channels ref = run("ida rtol=1e-10 atol=1e-14", t_end);
  for (const char* spec :
       {"generalized-alpha iteration=newton rtol=1e-12 atol=1e-12 step_control=fixed",
        "linear-acceleration iteration=newton balance_tol=1e-10 step_control=fixed"}) {
    double e[3];
    for (int k = 0; k < 3; ++k) {
      const double h = 8e-6 / (1 << k);
      e[k] = error(run(std::string(spec) + " step=" + std::to_string(h), t_end), ref);
    }
    const double p1 = std::log2(e[0] / e[1]), p2 = std::log2(e[1] / e[2]);
    std::cout << spec << ": errors " << e[0] << ", " << e[1] << ", " << e[2]
              << " at h = 8, 4, 2 us; "
              << "orders " << p1 << ", " << p2 << "\n";
    EXPECT_NEAR(p2, 2.0, 0.25) << spec;
  }
}
