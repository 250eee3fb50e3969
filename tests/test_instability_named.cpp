// A conditionally stable method's step above its limit is named (run/
// stability_note.h): warned of before the run, and the failure says why.
// scenes/demo.yaml linearized at its start: highest frequency 1084 Hz (the
// frame's mode 13 stiffened by the elements), so linear acceleration (stable
// for h omega <= 2 sqrt 3, Hughes, The Finite Element Method, section 9.1.2)
// has its limit at h = 2 sqrt 3 / (2 pi 1084 Hz) = 5.09e-4 s and the central
// difference (h omega <= 2) at 2.94e-4 s.
#include <gtest/gtest.h>

#include <cmath>

#include "integrators/integrator.h"
#include "io/scene.h"
#include "run/stability_note.h"
#include "run_faults_support.h"
#include "solver/system.h"

using namespace evas;
using namespace run_faults;

namespace {

fs::path demo() { return fs::path(EVAS_SOURCE_DIR) / "scenes" / "demo.yaml"; }

// The frequency and the limit steps, from the scene itself: the warning
// appears just above the limit and not just below it.
TEST(InstabilityNamed, WarnedAboveTheLimitOnly) {
  Scene scene = read_scene(demo().string());
  System sys(*scene.model);
  Vec q, v;
  sys.initial_state(q, v);
  const HighestFrequency hf = highest_frequency(sys, scene.t_start, q, v);
  ASSERT_GT(hf.omega, 0.0);
  EXPECT_NEAR(hf.omega / (2 * M_PI), 1084.0, 1.0);
  for (const auto& [name, limit] :
       {std::pair<std::string, double>{"linear-acceleration", std::sqrt(12.0)},
        {"central-difference", 2.0}}) {
    SCOPED_TRACE(name);
    IntegratorSettings s;
    s.name = name;
    s.step_control = StepControl::fixed;
    s.step = 0.99 * limit / hf.omega;
    EXPECT_EQ(stability_limit_warning(*scene.model, s, scene.t_start), "");
    s.step = 1.01 * limit / hf.omega;
    const std::string w = stability_limit_warning(*scene.model, s, scene.t_start);
    EXPECT_NE(w.find("h omega = "), std::string::npos) << w;
    EXPECT_NE(w.find("body 'frame', mode 13"), std::string::npos) << w;
  }
  // unconditionally stable methods and adaptive steps are not judged
  IntegratorSettings ga;
  ga.name = "generalized-alpha";
  ga.step = 1e-2;
  EXPECT_EQ(stability_limit_warning(*scene.model, ga, scene.t_start), "");
  IntegratorSettings la;
  la.name = "linear-acceleration";
  la.step = 1e-2;
  la.step_control = StepControl::adaptive;
  EXPECT_EQ(stability_limit_warning(*scene.model, la, scene.t_start), "");
}

// The run: the warning before it, and its failure naming the instability
// beside the iteration's own message.
TEST(InstabilityNamed, TheFailureSaysWhy) {
  TempFolder tmp;
  const Outcome o =
      run_evas({"run", demo().string(), "--integrator", "linear-acceleration", "--set", "step=1e-3",
                "--set", "step_control=fixed", "--out", (tmp.path() / "la").string()},
               tmp.path() / "la.log");
  EXPECT_NE(o.code, 0);
  EXPECT_NE(o.log.find("warning: linear-acceleration is stable for h omega <= 3.464"),
            std::string::npos)
      << o.log;
  EXPECT_NE(o.log.find("Instability: linear-acceleration is stable for h omega <= 3.464"),
            std::string::npos)
      << o.log;
  EXPECT_NE(o.log.find("h omega = 6.81"), std::string::npos) << o.log;
}

}  // namespace
