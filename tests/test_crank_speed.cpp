// The operating point's speed stated once: prescribed pistons and the motor
// without their own `speed` follow the crank's spin LOF (constant or a speed
// profile), a scene whose element speed disagrees with the crank's is refused
// naming both, and a run-up keeps every piston's crank angle on the integral
// of the crank's speed.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "elements/piston_conrod.h"
#include "io/results.h"
#include "io/scene.h"
#include "run/run.h"
#include "run/sink.h"

using namespace evas;
namespace fs = std::filesystem;

namespace {

// The validation engine (Case 1), END seconds (validation/engine/scenes.sh).
std::string engine_scene(double end) {
  static const fs::path dir = [] {
    const fs::path d = fs::temp_directory_path() / ("evas_crank_" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
  }();
  const fs::path d = dir / std::to_string(end);
  if (!fs::exists(d / "case1.yaml")) {
    const std::string cmd = std::string(EVAS_SOURCE_DIR) + "/validation/engine/scenes.sh " +
                            d.string() + " " + std::to_string(end);
    if (std::system(cmd.c_str()) != 0) throw std::runtime_error("scenes.sh failed");
  }
  std::ifstream f(d / "case1.yaml");
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

std::string replaced(const std::string& text, const std::string& re, const std::string& by) {
  return std::regex_replace(text, std::regex(re), by);
}

// Every element's `speed` removed (the pistons' and the motor's).
std::string following(const std::string& text) {
  return replaced(text, R"(\bspeed: [0-9.]+,\s*)", "");
}

// The engine as the paper's input gives it: every piston and the motor with
// its own speed w (engine.yaml states the speed once, on the crank).
std::string with_own_speeds(const std::string& text, const std::string& w = "314.159") {
  const std::string s =
      replaced(text, R"(firing_phase: ([0-9]+), )", "firing_phase: $1, speed: " + w + ", ");
  return replaced(s, R"(g_fw\], )", "g_fw], speed: " + w + ", ");
}

// The crank's speed w as well.
std::string with_speeds(const std::string& text, const std::string& w) {
  return replaced(with_own_speeds(text, w), R"(speed: 314\.159\})", "speed: " + w + "}");
}

struct Rows {
  std::vector<double> time;
  std::vector<std::string> names;
  std::vector<double> values;
  std::size_t width = 0;
  double at(std::size_t row, const std::string& name) const {
    for (std::size_t c = 0; c < names.size(); ++c)
      if (names[c] == name) return values[row * width + c];
    throw std::runtime_error("no channel " + name);
  }
};

Rows run(const std::string& text, const std::string& integrator) {
  Scene scene = parse_scene(text, "engine.yaml");
  scene.integrator.name = integrator;
  run::SceneRun sr(scene, scene.t_end);
  run::MemorySink sink;
  const run::Outcome o = sr.perform(scene.integrator, sink);
  EXPECT_TRUE(o.completed()) << o.message;
  Rows r;
  r.time = sink.times();
  for (const auto& c : sink.channels()) r.names.push_back(c.name);
  r.values = sink.values();
  r.width = sink.width();
  return r;
}

std::string error_of(const std::string& text) {
  try {
    parse_scene(text, "engine.yaml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// Within this build: following the crank and giving every element the same
// constant speed give the same bits. (Against earlier builds the same holds
// for the whole reference set: scripts/reference_runs.sh + compare_runs.sh.)
TEST(CrankSpeed, FollowingAConstantCrankIsBitwiseTheSame) {
  const std::string follow = engine_scene(0.01);
  const std::string own = with_own_speeds(follow);
  ASSERT_EQ(follow.find("speed: 314.159,"), std::string::npos);
  ASSERT_EQ(following(own), follow);
  const Rows a = run(own, "ida"), b = run(follow, "ida");
  ASSERT_EQ(a.values.size(), b.values.size());
  ASSERT_GT(a.time.size(), 5u);
  EXPECT_EQ(std::memcmp(a.values.data(), b.values.data(), a.values.size() * sizeof(double)), 0);
}

TEST(CrankSpeed, DisagreeingSpeedsAreRefusedNamingBoth) {
  const std::string own = with_own_speeds(engine_scene(0.01));
  const std::string cyl3_slow =
      replaced(own, R"(firing_phase: 180, speed: 314\.159)", "firing_phase: 180, speed: 300");
  const std::string e = error_of(cyl3_slow);
  EXPECT_NE(e.find("element 'cyl3'"), std::string::npos) << e;
  EXPECT_NE(e.find("300 rad/s disagrees with body 'crank'"), std::string::npos) << e;
  EXPECT_NE(e.find("314.159 rad/s"), std::string::npos) << e;
  // the motor too
  const std::string motor = replaced(own, R"(g_fw\], speed: 314\.159)", "g_fw], speed: 320");
  EXPECT_NE(error_of(motor).find("element 'dyno'"), std::string::npos) << error_of(motor);
  // all equal at another speed: accepted
  EXPECT_EQ(error_of(with_speeds(engine_scene(0.01), "418.879")), "");
}

TEST(CrankSpeed, ProfilesAreRefusedWhereTheyCannotBeFollowed) {
  const std::string ramp = replaced(engine_scene(0.01), R"(speed: 314\.159\})",
                                    "speed_profile: [[0, 104.72], [0.1, 418.88]]}");
  ASSERT_EQ(error_of(ramp), "");
  // a constant element speed against a crank profile
  const std::string own = replaced(ramp, R"(firing_phase: 540, )", "firing_phase: 540, speed: 1, ");
  EXPECT_NE(error_of(own).find("disagrees with body 'crank' (its spin LOF turns at a profile"),
            std::string::npos)
      << error_of(own);
  // the paper's constant-speed series cannot follow a ramp
  const std::string eq2 =
      replaced(ramp, R"(firing_phase: 0, )", "firing_phase: 0, side_force: eq2, ");
  EXPECT_NE(error_of(eq2).find("cannot follow a varying crank speed"), std::string::npos)
      << error_of(eq2);
  // a run-down to standstill has no crank-angle grid (the angle stops)
  const std::string stop = replaced(engine_scene(0.01), R"(speed: 314\.159\})",
                                    "speed_profile: [[0, 314.159], [0.005, 0]]}");
  EXPECT_NE(error_of(stop).find("the crank-angle grid needs a crank that keeps turning one way"),
            std::string::npos)
      << error_of(stop);
  // ... but a run-up from standstill has one, and a stop after the run's end
  // does not matter
  EXPECT_EQ(error_of(replaced(engine_scene(0.01), R"(speed: 314\.159\})",
                              "speed_profile: [[0, 0], [0.005, 314.159]]}")),
            "");
  EXPECT_EQ(error_of(replaced(engine_scene(0.01), R"(speed: 314\.159\})",
                              "speed_profile: [[0, 314.159], [0.1, 0]]}")),
            "");
  // nothing to follow: the crank held by a fixed frame
  const std::string fixed =
      replaced(engine_scene(0.01), R"(kind: spin, axis: \[1, 0, 0\], )", "kind: fixed, ");
  const std::string fixed_ok = replaced(fixed, R"(,\s*speed: 314\.159\})", "}");
  EXPECT_NE(error_of(fixed_ok).find("parameter 'speed' is required: no body has a spin LOF"),
            std::string::npos)
      << error_of(fixed_ok);
}

// With a second spinning body (here the block, slowly) the crank is still the
// body that carries each element's first marker: the pistons and the motor
// follow it, and their own speeds are still checked against it.
TEST(CrankSpeed, TheCrankIsTheBodyOfTheFirstMarker) {
  const std::string two =
      replaced(engine_scene(0.01), R"(lof: \{kind: fixed, origin: \[0, 0, 0\]\})",
               "lof: {kind: spin, axis: [1, 0, 0], origin: [0, 0, 0], speed: 0.5}");
  ASSERT_NE(two, engine_scene(0.01));
  EXPECT_EQ(error_of(two), "");
  const std::string own = replaced(with_own_speeds(two), R"(speed: 314\.159\})", "speed: 400}");
  EXPECT_NE(error_of(own).find("element 'cyl1': speed 314.159 rad/s disagrees with body 'crank'"),
            std::string::npos)
      << error_of(own);
}

// Prescribed mode under a ramp: the crank speed and acceleration the element
// uses are the profile's, and its piston acceleration is the second time
// derivative of its piston position (central differences), so the x' theta''
// term is there.
TEST(CrankSpeed, PrescribedPistonUsesTheCrankAcceleration) {
  PistonConrodParams p;
  p.crank_radius = 0.0575;
  p.conrod_length = 0.19;
  p.bore = 0.106;
  p.piston_mass = 1.6;
  p.rot_mass = 1.4;
  PistonConrod e("cyl", {0, 1, 2}, p, nullptr);
  e.leave_speed_to_crank();
  const SpeedProfile ramp({0.0, 0.1}, {100.0, 400.0});
  e.follow_speed(ramp);
  const double h = 1e-5;
  for (double t : {0.013, 0.037, 0.05, 0.071}) {
    const auto s = e.state(t);
    EXPECT_EQ(s.thd, ramp.speed(t));
    EXPECT_EQ(s.thdd, ramp.acceleration(t));
    ASSERT_GT(std::abs(s.thdd), 1000.0);
    const double fd = (e.state(t + h).x - 2 * s.x + e.state(t - h).x) / (h * h);
    EXPECT_NEAR(s.xdd, fd, 1e-4 * 0.0575 * 400 * 400) << "t = " << t;
  }
}

// `evas run --param crank.lof.speed=W` changes the operating point in one
// place: the crank-angle rows come 1 deg / W apart, the pistons follow, and
// the results file keeps the changed scene.
TEST(CrankSpeed, EvasRunTakesParam) {
  (void)engine_scene(0.005);
  const fs::path dir = fs::temp_directory_path() / ("evas_crank_" + std::to_string(::getpid()));
  const fs::path scene = dir / std::to_string(0.005) / "case1.yaml";
  const fs::path out = dir / "run_param";
  const double w = 418.879;  // 4000 rpm
  const std::string cmd = std::string(EVAS_BINARY_DIR) + "/evas run " + scene.string() +
                          " --param crank.lof.speed=418.879 --out " + out.string() + " --quiet";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  const ResultsData r = read_results((out / "results.h5").string());
  EXPECT_EQ(r.status, "completed");
  ASSERT_GT(r.time.size(), 10u);
  for (std::size_t i = 1; i < r.time.size(); ++i)
    EXPECT_NEAR(r.time[i] - r.time[i - 1], M_PI / 180 / w, 1e-12) << i;
  EXPECT_NE(r.scene.find("speed: 418.879"), std::string::npos);
  // a key that matches nothing is an input error (exit 1), nothing written
  const std::string bad = std::string(EVAS_BINARY_DIR) + "/evas run " + scene.string() +
                          " --param crank.lof.sped=1 --out " + (dir / "run_bad").string() +
                          " --quiet 2>/dev/null";
  EXPECT_EQ(WEXITSTATUS(std::system(bad.c_str())), 1);
}

// Closed form of a two-knot Fritsch-Carlson profile (end slopes zero):
// w(t) = w0 + (w1 - w0)(3 x^2 - 2 x^3), x = t / T; its integral.
double ramp_angle(double t, double w0, double w1, double T) {
  if (t >= T) return T * (w0 + 0.5 * (w1 - w0)) + w1 * (t - T);
  const double x = t / T;
  return T * (w0 * x + (w1 - w0) * (x * x * x - 0.5 * x * x * x * x));
}

// A run-up 1000 -> 4000 rpm over 0.1 s of the engine (0.12 s run): the
// crank-angle grid and the pistons' crank angle are the integral of the
// crank's speed (to 1e-9 deg, up to the table's 720 deg cycle), with IDA and
// generalized-alpha.
TEST(CrankSpeed, RunUpPistonsFollowTheCrank) {
  const double w0 = 1000 * M_PI / 30, w1 = 4000 * M_PI / 30, T = 0.1;
  std::ostringstream prof;
  prof.precision(17);
  prof << "speed_profile: [[0, " << w0 << "], [" << T << ", " << w1 << "]]}";
  std::string ramp = replaced(engine_scene(0.12), R"(speed: 314\.159\})", prof.str());
  for (const std::string integ : {"ida", "generalized-alpha"}) {
    std::string text = ramp;
    if (integ == "generalized-alpha")
      text = replaced(text, R"(integrator: \{[^}]*\})",
                      "integrator: {name: generalized-alpha, step: 5e-6}");
    const Rows r = run(text, integ);
    ASSERT_GT(r.time.size(), 100u) << integ;
    // rows on the crank-angle grid: whole degrees of the crank's own angle
    // (the LOF's), which is the integral of the profile; cylinder 1's crank
    // angle is the same modulo its 720 deg cycle
    double worst = 0.0, off_grid = 0.0;
    for (std::size_t i = 0; i < r.time.size(); ++i) {
      const double crank_deg = ramp_angle(r.time[i], w0, w1, T) * 180 / M_PI;
      worst = std::max(worst, std::abs(r.at(i, "crank_angle") - crank_deg));
      off_grid = std::max(off_grid, std::abs(crank_deg - std::round(crank_deg)));
      double want = std::fmod(crank_deg, 720.0);
      if (want < 0) want += 720.0;
      double d = std::abs(r.at(i, "cyl1.crank_angle") - want);
      worst = std::max(worst, std::min(d, 720.0 - d));
    }
    EXPECT_LT(off_grid, 1e-6) << integ;
    EXPECT_LT(worst, 1e-9) << integ;
    // the dynamometer follows as well: its twist is what the 5e4 N m/rad
    // spring needs to drag the crankshaft's rigid rotation through the
    // run-up (J alpha / K_r, about 0.05 rad at the ramp's steepest, plus the
    // gas torque), where a constant-speed driver would fall 16 rad behind by
    // the end of the ramp
    double twist = 0.0;
    for (std::size_t i = 0; i < r.time.size(); ++i)
      twist = std::max(twist, std::abs(r.at(i, "dyno.twist")));
    EXPECT_LT(twist, 0.2) << integ;
  }
}

}  // namespace
