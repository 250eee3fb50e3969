// Centres of cylindrical node sets (solver/cylinder_fit.h): the algebraic
// least-squares circle (Kasa, IEEE Trans. Instrum. Meas. 25 (1976) 8-14) is
// exact for points on a cylinder whatever their distribution, where the node
// centroid is not; on the kept crankshaft the fitted journal centres lie on
// the crank axis although the surface sets' centroids do not.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "bodies/cylinder_fit.h"
#include "io/body_file.h"

using namespace evas;

namespace {

// Points on a cylinder of radius r about `axis` through c, crowded on one side.
std::vector<Vec3> lopsided_cylinder(const Vec3& c, const Vec3& axis, double r, double len,
                                    double noise) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> g(0.0, noise);
  const Vec3 a = axis.normalized();
  const Vec3 e1 = a.cross(Vec3(0.3, 0.5, 0.7)).normalized(), e2 = a.cross(e1);
  std::vector<Vec3> p;
  for (int i = 0; i < 400; ++i) {
    const double phi = 2.0 * M_PI * std::pow(u(rng), 2.0);  // crowded near phi = 0
    const double z = len * (u(rng) - 0.5);
    p.push_back(c + (r + (noise > 0.0 ? g(rng) : 0.0)) * (std::cos(phi) * e1 + std::sin(phi) * e2) +
                z * a);
  }
  return p;
}

}  // namespace

TEST(CylinderFit, ExactOnACylinderWhateverTheNodeDistribution) {
  const Vec3 c(0.1335, -0.02, 0.01), axis(1.0, 0.1, -0.05);
  for (const double len : {0.035, 0.2}) {  // short journal (axis: least spread), long liner
    const auto pts = lopsided_cylinder(c, axis, 0.04, len, 0.0);
    Vec3 centroid = Vec3::Zero();
    for (const Vec3& p : pts) centroid += p / static_cast<double>(pts.size());
    const CylinderFit f = fit_cylinder(pts);
    // distance of the fitted centre from the true axis (along the axis the
    // centre is the nodes' mean position, not c)
    const Vec3 an = axis.normalized(), d = f.centre - c;
    const double off = (d - d.dot(an) * an).norm();
    std::printf("length %.3f: centroid off by %.2e m, fit off by %.2e m, radius %.9f, rms %.1e\n",
                len, (centroid - c).norm(), off, f.radius, f.rms);
    EXPECT_GT((centroid - c).norm(), 1e-3);  // the trap: mm off the axis
    EXPECT_LT(off, 1e-10);
    EXPECT_NEAR(f.radius, 0.04, 1e-10);
    EXPECT_NEAR(std::abs(f.axis.dot(an)), 1.0, 1e-12);
  }
  // with node noise of 1 um, the centre is found to about that
  const CylinderFit noisy = fit_cylinder(lopsided_cylinder(c, axis, 0.04, 0.035, 1e-6));
  const Vec3 an = axis.normalized(), dn = noisy.centre - c;
  EXPECT_LT((dn - dn.dot(an) * an).norm(), 2e-6);
}

TEST(CylinderFit, GivenAxisAndDegenerateSets) {
  const Vec3 c(0, 0, 0), axis(0, 0, 1);
  const auto pts = lopsided_cylinder(c, axis, 0.05, 0.01, 0.0);
  const Vec3 d = fit_cylinder(pts, &axis).centre - c;
  EXPECT_LT(std::hypot(d.x(), d.y()), 1e-12);
  EXPECT_THROW(fit_cylinder({Vec3(0, 0, 0), Vec3(1, 0, 0)}), InputError);
  const std::vector<Vec3> line = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(3, 0, 0)};
  EXPECT_THROW(fit_cylinder(line, &axis), InputError);
}

TEST(CylinderFit, KeptCrankshaftJournalsLieOnTheCrankAxis) {
  const ModalBody b =
      read_body_file(std::string(EVAS_SOURCE_DIR) + "/validation/bodies/crankshaft.h5");
  for (int j = 1; j <= 5; ++j) {
    const auto& ids = b.node_sets.at("journal" + std::to_string(j));
    std::vector<Vec3> pts;
    Vec3 centroid = Vec3::Zero();
    for (long id : ids) {
      pts.push_back(b.s.row(b.node_index(id)).transpose());
      centroid += pts.back() / static_cast<double>(ids.size());
    }
    const CylinderFit f = fit_cylinder(pts);
    const double radial = std::hypot(f.centre.y(), f.centre.z());
    std::printf(
        "journal%d: %zu nodes, centroid %.2e m off the axis, fit %.2e m, r = %.5f m, "
        "rms %.1e m, axis (%.6f, %.6f, %.6f)\n",
        j, ids.size(), std::hypot(centroid.y(), centroid.z()), radial, f.radius, f.rms, f.axis.x(),
        f.axis.y(), f.axis.z());
    // the FE nodes lie on the cylinder: measured centre offsets 3e-16 .. 6e-16 m
    // (the centroids: 0.38 .. 0.42 mm) against a 30 um clearance
    EXPECT_LT(radial, 1e-9);
    EXPECT_NEAR(std::abs(f.axis.x()), 1.0, 1e-12);
    EXPECT_NEAR(f.radius, 0.04, 1e-4);
  }
}
