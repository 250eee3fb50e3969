// Torsional-vibration channels ({torsion: [A, B]}, io/outputs.h): on a hand-made
// body of two rings whose modes are a rigid rotation about the axis, a twist
// (the rings turning opposite ways), a translation and a rotation about a cross
// axis, each marker's angle about the axis is known by hand from the modal
// coordinates; on the demo's spinning shaft the twist rate matches central
// differences of the twist angle; and the input errors name what is there.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "demo_output.h"
#include "integrators/integrator.h"
#include "integrators/settings.h"
#include "io/outputs.h"
#include "io/scene.h"
#include "run/run.h"
#include "run/sink.h"
#include "solver/system.h"

using namespace evas;

namespace {

// Two rings of four unit masses (radius r, in y-z planes at x = 0 and x = 1),
// sets "A" and "B". Modes: 0 rigid rotation about x; 1 twist (A by -1, B by +1
// rad per unit coordinate); 2 ring B moving along y; 3 ring B turning about y
// (about its own centre).
std::shared_ptr<ModalBody> two_rings(double r = 0.1) {
  auto b = std::make_shared<ModalBody>();
  b->name = "rings";
  const int N = 8;
  b->s.resize(N, 3);
  std::vector<Triplet> t;
  for (int i = 0; i < N; ++i) {
    const double a = M_PI / 2 * (i % 4), x = i < 4 ? 0.0 : 1.0;
    b->node_ids.push_back(i + 1);
    b->s.row(i) << x, r * std::cos(a), r * std::sin(a);
    t.emplace_back(i, i, 1.0);
  }
  b->mass.resize(N, N);
  b->mass.setFromTriplets(t.begin(), t.end());
  b->modes = Mat::Zero(3 * N, 4);
  for (int i = 0; i < N; ++i) {
    const Vec3 s = b->s.row(i).transpose();
    const Vec3 about_x = Vec3::UnitX().cross(s);
    b->modes.block<3, 1>(3 * i, 0) = about_x;
    b->modes.block<3, 1>(3 * i, 1) = (i < 4 ? -1.0 : 1.0) * about_x;
    if (i >= 4) {
      b->modes.block<3, 1>(3 * i, 2) = Vec3::UnitY();
      b->modes.block<3, 1>(3 * i, 3) = Vec3::UnitY().cross(s - Vec3(1, 0, 0));
    }
  }
  b->eigenvalues = Vec(4);
  b->eigenvalues << 0.0, 1e4, 2e4, 3e4;
  b->damping = Vec::Zero(4);
  b->kinds = {ModeKind::Rigid, ModeKind::Elastic, ModeKind::Elastic, ModeKind::Elastic};
  b->node_sets["A"] = {1, 2, 3, 4};
  b->node_sets["B"] = {5, 6, 7, 8};
  return b;
}

// The six torsion channels at (q, v) of the one body.
std::vector<double> torsion_values(const Lof& lof, const Vec3& axis, const Vec& q, const Vec& v) {
  Model model;
  auto body = two_rings();
  model.add_body("rings", body, lof);
  const int a = model.add_marker(make_set_marker("a", 0, *body, body->node_sets.at("A"), {}));
  const int b = model.add_marker(make_set_marker("b", 0, *body, body->node_sets.at("B"), {}));
  System sys(model);
  OutputSpec spec;
  spec.step = 1e-3;
  ChannelRequest req;
  req.kind = ChannelRequest::Kind::Torsion;
  req.name = "tv";
  req.index = a;
  req.index2 = b;
  req.axis = axis;
  spec.channels = {req};
  OutputSet out(spec, sys, 0.0, 0.01);
  EXPECT_EQ(out.size(), 6);
  EXPECT_EQ(out.channels()[2].name, "tv.twist");
  EXPECT_EQ(out.channels()[2].unit, "rad");
  EXPECT_EQ(out.channels()[5].name, "tv.twist_rate");
  EXPECT_EQ(out.channels()[5].unit, "rad/s");
  std::vector<double> y(6);
  out.values(0.004, q.data(), v.data(), y.data());
  return y;
}

using test_scenes::kDemo;

std::string demo_with_output(const std::string& output) {
  return test_scenes::demo_with_output(output, "0.004");
}

// A generated beam spinning at 200 rad/s (`lof` the spin LOF's axis and
// placement), markers `left` (named as given) and `right` on its end sets,
// and one output request; the request is on line 13.
std::string beam_scene(const std::string& lof, const std::string& left,
                       const std::string& request) {
  return "name: rings\nbodies:\n  - name: shaft\n"
         "    generate: {type: truss-beam, segments: 6, length: 0.6, width: 0.05}\n"
         "    modes: {rigid: false, elastic: 8}\n"
         "    lof: {kind: spin, " +
         lof +
         ", speed: 200}\n"
         "markers:\n  - {name: " +
         left +
         ", body: shaft, set: end0}\n"
         "  - {name: right, body: shaft, set: end1}\n"
         "time: {start: 0, end: 0.01}\noutput:\n  channels:\n    - " +
         request + "\n";
}

}  // namespace

