// Scene files: a valid scene builds the model it describes; bad scenes give an
// InputError "<file>:<line>: <item>: <what>" pointing at the offending line.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "bodies/body_builder.h"
#include "bodies/truss.h"
#include "io/body_file.h"
#include "io/outputs.h"
#include "io/scene.h"
#include "solver/system.h"

using namespace evas;

namespace {

// One directory per test process: ctest runs every case as its own process, in
// parallel, and each writes the shared body file the scenes refer to.
const std::string kDir = [] {
  const std::string d = ::testing::TempDir() + "evas_scene_" + std::to_string(::getpid()) + "/";
  std::filesystem::create_directories(d);
  return d;
}();

// Two bodies: one generated (spinning), one read from a body file (fixed).
const char* kScene = R"(name: two-beams
gravity: [0, 0, -9.81]
bodies:
  - name: shaft
    generate: {type: truss-beam, segments: 4, length: 0.4, width: 0.04}
    modes: {rigid: true, elastic: 5}
    damping_ratio: 0.01
    lof: {kind: spin, axis: [1, 0, 0], origin: [0, 0, 0], speed: 100.0}
  - name: frame
    file: frame_body.h5
    modes: {rigid: false, elastic: 4}
    damping_ratio: 0.02
    lof: {kind: fixed, origin: [0, 0, -0.2], rotation: [0, 0, 0]}
    initial: {q: [0.001, 0, 0, 0], v: [0, 0, 0, 0]}
markers:
  - {name: a, body: shaft, node: 3}
  - {name: b, body: shaft, set: end1}
  - {name: c, body: frame, set: end1, weights: [1, 1, 1, 1]}
  - {name: g, ground: [0, 0, -0.3]}
elements:
  - {name: k1, type: spring-damper, markers: [b, c], stiffness: [1e6, 1e6, 1e6], damping: [100, 100, 100]}
  - {name: k2, type: spring-damper, markers: [c, g], stiffness: [1e5, 1e5, 1e5]}
integrator: {name: ida, rtol: 1e-6, atol: 1e-8}
time: {start: 0, end: 0.01}
output:
  grid: time
  step: 1e-3
  channels:
    - {marker: a}
    - {element: k1}
    - {modal: frame}
)";

std::string write_text(const std::string& name, const std::string& text) {
  const std::string path = kDir + name;
  std::ofstream(path) << text;
  return path;
}

void ensure_frame_body() {
  static bool done = false;
  if (done) return;
  TrussBeamSpec spec;
  spec.segments = 3;
  spec.length = 0.3;
  BuildOptions opt;
  opt.num_elastic = 6;
  write_body_file(kDir + "frame_body.h5", build_modal_body("frame", make_truss_beam(spec), opt));
  done = true;
}

// 1-based line of the first occurrence of `needle` in `text`.
int line_of(const std::string& text, const std::string& needle) {
  const auto pos = text.find(needle);
  EXPECT_NE(pos, std::string::npos) << needle;
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + pos, '\n'));
}

std::string replace(std::string text, const std::string& from, const std::string& to) {
  const auto pos = text.find(from);
  EXPECT_NE(pos, std::string::npos) << from;
  return text.replace(pos, from.size(), to);
}

// Reads `text` as a scene file and expects an InputError that names the file,
// the line holding `at` and each fragment.
void expect_error(const std::string& file, const std::string& text, const std::string& at,
                  const std::vector<std::string>& fragments) {
  ensure_frame_body();
  const std::string path = write_text(file, text);
  try {
    read_scene(path);
    FAIL() << "no error for " << file;
  } catch (const InputError& e) {
    const std::string msg = e.what();
    const std::string where = file + ":" + std::to_string(line_of(text, at)) + ": ";
    EXPECT_NE(msg.find(where), std::string::npos) << "'" << msg << "' lacks '" << where << "'";
    for (const auto& f : fragments)
      EXPECT_NE(msg.find(f), std::string::npos) << "'" << msg << "' lacks '" << f << "'";
  }
}

}  // namespace

