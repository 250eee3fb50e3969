// Every force element of the paper is usable from a scene file (issue: "usable
// from a scene file, with bad parameters rejected by a clear error naming the
// element and the parameter"): one scene with a spinning crank and a block on
// mounts, carrying all element types, is read, run briefly with IDA, and every
// element's output channels stay finite; then one bad parameter per element type.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <random>

#include "integrators/integrator.h"
#include "io/outputs.h"
#include "io/scene.h"

using namespace evas;

namespace {

const std::string kDir = [] {
  const std::string d =
      ::testing::TempDir() + "evas_scene_elements_" + std::to_string(::getpid()) + "/";
  std::filesystem::create_directories(d + "data");
  // The pressure table is referenced relative to the scene file.
  std::filesystem::copy_file(
      std::string(EVAS_SOURCE_DIR) + "/validation/data/cylinder_pressure_3000rpm.txt",
      d + "data/p.txt", std::filesystem::copy_options::overwrite_existing);
  return d;
}();

const std::string kScene = R"(
name: all-elements
gravity: [0, 0, -9.81]
bodies:
  - name: crank
    generate: {type: truss-beam, segments: 6, length: 0.6, width: 0.15, area: 5e-4}
    modes: {rigid: true, elastic: 4}
    damping_ratio: 0.02
    lof: {kind: spin, axis: [1, 0, 0], origin: [0, 0, 0], speed: 314.159}
  - name: block
    generate: {type: truss-beam, segments: 6, length: 0.6, width: 0.2, area: 2e-3}
    modes: {rigid: true, elastic: 4}
    damping_ratio: 0.02
    lof: {kind: fixed, origin: [0, 0, 0]}
markers:
  - {name: j0, body: crank, set: end0}
  - {name: j1, body: crank, set: end1}
  - {name: pin, body: crank, set: section3}
  # bearing axes: marker z along the crank axis x (rotation of 90 deg about y)
  - {name: b0, body: block, set: end0, rotation: [0, 1.5707963267948966, 0]}
  - {name: b1, body: block, set: end1, rotation: [0, 1.5707963267948966, 0]}
  - {name: liner, body: block, set: section3}
  - {name: head, body: block, set: section4}
  - {name: g0, ground: [0, 0, 0]}
  - {name: g1, ground: [0.6, 0, 0]}
  - {name: idler1, ground: [0.6, 0.15, 0.1]}
  - {name: idler2, ground: [0.6, -0.1, 0.2]}
elements:
  - {name: main0, type: journal-bearing, markers: [b0, j0], radius: 0.03, width: 0.04,
     clearance: 3e-5, viscosity: 0.02, halves: 2, eps_max: 0.9, contact_stiffness: 1e10}
  - {name: main1, type: journal-bearing, markers: [b1, j1], radius: 0.03, width: 0.04,
     clearance: 3e-5, viscosity: 0.02, method: quadrature, eps_max: 0.9, contact_stiffness: 1e10}
  - {name: cyl1, type: piston-conrod, markers: [pin, liner, head], crank_radius: 0.0575,
     conrod_length: 0.18, bore: 0.02, piston_mass: 1.5, conrod_reciprocating_mass: 0.5,
     speed: 314.159, pressure_file: data/p.txt, crankcase_pressure: 1e5}
  - {name: dyno, type: motor, markers: [j0, g0], speed: 314.159, stiffness: 2e4, damping: 5}
  - {name: mount0, type: engine-mount, markers: [g0, b0], k_x: [1e6], k_y: [1e6],
     k_z: [2e6, 0, 1e9], damping: [200, 200, 200]}
  - {name: mount1, type: engine-mount, markers: [g1, b1], k_x: [1e6], k_y: [1e6], k_z: [2e6],
     damping: [200, 200, 200]}
  - {name: thrust, type: thrust-bearing, markers: [b0, j0], gap: 1e-4, stiffness: [1e8],
     smoothing: 1e-5, damping: 100}
  - {name: timing, type: belt, markers: [j1, idler1, idler2], tension: 300,
     radii: [0.06, 0.04, 0.04], normal: [1, 0, 0]}
integrator: {name: ida, rtol: 1e-6, atol: 1e-10}
time: {start: 0, end: 0.004}
output:
  grid: time
  step: 2e-4
  channels:
    - {element: main0}
    - {element: main1}
    - {element: cyl1}
    - {element: dyno}
    - {element: mount0}
    - {element: thrust}
    - {element: timing}
)";

std::string replace(std::string s, const std::string& a, const std::string& b) {
  const auto pos = s.find(a);
  EXPECT_NE(pos, std::string::npos) << a;
  if (pos != std::string::npos) s.replace(pos, a.size(), b);
  return s;
}

}  // namespace

