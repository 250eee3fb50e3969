// The journal's orbit under a periodic load (elements/bearing_orbit.h, `evas
// bearing --load-cycle`), verified against the effective-speed principle of
// dynamically loaded bearings: the film's pressure depends on the journal's
// spin om and the line of centres' turning rate g only through om - 2 g
// (Booker, "Dynamically loaded journal bearings: mobility method of solution",
// J. Basic Eng. 87, 1965; Hamrock, Schmid & Jacobson, Fundamentals of Fluid
// Film Lubrication, 2nd ed., 2004, "Dynamically loaded journal bearings"). A
// load of constant size turning at k om is carried, once the orbit settles, on
// a circle of the eccentricity that the same steady load gives at the speed
// |1 - 2 k| om: k = 1 (a synchronous load, an unbalance) at om itself, k = -1
// at 3 om, k = 1/4 at om / 2; k = 1/2 leaves no film at all (the half-speed
// whirl): the journal runs to the wall.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "elements/bearing_orbit.h"
#include "elements/bearing_static.h"
#include "film_support.h"
#include "io/load_cycle.h"
#include "model/types.h"

using namespace evas;
using film_test::json_number;
using film_test::run_bearing;
namespace fs = std::filesystem;

namespace {

JournalBearingParams params(const std::string& film) {
  JournalBearingParams p;
  p.radius = 0.03;
  p.width = 0.02;  // L/D = 1/3
  p.clearance = 3e-5;
  p.viscosity = 0.01;
  p.film = film;
  p.grid_phi = 36;
  p.grid_axial = 4;
  return p;
}

constexpr double kOmega = 3000.0 * M_PI / 30.0;  // 3000 rpm
constexpr double kLoad = 5000.0;                 // N

// A load of kLoad turning at k om, over one period of the crank angle (1 deg rows).
LoadCycle rotating(double k) {
  LoadCycle c;
  const double period = std::abs(k) > 0.0 ? 360.0 / std::abs(k) : 360.0;
  const int n = static_cast<int>(std::lround(period));
  for (int i = 0; i <= n; ++i) {
    const double a = period * i / n, ph = k * a * M_PI / 180.0;
    c.angle_deg.push_back(a);
    c.fx.push_back(kLoad * std::cos(ph));
    c.fy.push_back(kLoad * std::sin(ph));
  }
  c.fx.back() = c.fx.front(), c.fy.back() = c.fy.front();  // closed to the last bit
  return c;
}

struct Whirl {
  double eps_min, eps_max;
};
Whirl whirl(const BearingOrbit& o) {
  Whirl w{1.0, 0.0};
  for (const OrbitPoint& p : o.cycle)
    w.eps_min = std::min(w.eps_min, p.eccentricity),
    w.eps_max = std::max(w.eps_max, p.eccentricity);
  return w;
}

}  // namespace

TEST(BearingOrbit, RotatingLoadsRideAtTheEffectiveSpeedsEccentricity) {
  for (const std::string film : {"short", "finite"}) {
    const JournalBearing b("b", {0, 1}, params(film));
    for (const double k : {0.0, 1.0, -1.0, 0.25}) {
      const BearingOrbit o = bearing_orbit(b, kOmega, rotating(k), OrbitOptions{});
      ASSERT_TRUE(o.failure.empty()) << film << " k " << k << ": " << o.failure;
      EXPECT_TRUE(o.settled) << film << " k " << k;
      EXPECT_LT(o.change, 1e-4);
      const double expected =
          bearing_at_load(b, std::abs(1.0 - 2.0 * k) * kOmega, kLoad).eccentricity;
      const Whirl w = whirl(o);
      EXPECT_NEAR(w.eps_max, expected, 2e-5 * expected) << film << " k " << k;
      EXPECT_NEAR(w.eps_min, expected, 2e-5 * expected) << film << " k " << k;
      std::cout << film << " k " << k << ": eps " << w.eps_min << " .. " << w.eps_max
                << ", static at |1 - 2k| om " << expected << ", " << o.cycles << " cycles, "
                << o.steps << " steps\n";
    }
  }
}

// The Reynolds film on its grid (36 x 4 here): the load turns over the grid,
// the static answer is taken with the load along x, so the two agree to the
// grid's accuracy in the load's direction, not to the bit.
TEST(BearingOrbit, ReynoldsFilmRidesAtTheEffectiveSpeedsEccentricity) {
  const JournalBearing b("b", {0, 1}, params("reynolds"));
  for (const double k : {1.0, -1.0}) {
    OrbitOptions opt;
    opt.samples = 90;
    const BearingOrbit o = bearing_orbit(b, kOmega, rotating(k), opt);
    ASSERT_TRUE(o.failure.empty()) << o.failure;
    EXPECT_TRUE(o.settled);
    const double expected =
        bearing_at_load(b, std::abs(1.0 - 2.0 * k) * kOmega, kLoad).eccentricity;
    const Whirl w = whirl(o);
    EXPECT_NEAR(w.eps_max, expected, 2e-3 * expected) << "k " << k;
    EXPECT_NEAR(w.eps_min, expected, 2e-3 * expected) << "k " << k;
    std::cout << "reynolds k " << k << ": eps " << w.eps_min << " .. " << w.eps_max << ", static "
              << expected << "\n";
  }
}

