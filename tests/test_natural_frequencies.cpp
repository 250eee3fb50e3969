// Natural frequencies for a Campbell diagram (post/natural_frequencies.h): the
// elastic ones of every body and the six rigid-body modes of the engine on its
// mounts.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "io/body_file.h"
#include "io/scene.h"
#include "post/assembled_modes.h"
#include "post/natural_frequencies.h"
#include "solver/system.h"

using namespace evas;

namespace {

constexpr double kTwoPi = 6.283185307179586;
constexpr double kL = 0.8, kB = 0.1;                  // mounts at x = 0, L and y = +-b
constexpr double kx = 1.5e5, ky = 2.5e5, kz = 4.0e5;  // N/m per mount
constexpr double krx = 3.0e3;                         // N m/rad per mount (roll)

// A stiff truss beam along x (centre of mass at (L/2, 0, 0)) on four mounts in
// the plane of its centre of mass, symmetric about it. `mount_extra` is added
// to every mount's parameters; `mounts` false leaves the mounts out.
std::string scene_text(const std::string& mount_extra, bool mounts = true) {
  std::string s = R"(
name: block-on-mounts
gravity: [0, 0, 0]
bodies:
  - name: block
    generate: {type: truss-beam, segments: 4, length: 0.8, width: 0.2, area: 4e-3}
    modes: {rigid: true, elastic: 4}
    lof: {kind: fixed, origin: [0, 0, 0]}
markers:
  - {name: m1, body: block, set: end0, centre: [0, 0.1, 0]}
  - {name: m2, body: block, set: end0, centre: [0, -0.1, 0]}
  - {name: m3, body: block, set: end1, centre: [0.8, 0.1, 0]}
  - {name: m4, body: block, set: end1, centre: [0.8, -0.1, 0]}
  - {name: g1, ground: [0, 0.1, 0]}
  - {name: g2, ground: [0, -0.1, 0]}
  - {name: g3, ground: [0.8, 0.1, 0]}
  - {name: g4, ground: [0.8, -0.1, 0]}
)";
  if (mounts) {
    s += "elements:\n";
    for (int i = 1; i <= 4; ++i)
      s += "  - {name: mount" + std::to_string(i) + ", type: engine-mount, markers: [g" +
           std::to_string(i) + ", m" + std::to_string(i) +
           "], k_x: [1.5e5], k_y: [2.5e5], k_z: [4e5], damping: [500, 500, 500]" + mount_extra +
           "}\n";
  }
  s += "time: {start: 0, end: 0.01}\n";
  return s;
}

// The six frequencies of the body on mounts whose stiffness about its centre
// of mass is diagonal: translations kt (N/m, x, y, z), rotations kr (N m/rad,
// about x, y, z). The truss's braces make its inertia slightly non-diagonal
// (J_xz = -0.44 of J_zz = 39 kg m^2), which couples roll and yaw a little: the
// rotations are the 3 x 3 problem kr theta = omega^2 J theta (exact), and each
// lies within 0.1 % of the decoupled formula sqrt(kr_i / J_ii) / (2 pi).
void expect_modes(const std::vector<NaturalFrequency>& f, const Model& model, const Vec3& kt,
                  const Vec3& kr) {
  struct Expected {
    double hz, decoupled;
    std::string dir;
  };
  const MassProperties& mp = model.bodies()[0].mp;
  const char* dirs[6] = {"x", "y", "z", "rx", "ry", "rz"};
  std::vector<Expected> e;
  for (int i = 0; i < 3; ++i) {
    const double hz = std::sqrt(kt[i] / mp.mass) / kTwoPi;
    e.push_back({hz, hz, dirs[i]});
  }
  Eigen::GeneralizedSelfAdjointEigenSolver<Mat3> es(Mat3(kr.asDiagonal()), mp.inertia);
  for (int c = 0; c < 3; ++c) {
    int best = 0;
    es.eigenvectors().col(c).cwiseAbs2().cwiseProduct(mp.inertia.diagonal()).maxCoeff(&best);
    e.push_back({std::sqrt(es.eigenvalues()[c]) / kTwoPi,
                 std::sqrt(kr[best] / mp.inertia(best, best)) / kTwoPi, dirs[3 + best]});
  }
  std::sort(e.begin(), e.end(), [](const Expected& a, const Expected& b) { return a.hz < b.hz; });
  std::vector<NaturalFrequency> mount;
  for (const auto& x : f)
    if (x.kind == "mount") mount.push_back(x);
  ASSERT_EQ(mount.size(), 6u);
  for (int i = 0; i < 6; ++i) {
    EXPECT_NEAR(mount[i].hz, e[i].hz, 1e-9 * e[i].hz) << "mode " << i;
    EXPECT_NEAR(mount[i].hz, e[i].decoupled, 1e-3 * e[i].hz) << "mode " << i;
    EXPECT_EQ(mount[i].direction, e[i].dir) << "mode " << i;
    EXPECT_GT(mount[i].share, 0.99) << "mode " << i;  // nearly a single direction
    EXPECT_EQ(mount[i].body, "block");
    EXPECT_EQ(mount[i].mode, i);
  }
}

}  // namespace

