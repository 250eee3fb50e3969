// Surface velocity and equivalent radiated power (model/surface.h,
// io/calculix_surface.cpp, post/erp_spectrum.h; docs/theory.md section 8.3).
//
// References, each derived by hand:
// - face areas and outward normals of a unit tetrahedron's faces (area 1/2 for
//   the three faces in the coordinate planes, outward = away from the fourth
//   corner), shared 1/3 per corner (3-node faces) or 1/12 per corner and 1/4 per
//   mid-side node (6-node faces);
// - ERP = rho c sum_i A_i v_n,i^2 (Fritze, Marburg & Hardtke 2009, Acta Acustica
//   u. Acustica 95: the ERP approximation, radiation efficiency 1) for nodal
//   velocities computed by hand from the modes, and v_n = w . (s x n) for a rigid
//   rotation (the velocity w x s projected on n);
// - the mean normal velocity of a run against central differences of the mean
//   normal displacement computed from the modal coordinates;
// - a harmonic component of amplitude a carries the power a^2/2 (its mean
//   square), the third-octave bands sum to the mean ERP (Parseval).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "demo_output.h"
#include "io/body_file.h"
#include "io/calculix.h"
#include "io/outputs.h"
#include "io/scene.h"
#include "model/lof.h"
#include "model/surface.h"
#include "post/erp_spectrum.h"
#include "solver/system.h"

using namespace evas;
namespace fs = std::filesystem;

namespace {

// A unit tetrahedron (mm) and faces on its x-y, x-z planes and its slanted face.
InpMesh tet_mesh(bool second_order) {
  InpMesh m;
  std::vector<Vec3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  if (second_order)  // mid-side nodes 5..10 of C3D10: 12 23 31 14 24 34
    for (auto [a, b] :
         std::vector<std::pair<int, int>>{{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}})
      p.push_back(0.5 * (p[a] + p[b]));
  m.s.resize(static_cast<Eigen::Index>(p.size()), 3);
  for (std::size_t i = 0; i < p.size(); ++i) {
    m.node_ids.push_back(static_cast<long>(i + 1));
    m.s.row(static_cast<Eigen::Index>(i)) = p[i].transpose();
    m.index[static_cast<long>(i + 1)] = static_cast<int>(i);
  }
  InpElementBlock solid;
  solid.type = second_order ? "C3D10" : "C3D4";
  solid.ids = {1};
  solid.nodes = {second_order ? std::vector<long>{1, 2, 3, 4, 5, 6, 7, 8, 9, 10}
                              : std::vector<long>{1, 2, 3, 4}};
  InpElementBlock faces;
  faces.type = second_order ? "CPS6" : "CPS3";
  faces.ids = {11, 12, 13};
  if (second_order)
    faces.nodes = {{1, 2, 3, 5, 6, 7}, {1, 4, 2, 8, 9, 5}, {2, 3, 4, 6, 10, 9}};
  else
    faces.nodes = {{1, 2, 3}, {1, 4, 2}, {2, 3, 4}};  // z = 0 listed with normal +z (inward)
  m.elements = {solid, faces};
  m.element_sets["bottom"] = {11};
  m.element_sets["front"] = {12};
  m.element_sets["slant"] = {13};
  m.element_sets["volume"] = {1};
  return m;
}

int row_of(const SurfaceSet& s, long id) {
  for (std::size_t i = 0; i < s.nodes.size(); ++i)
    if (s.nodes[i] == id) return static_cast<int>(i);
  ADD_FAILURE() << "node " << id << " is not in the set";
  return 0;
}

}  // namespace