TEST(Scene, ValidSceneBuildsModel) {
  ensure_frame_body();
  const Scene s = read_scene(write_text("valid.yaml", kScene));
  EXPECT_EQ(s.name, "two-beams");
  EXPECT_EQ(s.text, kScene);
  const Model& m = *s.model;
  ASSERT_EQ(m.bodies().size(), 2u);
  EXPECT_EQ(m.bodies()[0].n(), 6 + 5);
  EXPECT_EQ(m.bodies()[1].n(), 4);
  EXPECT_EQ(m.size(), 15);
  EXPECT_EQ(m.bodies()[0].lof.kind(), LofKind::Spin);
  EXPECT_DOUBLE_EQ(m.bodies()[0].lof.spin_speed(0.0), 100.0);
  EXPECT_EQ(m.bodies()[1].lof.kind(), LofKind::Fixed);
  EXPECT_DOUBLE_EQ(m.bodies()[1].q0[0], 0.001);
  EXPECT_EQ(m.bodies()[1].v0.size(), 4);
  EXPECT_DOUBLE_EQ(m.gravity.z(), -9.81);
  ASSERT_EQ(m.markers().size(), 4u);
  EXPECT_TRUE(m.markers()[3].on_ground());
  ASSERT_EQ(m.elements().size(), 2u);
  EXPECT_EQ(m.elements()[0]->type(), "spring-damper");
  EXPECT_EQ(m.elements()[1]->markers(), (std::vector<int>{2, 3}));
  EXPECT_EQ(s.integrator.name, "ida");
  EXPECT_DOUBLE_EQ(s.t_end, 0.01);
  ASSERT_EQ(s.output.channels.size(), 3u);
  EXPECT_EQ(s.output.channels[2].kind, ChannelRequest::Kind::Modal);

  // Elastic damping from the ratio: c_k = 2 zeta omega_k.
  const ModalBody& frame = *m.bodies()[1].data;
  EXPECT_NEAR(frame.damping[0], 2 * 0.02 * std::sqrt(frame.eigenvalues[0]), 1e-9);
  // Modes of the file body: no rigid, elastic sorted by frequency.
  for (int k = 0; k < frame.num_modes(); ++k) EXPECT_EQ(frame.kinds[k], ModeKind::Elastic);
}

TEST(Scene, OutputsFromScene) {
  ensure_frame_body();
  const Scene s = read_scene(write_text("valid_out.yaml", kScene));
  System sys(*s.model);
  OutputSet out(s.output, sys, s.t_start, s.t_end);
  ASSERT_EQ(out.times().size(), 11u);
  EXPECT_DOUBLE_EQ(out.times().back(), 0.01);
  const int n_k1 = static_cast<int>(s.model->elements()[0]->channels().size());
  ASSERT_EQ(out.size(), 6 + n_k1 + 4);
  EXPECT_EQ(out.channels()[0].name, "a.px");
  EXPECT_EQ(out.channels()[4].unit, "m/s");
  EXPECT_EQ(out.channels()[6].name.rfind("k1.", 0), 0u);
  EXPECT_EQ(out.channels().back().name, "frame.q3");
  Vec q, v;
  sys.initial_state(q, v);
  std::vector<double> vals(out.size());
  out.values(0.0, q.data(), v.data(), vals.data());
  // Marker a: node 3 of the shaft at rest, spinning about x through the origin.
  const ModalBody& shaft = *s.model->bodies()[0].data;
  const int i3 = shaft.node_index(3);
  EXPECT_NEAR(vals[0], shaft.s(i3, 0), 1e-12);
  EXPECT_NEAR(vals[4], -100.0 * shaft.s(i3, 2), 1e-9);  // v = w x p, w = 100 e_x
  EXPECT_DOUBLE_EQ(vals.back(), 0.0);
  EXPECT_DOUBLE_EQ(vals[6 + n_k1], 0.001);  // frame.q0
}

TEST(Scene, CrankAngleGrid) {
  // Constant speed 100 rad/s: 10 degrees every (10 pi / 180) / 100 s.
  const Lof lof = Lof::spin(Vec3::Zero(), Mat3::Identity(), Vec3::UnitX(), 0.0, {0.0}, {100.0});
  const auto t = crank_angle_times(lof, 0.0, 0.01, 10.0, 0.0, false);
  const double dt = (10.0 * M_PI / 180.0) / 100.0;
  ASSERT_EQ(t.size(), 6u);  // 0..50 deg within 57.3 deg
  for (std::size_t k = 0; k < t.size(); ++k) EXPECT_NEAR(t[k], k * dt, 1e-14);
  // Accelerating profile: every output time has the requested angle.
  const Lof acc =
      Lof::spin(Vec3::Zero(), Mat3::Identity(), Vec3::UnitZ(), 0.1, {0.0, 1.0}, {10.0, 50.0});
  const auto t2 = crank_angle_times(acc, 0.0, 1.0, 30.0, 0.0, false);
  ASSERT_GT(t2.size(), 10u);
  for (double x : t2) {
    const double deg = acc.spin_angle(x) * 180.0 / M_PI;
    EXPECT_NEAR(deg - 30.0 * std::round(deg / 30.0), 0.0, 1e-8);
  }
  // Negative speed: angles decrease through multiples of the step.
  const Lof neg = Lof::spin(Vec3::Zero(), Mat3::Identity(), Vec3::UnitX(), 0.0, {0.0}, {-100.0});
  const auto t3 = crank_angle_times(neg, 0.0, 0.01, 10.0, 0.0, false);
  ASSERT_EQ(t3.size(), 6u);
  EXPECT_NEAR(t3[1], dt, 1e-14);
}

