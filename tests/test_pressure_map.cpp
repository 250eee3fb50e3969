// Gas pressure at several operating points (elements/pressure_map.h): tables
// per speed (and per load), interpolated linearly in the prescribed crank speed
// and in the scene's operating_point.load; a crank speed outside any load's
// tables or a load outside the map's is refused naming both ranges; bad map
// files name the file and line; the scene states the load once and refuses a
// load nothing reads. Hand-checked values: tables of constant pressure.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "elements/piston_conrod.h"
#include "elements/pressure_map.h"
#include "elements/registry.h"
#include "io/scene.h"
#include "study/scene_edit.h"

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

// The folder of tables and maps goes with the test program (ctest runs each
// test as its own process, each with its own folder).
class RemoveDir : public ::testing::Environment {
 public:
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir(), ec);
  }
};
::testing::Environment* const kRemoveDir = ::testing::AddGlobalTestEnvironment(new RemoveDir);

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

// Two loads, each with its own speeds, tables of constant pressure [Pa]:
//   L = 0.25:  1000 rpm 20e5,  3000 rpm 60e5
//   L = 0.75:  1000 rpm 40e5,  2000 rpm 70e5,  3000 rpm 100e5
// so every interpolated value below is a hand sum of halves and quarters.
std::string load_map(const std::string& name, const std::string& text = "") {
  constant_table("q1000.txt", 40e5);
  constant_table("q2000.txt", 70e5);
  constant_table("q3000.txt", 100e5);
  return map_file(name, !text.empty() ? text
                                      : "# speed [rpm]  load [-]  table\n"
                                        "1000 0.25 p1000.txt\n3000 0.25 p3000.txt\n"
                                        "1000 0.75 q1000.txt\n2000 0.75 q2000.txt\n"
                                        "3000 0.75 q3000.txt\n");
}

TEST(PressureMap, InterpolatesBilinearlyInSpeedAndLoad) {
  const PressureMap m = PressureMap::read(load_map("loads.txt"));
  ASSERT_TRUE(m.has_loads());
  ASSERT_EQ(m.loads().size(), 2u);
  EXPECT_EQ(m.loads()[1].entries.size(), 3u);
  EXPECT_EQ(m.min_load(), 0.25);
  EXPECT_EQ(m.max_load(), 0.75);
  const double w = 2000 * kRpm;
  // the tables themselves
  EXPECT_NEAR(m(0.3, 1000 * kRpm, 0.25), 20e5, 1e-6);
  EXPECT_NEAR(m(0.3, 3000 * kRpm, 0.75), 100e5, 1e-6);
  // halfway in speed and load: (1 - 1/2) 40e5 + 1/2 70e5
  EXPECT_NEAR(m(1.0, w, 0.5), 55e5, 1e-6);
  // a quarter in speed, a quarter in load: 3/4 30e5 + 1/4 55e5 = 36.25e5
  EXPECT_NEAR(m(2.0, 1500 * kRpm, 0.375), 36.25e5, 1e-6);
  // three quarters in load at 2500 rpm: 1/4 50e5 + 3/4 85e5 = 76.25e5
  EXPECT_NEAR(m(2.0, 2500 * kRpm, 0.625), 76.25e5, 1e-6);
  // clamped at the loads' ends (check_load refuses a scene beyond them)
  EXPECT_NEAR(m(1.0, w, 0.1), 40e5, 1e-6);
  EXPECT_NEAR(m(1.0, w, 0.9), 70e5, 1e-6);

  // the piston reads it at the crank's speed and the scene's load
  auto e = piston(load_map("loads2.txt"));
  EXPECT_NE(e->load_source().find("loads2.txt"), std::string::npos) << e->load_source();
  e->follow_speed(SpeedProfile({0.0, 0.1}, {1000 * kRpm, 3000 * kRpm}));
  e->set_operating_load(0.5);
  const auto& pc = dynamic_cast<const PistonConrod&>(*e);
  EXPECT_NEAR(pc.state(0.05).p, 55e5, 1e-9 * 55e5);  // 2000 rpm
  EXPECT_NEAR(pc.state(0.0).p, 30e5, 1e-9 * 30e5);   // 1000 rpm: 1/2 20e5 + 1/2 40e5
}

TEST(PressureMap, OneLoadIsUsedAtEveryLoad) {
  const PressureMap m =
      PressureMap::read(load_map("one.txt", "1000 0.5 p1000.txt\n3000 0.5 p3000.txt\n"));
  ASSERT_TRUE(m.has_loads());
  for (double L : {-1.0, 0.5, 7.0}) {
    EXPECT_NO_THROW(m.check_load(L, "test"));
    EXPECT_NEAR(m(1.0, 1500 * kRpm, L), 30e5, 1e-6);
  }
  // a map without loads is the speed interpolation alone, and reads no load
  auto e = piston(map_file("noload.txt", "1000 p1000.txt\n3000 p3000.txt\n"));
  EXPECT_EQ(e->load_source(), "");
}