TEST(SceneElements, EveryElementTypeRunsFromAScene) {
  Scene scene = parse_scene(kScene, kDir + "all.yaml");
  ASSERT_EQ(scene.model->elements().size(), 8u);
  System sys(*scene.model);
  OutputSet out(scene.output, sys, scene.t_start, scene.t_end);
  auto integ = make_integrator("ida");
  Vec q, v;
  sys.initial_state(q, v);
  integ->init(sys, 0.0, q, v, scene.integrator);
  std::vector<double> times(out.times().begin() + 1, out.times().end());
  std::vector<double> row(out.size());
  int rows = 0;
  double max_gas = 0;
  integrate(*integ, sys, 0.0, times, [&](double t, const Vec& qq, const Vec& vv) {
    out.values(t, qq.data(), vv.data(), row.data());
    for (int c = 0; c < out.size(); ++c) {
      ASSERT_TRUE(std::isfinite(row[c])) << out.channels()[c].name << " at t = " << t;
      if (out.channels()[c].name == "cyl1.gas_force") max_gas = std::max(max_gas, row[c]);
    }
    ++rows;
  });
  EXPECT_EQ(rows, 20);
  // The pressure table was found relative to the scene: gas force near firing TDC
  // (0..0.004 s at 3000 rpm is 0..72 deg after firing TDC; peak ~14 MPa) on a
  // 20 mm bore is about 4.4 kN.
  EXPECT_GT(max_gas, 2e3);
  std::cout << out.size() << " channels, max gas force " << max_gas << " N, "
            << integ->stats().steps << " IDA steps\n";
}

TEST(SceneElements, BadParameterNamesElementAndParameter) {
  struct Bad {
    std::string from, to, element, param;
  };
  const std::vector<Bad> cases = {
      {"clearance: 3e-5, viscosity: 0.02, halves: 2",
       "clearance: -3e-5, viscosity: 0.02, halves: 2", "main0", "clearance"},
      {"method: quadrature", "method: exact", "main1", "method"},
      {"bore: 0.02", "bore: 0", "cyl1", "bore"},
      {"speed: 314.159, stiffness: 2e4", "speed: 314.159, stiffness: fast", "dyno", "stiffness"},
      {"damping: [200, 200, 200]}\n  - {name: mount1", "damping: [200, 200]}\n  - {name: mount1",
       "mount0", "damping"},
      {"gap: 1e-4", "gap: -1e-4", "thrust", "gap"},
      {"tension: 300", "tension: -300", "timing", "tension"},
  };
  for (const auto& c : cases) {
    const std::string text = replace(kScene, c.from, c.to);
    try {
      parse_scene(text, kDir + "bad.yaml");
      ADD_FAILURE() << "no error for " << c.to;
    } catch (const InputError& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find("bad.yaml:"), std::string::npos) << msg;
      EXPECT_NE(msg.find("element '" + c.element + "'"), std::string::npos) << msg;
      EXPECT_NE(msg.find("'" + c.param + "'"), std::string::npos) << msg;
    }
  }
  // A missing pressure file is named with the path it was looked for at.
  try {
    parse_scene(replace(kScene, "data/p.txt", "data/none.txt"), kDir + "bad.yaml");
    ADD_FAILURE() << "no error for a missing pressure file";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("none.txt"), std::string::npos) << e.what();
  }
}

TEST(SceneElements, CoupledPistonRunsFromAScene) {
  // The same engine with the piston in mode coupled: its crank angle now comes
  // from the crank's motion (spin plus torsion against the dyno's clutch spring)
  // and its reciprocating inertia is solved with the modal accelerations.
  const std::string coupled = replace(kScene, "speed: 314.159, pressure_file: data/p.txt",
                                      "mode: coupled, pressure_file: data/p.txt");
  std::map<std::string, std::vector<double>> runs[2];
  for (int k = 0; k < 2; ++k) {
    Scene scene = parse_scene(k ? coupled : kScene, kDir + "all.yaml");
    System sys(*scene.model);
    EXPECT_EQ(sys.inertia_rank(), k);
    OutputSet out(scene.output, sys, scene.t_start, scene.t_end);
    auto integ = make_integrator("ida");
    Vec q, v;
    sys.initial_state(q, v);
    integ->init(sys, 0.0, q, v, scene.integrator);
    std::vector<double> times(out.times().begin() + 1, out.times().end());
    std::vector<double> row(out.size());
    integrate(*integ, sys, 0.0, times, [&](double t, const Vec& qq, const Vec& vv) {
      out.values(t, qq.data(), vv.data(), row.data());
      for (int c = 0; c < out.size(); ++c) {
        ASSERT_TRUE(std::isfinite(row[c])) << out.channels()[c].name;
        runs[k][out.channels()[c].name].push_back(row[c]);
      }
    });
  }
  // Same crank angle up to the crank's twist and the rigid rotation on its LOF
  // (measured 0.003 deg), same conrod force up to the speed fluctuation (measured
  // 6.4 N of 11 kN).
  double dth = 0.0, dF = 0.0, Fmax = 0.0;
  const auto& a0 = runs[0]["cyl1.crank_angle"];
  const auto& a1 = runs[1]["cyl1.crank_angle"];
  const auto& F0 = runs[0]["cyl1.conrod_force"];
  const auto& F1 = runs[1]["cyl1.conrod_force"];
  ASSERT_EQ(a0.size(), 20u);
  ASSERT_EQ(a1.size(), 20u);
  for (std::size_t i = 0; i < a0.size(); ++i) {
    dth = std::max(dth, std::abs(a1[i] - a0[i]));
    dF = std::max(dF, std::abs(F1[i] - F0[i]));
    Fmax = std::max(Fmax, std::abs(F0[i]));
  }
  std::cout << "coupled vs prescribed: crank angle " << dth << " deg, conrod force " << dF
            << " N of " << Fmax << " N\n";
  EXPECT_LT(dth, 0.5);
  EXPECT_GT(dth, 0.0);
  EXPECT_LT(dF, 0.05 * Fmax);
}

