// The process-wide caches behind scene parsing (io/body_cache.h): a body file
// read, checked and truncated once per recipe and shared; set markers fitted
// once per body and node set. What they return must equal what a parse
// without them makes, and a changed file or recipe must never be served stale.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "io/body_cache.h"
#include "io/body_file.h"
#include "io/scene.h"
#include "model/lof.h"
#include "random_body.h"

namespace evas {
namespace {

namespace fs = std::filesystem;

class BodyCache : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string tmpl = ::testing::TempDir() + "evas_cache_XXXXXX";
    ASSERT_NE(mkdtemp(tmpl.data()), nullptr);
    dir_ = tmpl;
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  // A scene on BODY keeping `elastic` elastic modes, with a set marker.
  Scene parse(const fs::path& body, int elastic, const std::string& zeta = "") const {
    const std::string text = "name: cache\nbodies:\n  - name: b\n    file: " + body.string() +
                             "\n    modes: {rigid: true, elastic: " + std::to_string(elastic) +
                             "}\n" + (zeta.empty() ? "" : "    damping_ratio: " + zeta + "\n") +
                             "markers:\n  - {name: m, body: b, set: first4}\n"
                             "  - {name: g, ground: [0, 0, 0]}\n"
                             "elements:\n  - {name: k, type: spring-damper, markers: [m, g], "
                             "stiffness: [1e5, 1e5, 1e5]}\n"
                             "time: {start: 0, end: 0.01}\n";
    return parse_scene(text, (dir_ / "scene.yaml").string());
  }
  fs::path dir_;
};

TEST_F(BodyCache, SameRecipeSharesOneBodyAndAnotherRecipeGetsItsOwn) {
  const fs::path file = dir_ / "b.h5";
  write_body_file(file.string(), test_bodies::random_body(12, 5, 7));
  const Scene a = parse(file, 3), b = parse(file, 3), c = parse(file, 5);
  const auto& da = a.model->bodies()[0].data;
  // the same file and recipe: one object, nothing copied
  EXPECT_EQ(da.get(), b.model->bodies()[0].data.get());
  EXPECT_EQ(da->num_modes(), 6 + 3);
  // another truncation is another body
  EXPECT_NE(da.get(), c.model->bodies()[0].data.get());
  EXPECT_EQ(c.model->bodies()[0].data->num_modes(), 6 + 5);
  // and the marker of each parse has the columns of its own body
  EXPECT_EQ(a.model->markers()[0].Bu.cols(), 9);
  EXPECT_EQ(b.model->markers()[0].Bu.cols(), 9);
  EXPECT_EQ(c.model->markers()[0].Bu.cols(), 11);
  // damping ratios that differ beyond 6 digits are two recipes, not one
  const Scene d1 = parse(file, 3, "0.0100000"), d2 = parse(file, 3, "0.01000001");
  EXPECT_NE(d1.model->bodies()[0].data.get(), d2.model->bodies()[0].data.get());
  EXPECT_NE(d1.model->bodies()[0].data->damping[8], d2.model->bodies()[0].data->damping[8]);
}

TEST_F(BodyCache, ARewrittenFileIsReadAgain) {
  const fs::path file = dir_ / "b.h5";
  write_body_file(file.string(), test_bodies::random_body(12, 4, 1));
  const Scene a = parse(file, 4);
  const Mat3X first = a.model->markers()[0].Bu;
  // another body under the same name (a new inode, size or time)
  fs::remove(file);
  write_body_file(file.string(), test_bodies::random_body(12, 4, 2));
  const Scene b = parse(file, 4);
  EXPECT_NE(a.model->bodies()[0].data.get(), b.model->bodies()[0].data.get());
  const ModalBody fresh = read_body_file(file.string());
  EXPECT_EQ(b.model->bodies()[0].data->modes, fresh.modes);
  // the marker is fitted on the new shapes, not served from the old body's fit
  const Marker want =
      make_set_marker("m", 0, *b.model->bodies()[0].data, fresh.node_sets.at("first4"), {});
  EXPECT_EQ(b.model->markers()[0].Bu, want.Bu);
  EXPECT_FALSE(b.model->markers()[0].Bu.isApprox(first));
}

TEST_F(BodyCache, CachedMarkerFitEqualsAFreshFit) {
  const fs::path file = dir_ / "b.h5";
  write_body_file(file.string(), test_bodies::random_body(20, 6, 3));
  const Scene a = parse(file, 6);
  const auto& data = a.model->bodies()[0].data;
  const std::vector<long> ids = data->node_sets.at("all");
  const std::vector<double> w(ids.size(), 0.5);
  const Vec3 centre(0.1, -0.05, 0.2);
  for (const Vec3* c : {static_cast<const Vec3*>(nullptr), &centre})
    for (int pass = 0; pass < 2; ++pass) {  // the first fits, the second is served
      const Marker got = set_marker_cached("x", 3, data, ids, w, c);
      const Marker want = make_set_marker("x", 3, *data, ids, w, c);
      EXPECT_EQ(got.name, "x");
      EXPECT_EQ(got.body, 3);
      EXPECT_EQ(got.Bu, want.Bu);
      EXPECT_EQ(got.Bt, want.Bt);
      EXPECT_EQ(got.c, want.c);
      EXPECT_EQ(got.has_rotation, want.has_rotation);
    }
  // a body built in memory is not in the cache: fitted each time, the same
  auto own = std::make_shared<const ModalBody>(test_bodies::random_body(20, 6, 3));
  const Marker m = set_marker_cached("y", 0, own, ids, {}, nullptr);
  EXPECT_EQ(m.Bu, make_set_marker("y", 0, *own, ids, {}).Bu);
}

TEST_F(BodyCache, CachedSurfaceEqualsAFreshOneAndKeysOnItsContent) {
  const fs::path file = dir_ / "b.h5";
  write_body_file(file.string(), test_bodies::random_body(20, 6, 4));
  const Scene a = parse(file, 6);
  const auto& data = a.model->bodies()[0].data;
  SurfaceSet set;
  set.nodes = data->node_sets.at("all");
  const auto n = static_cast<Eigen::Index>(set.nodes.size());
  set.area = Vec::LinSpaced(n, 1e-4, 3e-4);
  set.normal.resize(n, 3);
  for (Eigen::Index i = 0; i < n; ++i) set.normal.row(i) = Vec3(i % 3 == 0, i % 3 == 1, i % 3 == 2);
  LofState lof;
  lof.v_GL = Vec3(0.1, -0.2, 0.05);
  lof.w_GL_G = Vec3(0.0, 3.0, 1.0);
  const Vec qdot = Vec::LinSpaced(data->num_modes(), -0.4, 0.9);
  auto values = [&](const SurfaceRadiation& r) {
    std::vector<double> out(static_cast<std::size_t>(r.values()));
    r.evaluate(lof, qdot.data(), out.data());
    return out;
  };
  const std::vector<double> fresh = values(SurfaceRadiation(*data, set, 413.0, true, "t"));
  for (int pass = 0; pass < 2; ++pass)  // the first forms, the second is served
    EXPECT_EQ(values(surface_radiation_cached(data, set, 413.0, true, "t")), fresh);
  // another rho c, or another area on the same nodes, is not served the first
  const std::vector<double> louder = values(surface_radiation_cached(data, set, 826.0, true, "t"));
  EXPECT_DOUBLE_EQ(louder[2], 2.0 * fresh[2]);
  SurfaceSet bigger = set;
  bigger.area *= 4.0;
  const std::vector<double> wide = values(surface_radiation_cached(data, bigger, 413.0, true, "t"));
  EXPECT_DOUBLE_EQ(wide[2], 4.0 * fresh[2]);
  EXPECT_DOUBLE_EQ(wide[0], fresh[0]);  // the mean normal velocity is per area
  // and the error of a bad request is thrown each time, never cached away
  for (int pass = 0; pass < 2; ++pass)
    EXPECT_THROW(surface_radiation_cached(data, set, -1.0, true, "t"), InputError);
}

}  // namespace
}  // namespace evas