TEST(TorsionChannels, AnglesAndRatesAboutTheSpinAxisByHand) {
  // angle_a = q0 - q1, angle_b = q0 + q1 (the translation and the cross
  // rotation of ring B add nothing about x); the same with v for the rates
  Vec q(4), v(4);
  q << 0.003, -0.002, 0.5, 0.7;
  v << 0.4, 0.25, -3.0, 9.0;
  const Lof spin_x = Lof::spin(Vec3::Zero(), Mat3::Identity(), Vec3::UnitX(), 0.0, {0.0}, {300.0});
  const auto y = torsion_values(spin_x, Vec3::UnitX(), q, v);
  EXPECT_NEAR(y[0], q[0] - q[1], 1e-15);
  EXPECT_NEAR(y[1], q[0] + q[1], 1e-15);
  EXPECT_NEAR(y[2], 2.0 * q[1], 1e-15);
  EXPECT_NEAR(y[3], v[0] - v[1], 1e-14);
  EXPECT_NEAR(y[4], v[0] + v[1], 1e-14);
  EXPECT_NEAR(y[5], 2.0 * v[1], 1e-14);
  // about the cross axis y only ring B's own rotation counts
  const auto c = torsion_values(spin_x, Vec3::UnitY(), q, v);
  EXPECT_NEAR(c[0], 0.0, 1e-15);
  EXPECT_NEAR(c[1], q[3], 1e-15);
  EXPECT_NEAR(c[2], q[3], 1e-15);
  EXPECT_NEAR(c[5], v[3], 1e-14);
}

TEST(TorsionChannels, TheDefaultAxisIsTheSpinAxisInTheBodysAxes) {
  // a body whose x axis is turned onto G's z, spinning about G's z: the parser
  // takes the twist axis as the body's x (R_GL0^T z), and the values follow
  const std::string scene =
      beam_scene("axis: [0, 0, 1], origin: [0, 0, 0], rotation: [0, -1.5707963267948966, 0]",
                 "left", "{torsion: [left, right], name: tv}");
  const Scene s = parse_scene(scene, "rings.yaml");
  ASSERT_EQ(s.output.channels.size(), 1u);
  const ChannelRequest& r = s.output.channels[0];
  EXPECT_EQ(r.kind, ChannelRequest::Kind::Torsion);
  EXPECT_EQ(r.name, "tv");
  EXPECT_NEAR(std::abs(r.axis.x()), 1.0, 1e-12) << r.axis.transpose();
  EXPECT_NEAR(r.axis.y(), 0.0, 1e-12);
  EXPECT_NEAR(r.axis.z(), 0.0, 1e-12);
  // the axis as the spin sees it: R_GL0 axis = G's z
  const Vec3 g = s.model->bodies()[0].lof.at(0.0).R_GL * r.axis;
  EXPECT_NEAR(g.z(), 1.0, 1e-12);
}