// System::force() computes only the marker rows the elements declare they read
// (Element::motion_reads) and maps back only the loads they declare
// (Element::load_parts): the piston of prescribed kinematics reads none and
// puts no moment on the crankpin, the motor reads and loads only rotations, a
// mount without rotational terms only translations. A wrong declaration changes
// the residual (a piston declaring no moment on its liner: differences of up to
// 651 N), which this compares with the one from every row, at states off the
// initial one, for the scene above (every element type) and the paper's engine.
TEST(SceneElements, ResidualFromTheReadRowsEqualsTheFullOne) {
  const std::string engine = std::string(EVAS_SOURCE_DIR) + "/validation/engine/engine.yaml";
  std::vector<Scene> scenes;
  scenes.push_back(parse_scene(kScene, kDir + "all.yaml"));
  scenes.push_back(read_scene(engine));
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (Scene& scene : scenes) {
    System sys(*scene.model);
    const int n = sys.size();
    Vec q0, v0, f_full(n), f_read(n);
    sys.initial_state(q0, v0);
    for (int k = 0; k < 5; ++k) {
      Vec q = q0, v = v0;
      // modal coordinates perturbed by up to 2e-6 and their rates by up to 2e-2
      // (1e4 rad/s times the amplitude)
      for (int i = 0; i < n; ++i) {
        q[i] += 2e-6 * u(rng);
        v[i] += 2e-2 * u(rng);
      }
      const double t = 1e-3 * k;
      // the reduced residual first: what it leaves out is then from another state
      // (the last full one), never the values of this one
      sys.set_read_rows_only(true);
      sys.force(t, q.data(), v.data(), f_read.data());
      sys.set_read_rows_only(false);
      sys.force(t, q.data(), v.data(), f_full.data());
      ASSERT_TRUE(f_full.allFinite()) << scene.name;
      EXPECT_LE((f_read - f_full).lpNorm<Eigen::Infinity>(),
                1e-12 * f_full.lpNorm<Eigen::Infinity>())
          << scene.name << " at t = " << t;
    }
  }
}

// System::observe for a list of markers (what an output set's channels read)
// gives those markers the motion that observing every marker gives them.
TEST(SceneElements, ObservedMarkersMatchTheFullObservation) {
  const std::string engine = std::string(EVAS_SOURCE_DIR) + "/validation/engine/engine.yaml";
  Scene scene = read_scene(engine);
  System sys(*scene.model);
  const int n = sys.size();
  Vec q, v;
  sys.initial_state(q, v);
  q += Vec::Random(n) * 2e-6;
  v += Vec::Random(n) * 2e-2;
  const std::vector<int> some = {0, 5, 12, 16, 22, 24};  // j1, b1, p3, l3, fw, m1
  const double t = 0.0137;
  sys.observe(t, q.data(), v.data());
  std::vector<MarkerMotion> full;
  for (int m : some) full.push_back(sys.motion(m));
  sys.observe(t + 1e-3, q.data(), v.data());  // (another state in between)
  sys.observe(t, q.data(), v.data(), some);
  for (std::size_t i = 0; i < some.size(); ++i) {
    const MarkerMotion& a = full[i];
    const MarkerMotion& b = sys.motion(some[i]);
    EXPECT_LE((a.p - b.p).norm(), 1e-15 * a.p.norm() + 1e-18) << some[i];
    EXPECT_LE((a.v - b.v).norm(), 1e-14 * a.v.norm() + 1e-18) << some[i];
    EXPECT_LE((a.psi - b.psi).norm(), 1e-14 * a.psi.norm() + 1e-18) << some[i];
    EXPECT_LE((a.w - b.w).norm(), 1e-14 * a.w.norm() + 1e-18) << some[i];
    EXPECT_EQ(a.R, b.R) << some[i];
  }
}