TEST(SurfaceErp, MeshFacesGiveAreasAndOutwardNormals) {
  const auto s = mesh_surfaces(tet_mesh(false), unit_system("mm-t-s"), "tet.inp");
  ASSERT_EQ(s.size(), 3u);  // the volume's element set is no surface
  const SurfaceSet& bottom = s.at("bottom");
  ASSERT_EQ(bottom.nodes, (std::vector<long>{1, 2, 3}));
  EXPECT_NEAR(bottom.total_area(), 0.5e-6, 1e-20);  // 1/2 mm^2 in m^2
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(bottom.area[i], 0.5e-6 / 3, 1e-20);
    EXPECT_NEAR((bottom.normal.row(i).transpose() - Vec3(0, 0, -1)).norm(), 0.0, 1e-15);
  }
  const SurfaceSet& front = s.at("front");
  EXPECT_NEAR((front.normal.row(0).transpose() - Vec3(0, -1, 0)).norm(), 0.0, 1e-15);
  const SurfaceSet& slant = s.at("slant");
  EXPECT_NEAR(slant.total_area(), std::sqrt(3.0) / 2 * 1e-6, 1e-18);
  EXPECT_NEAR((slant.normal.row(0).transpose() - Vec3(1, 1, 1).normalized()).norm(), 0.0, 1e-15);
}

TEST(SurfaceErp, SixNodeFacesShareTheirAreaOneTwelfthAndOneQuarter) {
  const auto s = mesh_surfaces(tet_mesh(true), unit_system("SI"), "tet10.inp");
  const SurfaceSet& bottom = s.at("bottom");
  ASSERT_EQ(bottom.nodes.size(), 6u);
  EXPECT_NEAR(bottom.total_area(), 0.5, 1e-15);
  EXPECT_NEAR(bottom.area[row_of(bottom, 1)], 0.5 / 12, 1e-15);
  EXPECT_NEAR(bottom.area[row_of(bottom, 5)], 0.5 / 4, 1e-15);
}

TEST(SurfaceErp, AFaceWithNoSolidBehindItIsRefused) {
  InpMesh m = tet_mesh(false);
  m.elements[1].nodes[0] = {1, 2, 4};  // "bottom" now names the face of "front" again...
  m.elements[1].nodes[1] = {2, 3, 4};  // ... and a face no solid has:
  m.node_ids.push_back(5);
  m.s.conservativeResize(5, 3);
  m.s.row(4) << 1, 1, 0;
  m.index[5] = 4;
  m.elements[1].nodes[2] = {2, 3, 5};
  try {
    mesh_surfaces(m, unit_system("SI"), "bad.inp");
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string w = e.what();
    EXPECT_NE(w.find("bad.inp: element 13 of surface set 'slant' is a face of no solid element"),
              std::string::npos)
        << w;
  }
}

namespace {

// Three nodes at the unit points, modes given per node (the same
// displacement at every node for mode k when `same` says so, else (i, 2, -1)
// at node i), and the set of the three with areas 0.1, 0.2, 0.3 and normals
// y, z, x.
ModalBody three_nodes(const std::vector<bool>& same) {
  ModalBody b;
  b.name = "plate";
  b.s.resize(3, 3);
  b.s << 1, 0, 0, 0, 1, 0, 0, 0, 1;
  b.node_ids = {1, 2, 3};
  b.modes.resize(9, static_cast<Eigen::Index>(same.size()));
  for (int i = 0; i < 3; ++i)
    for (std::size_t k = 0; k < same.size(); ++k)
      b.modes.block<3, 1>(3 * i, static_cast<Eigen::Index>(k)) =
          same[k] ? Vec3(0, 0.5, 0) : Vec3(i, 2, -1);
  return b;
}

SurfaceSet three_node_set() {
  SurfaceSet set;
  set.nodes = {1, 2, 3};
  set.area = Vec3(0.1, 0.2, 0.3);
  set.normal.resize(3, 3);
  set.normal << 0, 1, 0, 0, 0, 1, 1, 0, 0;
  return set;
}

}  // namespace