// A rigid body of mass m on n identical mounts placed symmetrically about its
// centre of mass, in the plane of the centre of mass: the six modes uncouple,
// each translation f = sqrt(sum k / m) / (2 pi) and each rotation
// f = sqrt(sum k r^2 / J) / (2 pi), r the lever arm of the stiffness acting in
// that rotation (C. M. Harris and A. G. Piersol, Harris' Shock and Vibration
// Handbook, 5th ed., McGraw-Hill 2002, ch. 30 "Theory of vibration isolation",
// rigid body on resilient supports: the modes uncouple when the supports are
// symmetric about the centre of gravity and lie in its plane; J. P. Den Hartog,
// Mechanical Vibrations, 4th ed., Dover 1985, sec. 3.3 likewise for a body on
// springs). Here: bounce sqrt(4 kz / m), lateral sqrt(4 ky / m), fore-aft
// sqrt(4 kx / m), roll sqrt(4 kz b^2 / Jxx), pitch sqrt(4 kz (L/2)^2 / Jyy),
// yaw sqrt(4 (kx b^2 + ky (L/2)^2) / Jzz).
TEST(NaturalFrequencies, RigidBodyOnFourMountsMatchesTheTextbook) {
  const Scene scene = parse_scene(scene_text(""), "mounts.yaml");
  const Model& model = *scene.model;
  const MassProperties& mp = model.bodies()[0].mp;
  const double m = mp.mass;
  ASSERT_GT(m, 0.0);
  EXPECT_NEAR((mp.com - Vec3(kL / 2, 0, 0)).norm(), 0.0, 1e-12);
  const Mat3 J = mp.inertia;
  EXPECT_NEAR(J(0, 1), 0.0, 1e-12 * J.norm());
  EXPECT_NEAR(J(1, 2), 0.0, 1e-12 * J.norm());
  EXPECT_LT(std::abs(J(0, 2)), 0.02 * J(2, 2));
  const double a = kL / 2;
  const std::vector<NaturalFrequency> f = natural_frequencies(model, 1e6);
  expect_modes(f, model, Vec3(4 * kx, 4 * ky, 4 * kz),
               Vec3(4 * kz * kB * kB, 4 * kz * a * a, 4 * (kx * kB * kB + ky * a * a)));
  std::printf("m = %.6g kg, J = diag(%.6g, %.6g, %.6g), J_xz = %.3g kg m^2; mount modes [Hz]:", m,
              J(0, 0), J(1, 1), J(2, 2), J(0, 2));
  for (const auto& x : f)
    if (x.kind == "mount") std::printf(" %.6g (%s)", x.hz, x.direction.c_str());
  std::printf("\n");

  // the elastic modes are the body's, up to f_max
  const ModalBody& body = *model.bodies()[0].data;
  int elastic = 0;
  for (const auto& x : f)
    if (x.kind == "elastic") {
      EXPECT_EQ(x.body, "block");
      EXPECT_EQ(body.kinds[x.mode], ModeKind::Elastic);
      EXPECT_DOUBLE_EQ(x.hz, std::sqrt(body.eigenvalues[x.mode]) / kTwoPi);
      ++elastic;
    }
  EXPECT_EQ(elastic, 4);
  const std::vector<NaturalFrequency> none = natural_frequencies(model, 0.0);
  EXPECT_EQ(none.size(), 6u);  // the mount modes whatever f_max
}

// The same through the mount's orientation (mount axes turned 90 deg about z:
// mount x along G y) and its rotational stiffness (about the mount's x, now G y):
// the stiffness comes from the element, not from its parameters.
TEST(NaturalFrequencies, OrientationAndRotationalStiffnessComeFromTheElement) {
  const Scene scene = parse_scene(
      scene_text(", orientation: [0, 0, 1.5707963267948966], rot_stiffness: [3e3, 0, 0]"),
      "mounts.yaml");
  const Model& model = *scene.model;
  const double a = kL / 2;
  expect_modes(natural_frequencies(model, 1e6), model, Vec3(4 * ky, 4 * kx, 4 * kz),
               Vec3(4 * kz * kB * kB, 4 * kz * a * a + 4 * krx, 4 * (ky * kB * kB + kx * a * a)));
}

TEST(NaturalFrequencies, NoMountsNoMountModes) {
  const Scene scene = parse_scene(scene_text("", false), "mounts.yaml");
  const std::vector<NaturalFrequency> f = natural_frequencies(*scene.model, 1e6);
  EXPECT_EQ(f.size(), 4u);
  for (const auto& x : f) EXPECT_EQ(x.kind, "elastic");
  EXPECT_TRUE(mount_modes(*scene.model).hz.empty());
  EXPECT_THROW(natural_frequencies(*scene.model, -1.0), InputError);
}

