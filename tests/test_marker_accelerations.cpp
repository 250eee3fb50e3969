// Marker acceleration and angular velocity/acceleration channels (io/outputs.h,
// System::observe_accelerations): the full acceleration of a marker on the
// demo's spinning flexible shaft (LOF terms plus the modal accelerations
// qdd = -f) against central differences of its velocity channel over a fine
// output grid, the angular acceleration against differences of the angular
// velocity; the components in the marker's own axes against a hand rotation
// by the LOF's spin angle; and the input errors.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "demo_output.h"
#include "integrators/integrator.h"
#include "integrators/settings.h"
#include "io/scene.h"
#include "run/run.h"
#include "run/sink.h"

using namespace evas;

namespace {

using test_scenes::kDemo;

std::string demo_with_output(const std::string& output) {
  return test_scenes::demo_with_output(output, "0.002");
}

int column(const run::MemorySink& s, const std::string& name) {
  for (std::size_t i = 0; i < s.channels().size(); ++i)
    if (s.channels()[i].name == name) return static_cast<int>(i);
  ADD_FAILURE() << "no channel " << name;
  return 0;
}

}  // namespace

TEST(MarkerAccelerations, MatchDifferencesOfTheVelocities) {
  const Scene scene = parse_scene(
      demo_with_output("output:\n  grid: time\n  step: 2e-6\n  channels:\n"
                       "    - {marker: shaft_left, quantities: [velocity, acceleration, "
                       "angular_velocity, angular_acceleration]}\n"
                       "    - {marker: shaft_left, quantities: [velocity, acceleration, "
                       "angular_velocity], frame: marker}\n"),
      kDemo);
  ASSERT_TRUE(scene.warnings.empty());
  run::MemorySink sink;
  const run::Outcome o = test_scenes::run_tight(scene, sink);
  ASSERT_TRUE(o.completed()) << o.message;
  const long w = sink.width();
  const auto& val = sink.values();
  const auto& t = sink.times();
  ASSERT_GT(t.size(), 900u);
  const char* axes[] = {"x", "y", "z"};
  // a = dv/dt, al = dw/dt: central differences, error ~ (h omega)^2 / 6 = 1.6e-4
  // of the 2.5-kHz top mode's share
  for (const auto& [deriv, of] : {std::pair<std::string, std::string>{"a", "v"}, {"al", "w"}}) {
    double worst = 0.0, scale = 0.0;
    for (int a = 0; a < 3; ++a) {
      const int cd = column(sink, "shaft_left." + deriv + axes[a]);
      const int cv = column(sink, "shaft_left." + of + axes[a]);
      for (std::size_t k = 1; k + 1 < t.size(); ++k) {
        const double fd = (val[(k + 1) * w + cv] - val[(k - 1) * w + cv]) / (t[k + 1] - t[k - 1]);
        worst = std::max(worst, std::abs(val[k * w + cd] - fd));
        scale = std::max(scale, std::abs(val[k * w + cd]));
      }
    }
    std::printf("  %s against d%s/dt: largest difference %.3e of max |%s| = %.4e\n", deriv.c_str(),
                of.c_str(), worst / scale, deriv.c_str(), scale);
    EXPECT_LT(worst, 2e-4 * scale) << deriv;
    EXPECT_GT(scale, 1.0) << deriv << ": the shaft end must accelerate";
  }
  // In the marker's axes: the shaft's LOF turns about x at 300 rad/s from angle 0
  // and the marker carries no rotation of its own, so its axes are Rx(300 t):
  // x components are equal, y, z turn by -300 t (hand rotation).
  for (const char* q : {"v", "a", "w"}) {
    const int gx = column(sink, std::string("shaft_left.") + q + "x");
    const int lx = column(sink, std::string("shaft_left.") + q + "x_local");
    for (std::size_t k = 0; k < t.size(); k += 97) {
      const double th = 300.0 * t[k], c = std::cos(th), s2 = std::sin(th);
      const double* g = &val[k * w + gx];
      const double* l = &val[k * w + lx];
      const double tol = 1e-12 * (std::abs(g[0]) + std::abs(g[1]) + std::abs(g[2]) + 1e-300);
      EXPECT_NEAR(l[0], g[0], tol) << q << " at t = " << t[k];
      EXPECT_NEAR(l[1], c * g[1] + s2 * g[2], tol) << q << " at t = " << t[k];
      EXPECT_NEAR(l[2], -s2 * g[1] + c * g[2], tol) << q << " at t = " << t[k];
    }
  }
  // the spin shows in the angular velocity: 300 rad/s about x, within the
  // elastic and rigid-mode rates
  EXPECT_NEAR(val[500 * w + column(sink, "shaft_left.wx")], 300.0, 1.0);
}

TEST(MarkerAccelerations, BadRequestsAreInputErrors) {
  auto refused = [](const std::string& channel, const std::string& says) {
    try {
      parse_scene(demo_with_output("output:\n  step: 1e-4\n  channels:\n    - " + channel + "\n"),
                  kDemo);
      ADD_FAILURE() << channel << " was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
    }
  };
  refused("{marker: shaft_left, quantities: [jerk]}", "unknown quantity 'jerk' (known: position");
  refused("{marker: shaft_left, quantities: [velocity, velocity]}", "given twice");
  refused("{marker: shaft_left, quantities: []}", "must be a list");
  refused("{marker: shaft_left, frame: body}", "frame");
  refused("{element: bearing_left, frame: marker}", "belong to a marker request");
}