TEST(SurfaceErp, NormalVelocityAndErpByHand) {
  // three nodes, one mode: node i moves with phi_i = (i, 2, -1) per unit q
  const ModalBody b = three_nodes({false});
  const SurfaceSet set = three_node_set();
  const double rho_c = 413.0;
  SurfaceRadiation sr(b, set, rho_c, true, "test");
  const double qdot = 0.7;
  // by hand: v_n = n . phi qdot = (2, -1, 2) * 0.7
  const double vn[3] = {2 * qdot, -1 * qdot, 2 * qdot};
  LofState fixed;
  std::vector<double> out(static_cast<std::size_t>(sr.values()));
  sr.evaluate(fixed, &qdot, out.data());
  const double A = 0.6,
               erp = rho_c * (0.1 * vn[0] * vn[0] + 0.2 * vn[1] * vn[1] + 0.3 * vn[2] * vn[2]);
  EXPECT_NEAR(out[0], (0.1 * vn[0] + 0.2 * vn[1] + 0.3 * vn[2]) / A, 1e-15);
  EXPECT_NEAR(out[1], std::sqrt(erp / (rho_c * A)), 1e-14);
  EXPECT_NEAR(out[2], erp, 1e-12 * erp);
  double sum = 0.0;
  for (int k = 0; k < sr.components(); ++k) sum += out[5 + k] * out[5 + k];
  EXPECT_NEAR(sum, erp, 1e-12 * erp);
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(out[5 + sr.components() + sr.elastic_components() + i], vn[i], 1e-15);
  // a rigid rotation of the frame about z at 5 rad/s and a drift along y:
  // v_n,i = n_i . (v + w x s_i)
  LofState turning;
  turning.w_GL_G = Vec3(0, 0, 5);
  turning.v_GL = Vec3(0, 0.3, 0);
  const double still = 0.0;
  sr.evaluate(turning, &still, out.data());
  for (int i = 0; i < 3; ++i) {
    const Vec3 s = b.s.row(i).transpose(), n = set.normal.row(i).transpose();
    EXPECT_NEAR(out[5 + sr.components() + sr.elastic_components() + i],
                n.dot(turning.v_GL + turning.w_GL_G.cross(s)), 1e-15);
  }
}

// The rigid/elastic split (model/surface.h): a body moving rigidly (its
// frame, and its explicit rigid modes) radiates nothing in the elastic ERP and
// all of its ERP in the rigid one; its deformation alone the other way round.
TEST(SurfaceErp, RigidBodyMotionRadiatesNoElasticPower) {
  // mode 0: a rigid translation along y (0.5 at every node); mode 1: a deformation
  ModalBody b = three_nodes({true, false});
  b.kinds = {ModeKind::Rigid, ModeKind::Elastic};
  const SurfaceSet set = three_node_set();
  SurfaceRadiation sr(b, set, 413.0, false, "test");
  ASSERT_EQ(sr.values(), 5 + sr.components() + sr.elastic_components());
  std::vector<double> out(static_cast<std::size_t>(sr.values()));
  auto elastic_sum = [&] {
    double e = 0.0;
    for (int k = 0; k < sr.elastic_components(); ++k) {
      const double c = out[static_cast<std::size_t>(5 + sr.components() + k)];
      e += c * c;
    }
    return e;
  };
  // rigid: the frame turns and drifts, the rigid mode moves, the elastic one not
  LofState moving;
  moving.w_GL_G = Vec3(0.3, -2, 5);
  moving.v_GL = Vec3(0.1, 0.3, -0.2);
  const double rigid_only[2] = {1.7, 0.0};
  sr.evaluate(moving, rigid_only, out.data());
  ASSERT_GT(out[2], 0.0);
  EXPECT_EQ(out[3], 0.0);                       // erp_elastic
  EXPECT_NEAR(out[4], out[2], 1e-14 * out[2]);  // erp_rigid = erp
  EXPECT_EQ(elastic_sum(), 0.0);
  // elastic: the frame still, the deformation only
  const double elastic_only[2] = {0.0, 0.7};
  sr.evaluate(LofState{}, elastic_only, out.data());
  ASSERT_GT(out[2], 0.0);
  EXPECT_NEAR(out[3], out[2], 1e-14 * out[2]);
  EXPECT_EQ(out[4], 0.0);
  EXPECT_NEAR(elastic_sum(), out[3], 1e-14 * out[3]);
  // both: each part is what it is alone; their sum differs by the cross term
  const double both[2] = {1.7, 0.7};
  sr.evaluate(moving, both, out.data());
  std::vector<double> alone(out.size());
  sr.evaluate(moving, rigid_only, alone.data());
  EXPECT_NEAR(out[4], alone[4], 1e-14 * alone[4]);
  sr.evaluate(LofState{}, elastic_only, alone.data());
  EXPECT_NEAR(out[3], alone[3], 1e-14 * alone[3]);
}