// The validation engine: the block and the crankshaft as one rigid body on its
// four mounts (k = 1.5e5 / 1.5e5 / 3e5 N/m): six positive, finite frequencies in
// the usual range of engine mounting systems; the crank's elastic frequencies
// are those of its body file.
TEST(NaturalFrequencies, ValidationEngine) {
  const std::string dir = std::string(EVAS_SOURCE_DIR) + "/validation/";
  const Scene scene = read_scene(dir + "engine/engine.yaml");
  const Model& model = *scene.model;
  const double f_max = 2500.0;
  const std::vector<NaturalFrequency> f = natural_frequencies(model, f_max, scene.t_start);
  const MountModes mm = mount_modes(model, scene.t_start);
  EXPECT_EQ(mm.bodies.size(), 2u);  // block and crank
  EXPECT_EQ(mm.mounts.size(), 4u);
  std::printf("engine: mass %.6g kg, centre of mass (%.4g, %.4g, %.4g) m\n", mm.mass, mm.point.x(),
              mm.point.y(), mm.point.z());
  int mounts = 0;
  for (const auto& x : f)
    if (x.kind == "mount") {
      ++mounts;
      EXPECT_EQ(x.body, "block");
      EXPECT_TRUE(std::isfinite(x.hz));
      EXPECT_GT(x.hz, 1.0);
      EXPECT_LT(x.hz, 40.0);
      std::printf("  mount mode %d: %.4g Hz, %s (%.0f %%)\n", x.mode, x.hz, x.direction.c_str(),
                  100 * x.share);
    }
  EXPECT_EQ(mounts, 6);

  const ModalBody crank = read_body_file(dir + "bodies/crankshaft.h5");
  std::vector<double> file_hz, scene_hz;
  for (int k = 0; k < crank.num_modes(); ++k)
    if (crank.kinds[k] == ModeKind::Elastic && std::sqrt(crank.eigenvalues[k]) / kTwoPi <= f_max)
      file_hz.push_back(std::sqrt(crank.eigenvalues[k]) / kTwoPi);
  for (const auto& x : f)
    if (x.kind == "elastic" && x.body == "crank") scene_hz.push_back(x.hz);
  ASSERT_FALSE(file_hz.empty());
  ASSERT_EQ(scene_hz.size(), file_hz.size());
  for (std::size_t i = 0; i < file_hz.size(); ++i)
    EXPECT_NEAR(scene_hz[i], file_hz[i], 1e-9 * file_hz[i]);
}

// The assembled system's modes (post/assembled_modes.h) of the same block on
// its four mounts, from the linearized equations of the whole model (the
// truss's elastic modes included), against the rigid engine of mount_modes():
// six modes labelled "mount", their undamped frequencies |lambda| / (2 pi)
// within 0.5 % (the truss's elastic compliance lowers them a little), and the
// vertical one's damping ratio that of a single degree of freedom,
// zeta = c / (2 sqrt(k m)) with k = 4 k_z, c = 4 x 500 N s/m.
TEST(NaturalFrequencies, AssembledModesOfTheBlockOnItsMounts) {
  const Scene scene = parse_scene(scene_text(""), "mounts.yaml");
  const Model& model = *scene.model;
  const MountModes mm = mount_modes(model);
  ASSERT_EQ(mm.hz.size(), 6u);
  System sys(*scene.model);
  Vec q, v;
  sys.initial_state(q, v);
  Vec qv(2 * q.size());
  qv << q, v;
  const AssembledModes am = assembled_modes(sys, model, {0.0}, {qv}, 200.0);
  ASSERT_TRUE(am.reason.empty()) << am.reason;
  std::vector<const AssembledMode*> mount;
  for (const AssembledMode& m : am.modes)
    if (m.where == "mount") mount.push_back(&m);
  ASSERT_EQ(mount.size(), 6u);
  for (std::size_t i = 0; i < 6; ++i) {
    const double zeta = mount[i]->damping_ratio;
    const double undamped = mount[i]->hz / std::sqrt(1.0 - zeta * zeta);
    EXPECT_NEAR(undamped / mm.hz[i], 1.0, 5e-3) << mount[i]->label;
    EXPECT_EQ(mount[i]->label.rfind("mount: block rigid ", 0), 0u) << mount[i]->label;
  }
  const double m = mm.mass, zeta_z = 4.0 * 500.0 / (2.0 * std::sqrt(4.0 * kz * m));
  bool found = false;
  for (const AssembledMode* a : mount)
    if (a->label.find("rigid tz") != std::string::npos) {
      EXPECT_NEAR(a->damping_ratio / zeta_z, 1.0, 1e-2) << a->label;
      found = true;
    }
  EXPECT_TRUE(found);
  // a scene it cannot linearize says why
  const AssembledModes none = assembled_modes(sys, model, {}, {}, 200.0);
  EXPECT_TRUE(none.modes.empty());
  EXPECT_FALSE(none.reason.empty());
}