TEST(PressureMap, BadLoadColumnsNameFileAndLine) {
  auto error_reading = [](const std::string& name, const std::string& text) {
    return error_of([&] { PressureMap::read(load_map(name, text)); });
  };
  std::string why = error_reading("mix.txt", "1000 p1000.txt\n3000 0.5 p3000.txt\n");
  EXPECT_NE(why.find("mix.txt:2: mixes 'speed_rpm table_file' and 'speed_rpm load table_file'"),
            std::string::npos)
      << why;
  why = error_reading("mix2.txt", "# loads\n1000 0.5 p1000.txt\n\n3000 p3000.txt\n");
  EXPECT_NE(why.find("mix2.txt:4: mixes"), std::string::npos) << why;
  EXPECT_NE(why.find("line 2 has 3 columns"), std::string::npos) << why;
  // loads decreasing, and one load's lines split by another's
  why = error_reading("down.txt", "1000 0.5 p1000.txt\n3000 0.5 p3000.txt\n1000 0.25 p1000.txt\n");
  EXPECT_NE(why.find("down.txt:3: loads must increase (load 0.25 after load 0.5)"),
            std::string::npos)
      << why;
  EXPECT_NE(why.find("all lines of one load together"), std::string::npos) << why;
  why =
      error_reading("split.txt", "1000 0.25 p1000.txt\n1000 0.5 p1000.txt\n3000 0.25 p3000.txt\n");
  EXPECT_NE(why.find("split.txt:3: loads must increase"), std::string::npos) << why;
  why = error_reading("slow.txt", "3000 0.5 p3000.txt\n1000 0.5 p1000.txt\n");
  EXPECT_NE(why.find("slow.txt:2: speeds must increase strictly within load 0.5"),
            std::string::npos)
      << why;
  why = error_reading("word.txt", "1000 half p1000.txt\n");
  EXPECT_NE(why.find("word.txt:1: load 'half' is not a number"), std::string::npos) << why;
  why = error_reading("nan.txt", "1000 nan p1000.txt\n");
  EXPECT_NE(why.find("nan.txt:1: load 'nan' must be finite"), std::string::npos) << why;
  why = error_reading("four.txt", "1000 0.5 p1000.txt extra\n");
  EXPECT_NE(why.find("four.txt:1: expected 'speed_rpm table_file' or 'speed_rpm load"),
            std::string::npos)
      << why;
}

TEST(PressureMap, EveryLoadMustCoverTheCrankSpeeds) {
  const std::string map = load_map("short.txt",
                                   "1000 0.25 p1000.txt\n3000 0.25 p3000.txt\n"
                                   "1000 0.75 q1000.txt\n2000 0.75 q2000.txt\n");
  auto e = piston(map);
  const std::string why = error_of([&] {
    e->follow_speed(SpeedProfile({0.0, 0.1}, {1000 * kRpm, 3000 * kRpm}));
  });
  EXPECT_NE(why.find("short.txt at load 0.75 covers 1000 .. 2000 rpm, but the crank turns at "
                     "1000 .. 3000 rpm"),
            std::string::npos)
      << why;
  // within every load's speeds: accepted
  auto ok = piston(map);
  EXPECT_NO_THROW(ok->follow_speed(SpeedProfile({0.0, 0.1}, {1000 * kRpm, 2000 * kRpm})));
}

TEST(PressureMap, LoadOutsideTheMapIsRefused) {
  auto e = piston(load_map("range.txt"));
  e->follow_speed(SpeedProfile({0.0}, {2000 * kRpm}));
  for (double L : {0.2, 1.5}) {
    const std::string why = error_of([&] { e->set_operating_load(L); });
    EXPECT_NE(why.find("piston-conrod 'cyl1': operating_point.load = "), std::string::npos) << why;
    EXPECT_NE(why.find("is outside the loads of the pressure map"), std::string::npos) << why;
    EXPECT_NE(why.find("range.txt, 0.25 .. 0.75"), std::string::npos) << why;
  }
  EXPECT_NO_THROW(e->set_operating_load(0.75));
}