TEST(SurfaceErp, MeanNormalVelocityMatchesDifferencesOfTheModalDisplacement) {
  // the demo's frame (fixed LOF), set section5 facing +z with 0.01 m^2 in all
  const std::string text = test_scenes::demo_with_output(
      "output:\n  step: 1e-5\n  channels:\n"
      "    - {surface: section5, body: frame, name: skin, normal: [0, 0, 1], area: 0.01}\n"
      "    - {modal: frame}\n",
      "0.004");
  const Scene scene = parse_scene(text, test_scenes::kDemo);
  run::MemorySink sink;
  const run::Outcome o = test_scenes::run_tight(scene, sink);
  ASSERT_TRUE(o.completed()) << o.message;
  const ModalBody& body = *scene.model->bodies()[scene.model->find_body("frame")].data;
  const std::vector<int> rows = body.node_indices(body.node_sets.at("section5"));
  // mean normal displacement per unit modal coordinate: d = g . q
  Vec g = Vec::Zero(body.num_modes());
  for (int r : rows) g += body.modes.row(3 * r + 2).transpose() / static_cast<double>(rows.size());
  const auto& ch = sink.channels();
  auto col = [&](const std::string& n) {
    for (std::size_t i = 0; i < ch.size(); ++i)
      if (ch[i].name == n) return static_cast<int>(i);
    ADD_FAILURE() << "no channel " << n;
    return 0;
  };
  auto at = [&](std::size_t row, int c) {
    return sink
        .values()[row * static_cast<std::size_t>(sink.width()) + static_cast<std::size_t>(c)];
  };
  const int vm = col("skin.vn_mean"), q0 = col("frame.q0");
  const auto& t = sink.times();
  double worst = 0.0, scale = 0.0;
  for (std::size_t k = 1; k + 1 < t.size(); ++k) {
    auto d = [&](std::size_t j) {
      double x = 0.0;
      for (int m = 0; m < body.num_modes(); ++m) x += g[m] * at(j, q0 + m);
      return x;
    };
    const double fd = (d(k + 1) - d(k - 1)) / (t[k + 1] - t[k - 1]);
    worst = std::max(worst, std::abs(fd - at(k, vm)));
    scale = std::max(scale, std::abs(at(k, vm)));
  }
  ASSERT_GT(scale, 1e-4);  // the frame does vibrate
  EXPECT_LT(worst, 2e-3 * scale) << worst << " against " << scale;
}