TEST(TorsionChannels, TwistRateMatchesDifferencesOfTheTwistOnTheDemoShaft) {
  const Scene scene =
      parse_scene(demo_with_output("output:\n  grid: time\n  step: 2e-6\n  channels:\n"
                                   "    - {torsion: [shaft_left, shaft_right]}\n"),
                  kDemo);
  run::MemorySink sink;
  const run::Outcome o = test_scenes::run_tight(scene, sink);
  ASSERT_TRUE(o.completed()) << o.message;
  ASSERT_EQ(sink.width(), 6);
  EXPECT_EQ(sink.channels()[2].name, "twist_shaft_left_shaft_right.twist");
  const auto& t = sink.times();
  const auto row = [&](std::size_t i) { return &sink.values()[i * 6]; };
  ASSERT_GT(t.size(), 1000u);
  double worst = 0.0, scale = 0.0;
  for (std::size_t i = 1; i + 1 < t.size(); ++i) {
    const double fd = (row(i + 1)[2] - row(i - 1)[2]) / (t[i + 1] - t[i - 1]);
    worst = std::max(worst, std::abs(fd - row(i)[5]));
    scale = std::max(scale, std::abs(row(i)[5]));
    EXPECT_DOUBLE_EQ(row(i)[2], row(i)[1] - row(i)[0]);
  }
  std::printf("  twist rate against d(twist)/dt: largest difference %.3e of max %.4e rad/s\n",
              worst / scale, scale);
  ASSERT_GT(scale, 0.0) << "the shaft does not twist: the check would be empty";
  EXPECT_LT(worst, 1e-3 * scale) << "worst " << worst << " of " << scale;
}

TEST(TorsionChannels, BadRequestsNameWhatIsThere) {
  struct Bad {
    std::string request, says;
  };
  for (const Bad& b : std::vector<Bad>{
           {"{torsion: [shaft_left, nowhere]}", "no marker named 'nowhere' (known: shaft_left"},
           {"{torsion: [shaft_left, frame_left]}", "on different bodies ('shaft', 'frame')"},
           {"{torsion: [shaft_left, ground_left]}", "is on the ground"},
           {"{torsion: [shaft_left, shaft_left]}", "the two markers are the same"},
           {"{torsion: shaft_left}", "must list two markers on one body"},
           {"{torsion: [frame_left, frame_right]}", "has no spin LOF to take the twist axis"},
           {"{torsion: [shaft_left, shaft_right], axis: [0, 0, 0]}", "'axis' must not be zero"},
           {"{torsion: [shaft_left, shaft_right], quantities: [position]}", "unknown key"},
           {"{marker: shaft_left, axis: [1, 0, 0]}", "belong to a torsion request"},
           {"{torsion: [shaft_left, shaft_right], name: 'a b'}", "without spaces"}}) {
    SCOPED_TRACE(b.request);
    try {
      parse_scene(demo_with_output("output:\n  channels:\n    - " + b.request + "\n"), kDemo);
      ADD_FAILURE() << "accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(b.says), std::string::npos) << e.what();
    }
  }
  // two requests under one name
  try {
    parse_scene(demo_with_output("output:\n  channels:\n"
                                 "    - {torsion: [shaft_left, shaft_right], name: tv}\n"
                                 "    - {torsion: [shaft_left, shaft_mid], name: tv}\n"),
                kDemo);
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("give each torsion request its own 'name'"),
              std::string::npos)
        << e.what();
  }
}

TEST(TorsionChannels, NamesThatCannotBeChannelNamesAreRefused) {
  // markers whose names make the default name no word: 'name' is asked for
  const std::string scene =
      beam_scene("axis: [1, 0, 0], origin: [0, 0, 0]", "le.ft", "{torsion: [le.ft, right]}");
  try {
    parse_scene(scene, "rings.yaml");
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("the default name 'twist_le.ft_right'"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("rings.yaml:13"), std::string::npos) << e.what();
  }
  // a torsion request named like the engine's motor: dyno.twist twice
  std::ifstream f(std::string(EVAS_SOURCE_DIR) + "/validation/engine/engine.yaml");
  std::stringstream ss;
  ss << f.rdbuf();
  const std::string engine = ss.str() + "    - {torsion: [j1, fw], name: dyno}\n";
  const Scene s =
      parse_scene(engine, std::string(EVAS_SOURCE_DIR) + "/validation/engine/engine.yaml");
  System sys(*s.model);
  try {
    OutputSet out(s.output, sys, s.t_start, s.t_end);
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("two channels are named 'dyno.twist'"), std::string::npos)
        << e.what();
  }
}