// A crank turning at 2000 rpm and one prescribed piston with the map MAP
// (relative to the scene file in dir()), plus EXTRA at the top level: line 19.
std::string scene_text(const std::string& map, const std::string& extra) {
  return R"(name: load
bodies:
  - name: crank
    generate: {type: truss-beam, segments: 6, length: 0.6, width: 0.15, area: 5e-4}
    modes: {rigid: true, elastic: 4}
    lof: {kind: spin, axis: [1, 0, 0], origin: [0, 0, 0], speed: 209.43951023931956}
  - name: block
    generate: {type: truss-beam, segments: 6, length: 0.6, width: 0.2, area: 2e-3}
    modes: {rigid: true, elastic: 4}
    lof: {kind: fixed, origin: [0, 0, 0]}
markers:
  - {name: pin, body: crank, set: section3}
  - {name: liner, body: block, set: section3}
  - {name: head, body: block, set: section4}
elements:
  - {name: cyl1, type: piston-conrod, markers: [pin, liner, head], crank_radius: 0.0575,
     conrod_length: 0.18, bore: 0.08, piston_mass: 0.5, pressure_map: )" +
         map + R"(}
time: {start: 0, end: 0.01}
)" + extra;
}

std::string scene_error(const std::string& text) {
  return error_of([&] { parse_scene(text, (dir() / "load.yaml").string()); });
}

TEST(PressureMap, SceneStatesTheLoadOnce) {
  load_map("scene_loads.txt");
  map_file("scene_plain.txt", "1000 p1000.txt\n3000 p3000.txt\n");
  const std::string path = (dir() / "load.yaml").string();
  // the load reaches the piston: 2000 rpm, halfway in load
  const Scene scene =
      parse_scene(scene_text("scene_loads.txt", "operating_point: {load: 0.5}\n"), path);
  const auto& pc = dynamic_cast<const PistonConrod&>(*scene.model->elements().at(0));
  EXPECT_NEAR(pc.state(0.003).p, 55e5, 1e-9 * 55e5);

  // a map with loads, and no load in the scene
  std::string why = scene_error(scene_text("scene_loads.txt", ""));
  EXPECT_NE(why.find("element 'cyl1': its pressure map "), std::string::npos) << why;
  EXPECT_NE(why.find("scene_loads.txt has a load column, but the scene gives no "
                     "operating_point.load"),
            std::string::npos)
      << why;
  why = scene_error(scene_text("scene_loads.txt", "operating_point: {}\n"));
  EXPECT_NE(why.find("gives no operating_point.load"), std::string::npos) << why;
  // a load nothing reads
  why = scene_error(scene_text("scene_plain.txt", "operating_point: {load: 0.5}\n"));
  EXPECT_NE(why.find("load.yaml:19: operating_point: 'load' is given, but no element reads a load"),
            std::string::npos)
      << why;
  // a load outside the map's, not a number, not finite, an unknown key
  why = scene_error(scene_text("scene_loads.txt", "operating_point: {load: 1.5}\n"));
  EXPECT_NE(why.find("element 'cyl1'"), std::string::npos) << why;
  EXPECT_NE(why.find("operating_point.load = 1.5 is outside the loads of the pressure map"),
            std::string::npos)
      << why;
  for (const char* bad : {".nan", ".inf", "-.inf"}) {
    why = scene_error(
        scene_text("scene_loads.txt", std::string("operating_point: {load: ") + bad + "}\n"));
    EXPECT_NE(why.find("load.yaml:19: operating_point: 'load' must be finite"), std::string::npos)
        << why;
  }
  why = scene_error(scene_text("scene_loads.txt", "operating_point: {load: full}\n"));
  EXPECT_NE(why.find("operating_point: 'load' must be a number, got 'full'"), std::string::npos)
      << why;
  why = scene_error(scene_text("scene_loads.txt", "operating_point: {load: 0.5, speed: 3}\n"));
  EXPECT_NE(why.find("operating_point: unknown key 'speed' (known: load)"), std::string::npos)
      << why;
}

TEST(PressureMap, StudyOverridesReachTheLoad) {
  load_map("scene_loads.txt");
  const std::string path = (dir() / "load.yaml").string();
  // --param/--sweep operating_point.load=...: the mapping is made when absent
  const std::string edited =
      study::edit_scene_text(scene_text("scene_loads.txt", ""), {"operating_point.load=0.25"});
  const Scene scene = parse_scene(edited, path);
  const auto& pc = dynamic_cast<const PistonConrod&>(*scene.model->elements().at(0));
  EXPECT_NEAR(pc.state(0.003).p, 40e5, 1e-9 * 40e5);  // 2000 rpm at load 0.25
  const std::string again = study::edit_scene_text(edited, {"operating_point.load=0.75"});
  const Scene full = parse_scene(again, path);
  const auto& pf = dynamic_cast<const PistonConrod&>(*full.model->elements().at(0));
  EXPECT_NEAR(pf.state(0.003).p, 70e5, 1e-9 * 70e5);
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