TEST(SurfaceErp, SpectrumGivesTheHarmonicsPowerAndBandsSumToTheMean) {
  // 1024 samples at 10 kHz; components at bins 50 and 200 (488 and 1953 Hz)
  const int n = 1024;
  const double fs = 1e4;
  std::vector<double> t(n), c0(n), c1(n);
  const double f0 = 50 * fs / n, f1 = 200 * fs / n;
  for (int i = 0; i < n; ++i) {
    t[i] = i / fs;
    c0[i] = 3.0 * std::sin(2 * M_PI * f0 * t[i]);
    c1[i] = 0.5 * std::cos(2 * M_PI * f1 * t[i]) + 0.2 * std::sin(2 * M_PI * f0 * t[i]);
  }
  TimeSpectrumOptions o;
  o.window = "rectangular";
  std::vector<ErpBand> bands;
  const ErpSpectrum s = erp_spectrum(t, {c0, c1}, o, &bands);
  EXPECT_NEAR(s.power[50], 0.5 * (9.0 + 0.04), 1e-10);
  EXPECT_NEAR(s.power[200], 0.5 * 0.25, 1e-10);
  EXPECT_NEAR(s.mean, 0.5 * (9.0 + 0.25 + 0.04), 1e-10);
  double sum = 0.0;
  for (const ErpBand& b : bands) sum += b.power;
  EXPECT_NEAR(sum, s.mean, 1e-9);
  EXPECT_NEAR(erp_level(1e-12), 0.0, 1e-12);
  EXPECT_NEAR(erp_level(1.0), 120.0, 1e-12);
}

TEST(SurfaceErp, BodyFilesKeepTheSurfaceSets) {
  const auto s = mesh_surfaces(tet_mesh(false), unit_system("SI"), "tet.inp");
  ModalBody b;
  b.name = "tet";
  b.node_ids = {1, 2, 3, 4};
  b.s = tet_mesh(false).s;
  std::vector<Triplet> tr;
  for (int i = 0; i < 4; ++i) tr.emplace_back(i, i, 0.25);
  b.mass.resize(4, 4);
  b.mass.setFromTriplets(tr.begin(), tr.end());
  b.modes = Mat::Zero(12, 1);
  for (int i = 0; i < 4; ++i) b.modes(3 * i + 2, 0) = 1.0;
  b.eigenvalues = Vec::Zero(1);
  b.damping = Vec::Zero(1);
  b.kinds = {ModeKind::Rigid};
  b.node_sets["bottom"] = {1, 2, 3};
  b.surfaces["bottom"] = s.at("bottom");
  const fs::path path =
      fs::temp_directory_path() / ("evas_surface_" + std::to_string(::getpid()) + ".h5");
  write_body_file(path.string(), b);
  const ModalBody r = read_body_file(path.string());
  fs::remove(path);
  ASSERT_EQ(r.surfaces.count("bottom"), 1u);
  const SurfaceSet& x = r.surfaces.at("bottom");
  EXPECT_EQ(x.nodes, s.at("bottom").nodes);
  EXPECT_EQ((x.area - s.at("bottom").area).norm(), 0.0);
  EXPECT_EQ((x.normal - s.at("bottom").normal).norm(), 0.0);
}

TEST(SurfaceErp, SceneErrorsNameWhatIsThere) {
  auto error_of = [](const std::string& request) {
    try {
      parse_scene(
          test_scenes::demo_with_output("output:\n  channels:\n    - " + request + "\n", "0.001"),
          test_scenes::kDemo);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error_of("{surface: section5, body: frame}")
                .find("holds no areas and normals for set 'section5' (it holds them for: no set"),
            std::string::npos);
  EXPECT_NE(error_of("{surface: nowhere, body: frame, normal: [0, 0, 1], area: 1}")
                .find("has no node set 'nowhere' (known: "),
            std::string::npos);
  EXPECT_NE(error_of("{surface: section5, body: framework, normal: [0, 0, 1], area: 1}")
                .find("no body named 'framework' (known: shaft, frame)"),
            std::string::npos);
  EXPECT_NE(error_of("{surface: section5, body: frame, normal: [0, 0, 0], area: 1}")
                .find("'normal' must not be zero"),
            std::string::npos);
  EXPECT_NE(error_of("{surface: section5, body: frame, normal: [0, 0, 1], areas: [1, 2]}")
                .find("'areas' must list one area [m^2] per node of set 'section5'"),
            std::string::npos);
  EXPECT_NE(error_of("{surface: section5, body: frame, normal: [0, 0, 1], area: 1, rho_c: -4}")
                .find("'rho_c' = -4 must be > 0"),
            std::string::npos);
}
