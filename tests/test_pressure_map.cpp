// Gas pressure at several operating points (elements/pressure_map.h): tables
// per speed, interpolated linearly in the prescribed crank speed; a crank
// speed outside the tables' range is refused naming both ranges; bad map files
// name the file and line. Hand-checked values: tables of constant pressure.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "elements/piston_conrod.h"
#include "elements/pressure_map.h"
#include "elements/registry.h"

using namespace evas;
namespace fs = std::filesystem;

namespace {

constexpr double kRpm = M_PI / 30.0;

const fs::path& dir() {
  static const fs::path d = [] {
    const fs::path p = fs::temp_directory_path() / ("evas_pmap_" + std::to_string(::getpid()));
    fs::create_directories(p);
    return p;
  }();
  return d;
}

// A table of constant pressure p [Pa] over the cycle, written to NAME.
void constant_table(const std::string& name, double p) {
  std::vector<double> a, v;
  for (int i = 0; i < 72; ++i) {
    a.push_back(10.0 * i);
    v.push_back(p);
  }
  PressureTable(a, v, name).write((dir() / name).string(), "constant");
}

std::string map_file(const std::string& name, const std::string& text) {
  constant_table("p1000.txt", 20e5);
  constant_table("p3000.txt", 60e5);
  std::ofstream((dir() / name).string()) << text;
  return (dir() / name).string();
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(PressureMap, InterpolatesLinearlyInSpeed) {
  const PressureMap m = PressureMap::read(
      map_file("map.txt", "# speed [rpm]  table\n1000 p1000.txt\n\n3000 p3000.txt  # full load\n"));
  ASSERT_EQ(m.entries().size(), 2u);
  EXPECT_NEAR(m.min_speed(), 1000 * kRpm, 1e-12);
  EXPECT_NEAR(m(0.3, 1000 * kRpm), 20e5, 1e-6);
  EXPECT_NEAR(m(0.3, 3000 * kRpm), 60e5, 1e-6);
  EXPECT_NEAR(m(1.0, 1500 * kRpm), 30e5, 1e-6);  // a quarter of the way
  EXPECT_NEAR(m(2.0, 2000 * kRpm), 40e5, 1e-6);
}

TEST(PressureMap, BadMapFilesNameFileAndLine) {
  const std::string down = map_file("down.txt", "3000 p3000.txt\n1000 p1000.txt\n");
  EXPECT_NE(error_of([&] { PressureMap::read(down); }).find("down.txt:2: speeds must increase"),
            std::string::npos);
  const std::string missing = map_file("missing.txt", "1000 p1000.txt\n2000 nothing.txt\n");
  EXPECT_NE(error_of([&] { PressureMap::read(missing); }).find("missing.txt:2: "),
            std::string::npos);
  const std::string garbage = map_file("garbage.txt", "1000\n");
  EXPECT_NE(error_of([&] { PressureMap::read(garbage); }).find("garbage.txt:1: expected"),
            std::string::npos);
}

// The element as a scene builds it: prescribed, no speed of its own, the map.
std::unique_ptr<Element> piston(const std::string& map, const std::string& mode = "prescribed",
                                double speed = -1) {
  const ElementType& t = element_type("piston-conrod");
  ParamValues v;
  v.numbers = {
      {"crank_radius", {0.05}}, {"conrod_length", {0.2}}, {"bore", {0.1}}, {"piston_mass", {1.0}}};
  if (speed > 0) v.numbers["speed"] = {speed};
  v.texts = {{"pressure_map", map}, {"mode", mode}};
  complete_params(t, v, "test");
  return t.make("cyl1", {0, 1, 2}, v);
}

TEST(PressureMap, PistonReadsItAtTheCrankSpeed) {
  const std::string map = map_file("map2.txt", "1000 p1000.txt\n3000 p3000.txt\n");
  auto e = piston(map);
  ASSERT_TRUE(e->wants_speed());
  const SpeedProfile ramp({0.0, 0.1}, {1000 * kRpm, 3000 * kRpm});
  e->follow_speed(ramp);
  const auto& pc = dynamic_cast<const PistonConrod&>(*e);
  for (double t : {0.0, 0.02, 0.05, 0.08, 0.1, 0.2}) {
    const double rpm = ramp.speed(t) / kRpm;
    const double want = 20e5 + (rpm - 1000) / 2000 * 40e5;
    EXPECT_NEAR(pc.state(t).p, want, 1e-6 * want) << "t = " << t;
  }
  // a ramp that leaves the tables' speeds is refused, naming both ranges
  auto e2 = piston(map);
  const std::string why = error_of([&] {
    e2->follow_speed(SpeedProfile({0.0, 0.1}, {1000 * kRpm, 4000 * kRpm}));
  });
  EXPECT_NE(why.find("covers 1000 .. 3000 rpm, but the crank turns at 1000 .. 4000 rpm"),
            std::string::npos)
      << why;
  // so is an own constant speed outside it, and a coupled piston
  EXPECT_NE(error_of([&] { piston(map, "prescribed", 500 * kRpm); }).find("500 .. 500 rpm"),
            std::string::npos);
  EXPECT_NE(error_of([&] { piston(map, "coupled"); }).find("needs mode 'prescribed'"),
            std::string::npos);
}

}  // namespace