TEST(BearingOrbit, HalfSpeedLoadFindsNoFilm) {
  const JournalBearing b("b", {0, 1}, params("short"));
  const BearingOrbit o = bearing_orbit(b, kOmega, rotating(0.5), OrbitOptions{});
  ASSERT_FALSE(o.failure.empty());
  EXPECT_NE(o.failure.find("at crank angle"), std::string::npos) << o.failure;
  EXPECT_NE(o.failure.find("eps_max"), std::string::npos) << o.failure;
  ASSERT_GT(o.cycle.size(), 1u);
  // the journal drifted outwards all the way: the last point reached is the farthest
  EXPECT_GT(o.cycle.back().eccentricity, 0.95);
  EXPECT_GT(o.cycle.back().eccentricity, o.cycle.front().eccentricity);
}

// A connecting-rod-like cycle (a firing peak over inertia, 720 deg): the orbit
// does not depend on the step's tolerance beyond it, and one cycle after it
// settled it repeats itself.
TEST(BearingOrbit, RodCycleConvergesWithTheTolerance) {
  LoadCycle c;
  for (int i = 0; i <= 720; ++i) {
    const double a = i * M_PI / 180.0;
    c.angle_deg.push_back(i);
    c.fx.push_back(18000.0 * std::exp(-std::pow((i - 370) / 25.0, 2)) -
                   4000.0 * (std::cos(a) + 0.3 * std::cos(2.0 * a)));
    c.fy.push_back(1500.0 * std::sin(a));
  }
  c.fx.back() = c.fx.front(), c.fy.back() = c.fy.front();
  const JournalBearing b("b", {0, 1}, params("short"));
  OrbitOptions loose, tight;
  loose.tolerance = 1e-6;
  tight.tolerance = 1e-9;
  tight.settle_tol = loose.settle_tol = 1e-6;
  const BearingOrbit a = bearing_orbit(b, kOmega, c, loose), t = bearing_orbit(b, kOmega, c, tight);
  ASSERT_TRUE(a.settled && t.settled);
  double diff = 0.0, h_min = 1.0;
  for (std::size_t k = 0; k < t.cycle.size(); ++k) {
    diff = std::max(diff, (a.cycle[k].e - t.cycle[k].e).norm() / 3e-5);
    h_min = std::min(h_min, t.cycle[k].min_film);
  }
  EXPECT_LT(diff, 1e-4);
  EXPECT_GT(t.steps, a.steps);
  EXPECT_GT(h_min, 0.0);
  std::cout << "rod cycle: tolerance 1e-6 against 1e-9: " << diff << " c; steps " << a.steps
            << " / " << t.steps << "; minimum film " << h_min << " m\n";
}

TEST(BearingOrbit, LoadCycleFileAndItsErrors) {
  const fs::path dir = fs::temp_directory_path() / ("evas_orbit_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path f = dir / "cycle.csv";
  {
    std::ofstream o(f);
    o << "# comment\nangle_deg, fx, fy\n0, 100, 0\n\n90, 0, 100\n180, -100, 0\n360, 100, 0\n";
  }
  const LoadCycle c = read_load_cycle(f.string());
  ASSERT_EQ(c.angle_deg.size(), 4u);
  EXPECT_DOUBLE_EQ(c.period_deg(), 360.0);
  EXPECT_NEAR(c.at(45.0).x(), 50.0, 1e-12);
  EXPECT_NEAR(c.at(45.0 + 720.0).y(), 50.0, 1e-12);  // the cycle repeats
  EXPECT_NEAR(c.at(-315.0).y(), 50.0, 1e-12);
  EXPECT_NEAR(c.at(270.0).x(), 0.0, 1e-12);
  // the bad files and options are the bad-input catalogue's (cycle_*)
  LoadCycle open = c;
  open.fx.back() = 90.0;
  EXPECT_THROW(check_load_cycle(open, "x"), InputError);
  const JournalBearing mc("b", {0, 1}, [] {
    JournalBearingParams p = params("reynolds");
    p.cavitation = "mass-conserving";
    p.feed = "axial-grooves";
    return p;
  }());
  try {
    bearing_orbit(mc, kOmega, c, OrbitOptions{});
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("static answer only"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}

TEST(BearingOrbit, CommandWritesTheOrbit) {
  const fs::path dir = fs::temp_directory_path() / ("evas_orbit_cmd_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  {
    std::ofstream o(dir / "sync.csv");
    const LoadCycle c = rotating(1.0);
    o << "angle_deg,fx,fy\n";
    o.precision(17);
    for (std::size_t k = 0; k < c.fx.size(); ++k)
      o << c.angle_deg[k] << "," << c.fx[k] << "," << c.fy[k] << "\n";
  }
  int code = -1;
  const std::string out = run_bearing(
      "--radius 0.03 --width 0.02 --clearance 3e-5 --viscosity 0.01 --speed 3000 "
      "--load-cycle " +
          (dir / "sync.csv").string() + " --out " + (dir / "o").string() + " --no-plot --json",
      code);
  ASSERT_EQ(code, 0) << out;
  const double expected =
      bearing_at_load(JournalBearing("b", {0, 1}, params("short")), kOmega, kLoad).eccentricity;
  EXPECT_NEAR(json_number(out, "max_eccentricity"), expected, 2e-5 * expected) << out;
  EXPECT_NE(out.find("\"settled\": true"), std::string::npos) << out;
  std::ifstream csv(dir / "o" / "orbit.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header,
            "angle_deg,time_s,x_m,y_m,eccentricity,min_film_m,max_pressure_Pa,load_x_N,load_y_N");
  int rows = 0;
  for (std::string line; std::getline(csv, line);) ++rows;
  EXPECT_EQ(rows, 361);
  EXPECT_TRUE(fs::exists(dir / "o" / "orbit.gp"));
  EXPECT_FALSE(fs::exists(dir / "o" / "orbit.png"));  // --no-plot
  fs::remove_all(dir);
}
