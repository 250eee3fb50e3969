// One run for every front end (run/run.h): `evas run`, a one-case study
// (study::run_case), the run layer itself and (python/tests) Python give the
// same rows, bit for bit, on the validation engine (Case 1), the engine with
// element internal states (Maxwell mounts and a clutch disk, Case 1 with
// states), the engine welded to the ground by fixed joints (a constrained
// system with multiplier channels) and a jointed beam under generalized-alpha.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>

#include "io/results.h"
#include "io/scene.h"
#include "run/run.h"
#include "sdof_problem.h"
#include "study/run_case.h"

using namespace evas;
namespace fs = std::filesystem;

namespace {

const fs::path& work_dir() {
  static const fs::path dir = [] {
    const fs::path d = fs::temp_directory_path() / ("evas_run_" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    // the validation engine's scenes, 0.01 s each (validation/engine/scenes.sh)
    const std::string cmd =
        std::string(EVAS_SOURCE_DIR) + "/validation/engine/scenes.sh " + d.string() + " 0.01";
    if (std::system(cmd.c_str()) != 0) throw std::runtime_error("scenes.sh failed");
    return d;
  }();
  return dir;
}

struct Rows {
  std::vector<double> time;
  std::vector<std::string> names;
  Mat values;
};

Rows by_evas_run(const std::string& scene, const std::string& tag, const std::string& extra) {
  const fs::path out = work_dir() / ("run_" + tag);
  const std::string cmd = std::string(EVAS_BINARY_DIR) + "/evas run " + scene + " --out " +
                          out.string() + " --quiet " + extra;
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
  const ResultsData r = read_results((out / "results.h5").string());
  EXPECT_EQ(r.status, "completed");
  return {r.time, r.names, r.values};
}

Rows by_run_layer(const std::string& scene_path, const IntegratorSettings& s) {
  const Scene scene = read_scene(scene_path);
  run::SceneRun sr(scene, scene.t_end);
  run::MemorySink sink;
  const run::Outcome o = sr.perform(s, sink);
  EXPECT_TRUE(o.completed()) << o.message;
  Rows r;
  r.time = sink.times();
  for (const auto& c : sink.channels()) r.names.push_back(c.name);
  const long nr = static_cast<long>(r.time.size());
  r.values =
      Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
          sink.values().data(), nr, sink.width());
  return r;
}

Rows by_study(const std::string& scene_path, const IntegratorSettings& s) {
  const study::SceneSource src = study::load_scene_source(scene_path, {});
  const study::SceneInfo info = study::probe_scene(src);
  std::vector<int> all(info.channels.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
  const study::RunData d = study::run_case(src, s, all);
  EXPECT_EQ(d.status, study::CaseStatus::completed)
      << study::to_text(d.status) << ": " << d.message;
  Rows r;
  r.time = d.time;
  for (const auto& c : info.channels) r.names.push_back(c.name);
  r.values = d.y;
  return r;
}

// Equal bit for bit over the columns of `b` (a study keeps the scene's own
// channels, without the integrator's multipliers).
void expect_same_bits(const Rows& a, const Rows& b, const std::string& what) {
  ASSERT_EQ(a.time.size(), b.time.size()) << what;
  ASSERT_GE(a.names.size(), b.names.size()) << what;
  ASSERT_GT(a.time.size(), 2u) << what;
  EXPECT_EQ(std::memcmp(a.time.data(), b.time.data(), a.time.size() * sizeof(double)), 0) << what;
  long differ = 0;
  for (long r = 0; r < b.values.rows(); ++r)
    for (long c = 0; c < b.values.cols(); ++c) {
      EXPECT_EQ(a.names[static_cast<std::size_t>(c)], b.names[static_cast<std::size_t>(c)]);
      const double x = a.values(r, c), y = b.values(r, c);
      if (std::memcmp(&x, &y, sizeof x) != 0) ++differ;
    }
  EXPECT_EQ(differ, 0) << what << ": values that differ in their bits";
}

void expect_one_run(const std::string& scene, const std::string& tag, const std::string& extra,
                    const IntegratorSettings& s, std::size_t multipliers) {
  const Rows cli = by_evas_run(scene, tag, extra);
  const Rows lib = by_run_layer(scene, s);
  const Rows st = by_study(scene, s);
  expect_same_bits(cli, lib, tag + ": evas run against the run layer");
  EXPECT_EQ(cli.names.size(), lib.names.size()) << tag;
  expect_same_bits(cli, st, tag + ": evas run against a one-case study");
  EXPECT_EQ(cli.names.size(), st.names.size() + multipliers) << tag;
}

IntegratorSettings scene_settings(const std::string& scene) { return read_scene(scene).integrator; }

}  // namespace

TEST(OneRun, EngineCase1SameRowsFromEveryFrontEnd) {
  const std::string scene = (work_dir() / "case1.yaml").string();
  expect_one_run(scene, "case1", "", scene_settings(scene), 0);
}

TEST(OneRun, EngineWithInternalStatesSameRowsFromEveryFrontEnd) {
  const std::string scene = (work_dir() / "case5.yaml").string();
  const IntegratorSettings s = scene_settings(scene);
  ASSERT_GT(read_scene(scene).model->elements().size(), 0u);
  expect_one_run(scene, "states", "", s, 0);
}

TEST(OneRun, WeldedEngineSameRowsAndMultipliersFromEveryFrontEnd) {
  const std::string scene = (work_dir() / "case3.yaml").string();
  // 4 fixed joints of 6 equations: 24 multiplier channels (c.lambda)
  expect_one_run(scene, "welded", "", scene_settings(scene), 24);
}

TEST(OneRun, JointedBeamUnderGeneralizedAlphaSameRowsFromEveryFrontEnd) {
  const std::string scene = std::string(EVAS_SOURCE_DIR) + "/scenes/hinged_beam.yaml";
  IntegratorSettings s = scene_settings(scene);
  s.name = "generalized-alpha";
  s.step = 1e-4;
  expect_one_run(scene, "beam", "--integrator generalized-alpha --step 1e-4", s, 5);
}

TEST(OneRun, ProblemRunEndsOnTheEndPoint) {
  // run_to_end is what `evas problem` runs: the same start, landing on t_end.
  // q'' = -4 q from q = 1: q = cos 2t, v = -2 sin 2t.
  test::Oscillator o;
  o.omega = 2.0;
  o.q0 = 1.0;
  test::SdofProblem p({o});
  IntegratorSettings s;
  s.rtol = 1e-10;
  s.atol = 1e-12;
  const run::EndState e = run::run_to_end(p, s, 0.0, 1.0);
  ASSERT_TRUE(e.outcome.completed()) << e.outcome.message;
  EXPECT_NEAR(e.q(0), std::cos(2.0), 1e-7);
  EXPECT_NEAR(e.v(0), -2.0 * std::sin(2.0), 1e-7);
  EXPECT_GT(e.outcome.stats.steps, 10);
  EXPECT_EQ(e.lambda.size(), 0);
}