TEST(Scene, UnknownKey) {
  const std::string text = replace(kScene, "    lof: {kind: spin", "    lofx: {kind: spin");
  expect_error("unknown_key.yaml", text, "lofx",
               {"bodies[0] 'shaft'", "unknown key 'lofx'", "(known: name, file, generate"});
}

TEST(Scene, BadValueType) {
  const std::string text = replace(kScene, "rtol: 1e-6", "rtol: tight");
  expect_error("bad_type.yaml", text, "rtol: tight",
               {"integrator", "'rtol' must be a number, got 'tight'"});
}

TEST(Scene, WrongVectorLength) {
  const std::string text = replace(kScene, "stiffness: [1e6, 1e6, 1e6]", "stiffness: [1e6, 1e6]");
  expect_error("short_vector.yaml", text, "stiffness: [1e6, 1e6]",
               {"element 'k1'", "parameter 'stiffness' must have 3 values, got 2"});
}

TEST(Scene, OutOfRangeParameter) {
  const std::string text = replace(kScene, "damping: [100, 100, 100]", "damping: [100, -5, 100]");
  expect_error("range.yaml", text, "damping: [100, -5", {"element 'k1'", "parameter 'damping'"});
}

TEST(Scene, UnknownMarkerName) {
  const std::string text = replace(kScene, "markers: [c, g]", "markers: [c, gg]");
  expect_error("marker_name.yaml", text, "markers: [c, gg]",
               {"element 'k2'", "no marker named 'gg'", "known: a, b, c, g"});
}

TEST(Scene, MissingBodyFile) {
  const std::string text = replace(kScene, "file: frame_body.h5", "file: nowhere.h5");
  expect_error("missing_file.yaml", text, "file: nowhere.h5", {"bodies[1] 'frame'", "nowhere.h5"});
}

TEST(Scene, UnknownElementType) {
  const std::string text = replace(kScene, "type: spring-damper, markers: [c, g]",
                                   "type: spring-dumper, markers: [c, g]");
  expect_error("elem_type.yaml", text, "spring-dumper",
               {"element 'k2'", "unknown element type 'spring-dumper'"});
}

TEST(Scene, UnknownElementParameter) {
  const std::string text =
      replace(kScene, "stiffness: [1e5, 1e5, 1e5]", "stifness: [1e5, 1e5, 1e5]");
  expect_error("elem_key.yaml", text, "stifness", {"element 'k2'", "unknown key 'stifness'"});
}

TEST(Scene, UnknownNode) {
  const std::string text = replace(kScene, "body: shaft, node: 3", "body: shaft, node: 999");
  expect_error("node.yaml", text, "node: 999", {"marker 'a'", "999"});
}

TEST(Scene, UnknownNodeSet) {
  const std::string text = replace(kScene, "body: shaft, set: end1", "body: shaft, set: end9");
  expect_error("set.yaml", text, "set: end9", {"marker 'b'", "no node set 'end9'", "end1"});
}

TEST(Scene, InitialStateWrongSize) {
  const std::string text = replace(kScene, "q: [0.001, 0, 0, 0]", "q: [0.001, 0]");
  expect_error("initial.yaml", text, "q: [0.001, 0]",
               {"bodies[1] 'frame' initial", "'q' must have 4 values, got 2"});
}

TEST(Scene, SpinWithoutAxis) {
  const std::string text = replace(kScene, "axis: [1, 0, 0], ", "");
  expect_error("axis.yaml", text, "lof: {kind: spin", {"bodies[0] 'shaft' lof", "'axis'"});
}

TEST(Scene, UnknownIntegrator) {
  const std::string text = replace(kScene, "name: ida", "name: rk4");
  expect_error("integ.yaml", text, "name: rk4", {"integrator", "'rk4'", "ida"});
}

TEST(Scene, EndBeforeStart) {
  const std::string text = replace(kScene, "end: 0.01", "end: -1");
  expect_error("time.yaml", text, "end: -1", {"time", "'end'"});
}

TEST(Scene, UnknownChannelSource) {
  const std::string text = replace(kScene, "- {element: k1}", "- {element: k9}");
  expect_error("channel.yaml", text, "element: k9",
               {"output.channels[1]", "no element named 'k9'"});
}

TEST(Scene, YamlSyntaxError) {
  const std::string text =
      replace(kScene, "time: {start: 0, end: 0.01}", "time: {start: 0, end: [0.01}");
  ensure_frame_body();
  const std::string path = write_text("syntax.yaml", text);
  try {
    read_scene(path);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("syntax.yaml:"), std::string::npos) << e.what();
  }
}

TEST(Scene, MissingSceneFile) {
  try {
    read_scene(kDir + "no_such_scene.yaml");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no_such_scene.yaml"), std::string::npos);
  }
}
