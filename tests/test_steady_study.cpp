// A study on the steady cycle (study/steady_start.h): every run, the
// reference's too, starts from the scene's periodic state and lasts one
// period, so the error is the integration error without the start-up.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "io/scene.h"
#include "study/study.h"
#include "study/task.h"

namespace evas::study {
namespace {

namespace fs = std::filesystem;

const std::string kEngine = std::string(EVAS_SOURCE_DIR) + "/validation/engine/engine.yaml";

fs::path out_dir(const std::string& name) {
  const fs::path d =
      fs::temp_directory_path() / ("evas_steady_" + std::to_string(::getpid())) / name;
  fs::remove_all(d);
  return d;
}

Options steady_options(const std::string& name) {
  Options o;
  o.scene = kEngine;
  o.channels = "main3.fx,main3.fy,mount1.fz";
  o.reference = "ida rtol=1e-7 atol=1e-10";
  o.out_dir = out_dir(name).string();
  o.plot = false;
  o.start.steady = true;
  return o;
}

// The reference run from the periodic state is the periodic cycle itself: it
// matches the cycle evas periodic converges to (a sweep task's rows), row for
// row, to the periodicity defect; a case is measured on that one cycle.
TEST(SteadyStudy, RunsOnePeriodFromThePeriodicState) {
  const Options o = steady_options("wp");
  const WorkPrecisionResult r = work_precision(o, {{"ida rtol=1e-4", ""}});
  // 0 .. 720 deg: the last row is the state one period on
  ASSERT_EQ(r.reference.time.size(), 721u);
  EXPECT_NEAR(r.reference.crank.front(), 0.0, 1e-9);
  EXPECT_NEAR(r.reference.crank.back(), 720.0, 1e-9);
  EXPECT_NE(r.info.start.find("the periodic state"), std::string::npos) << r.info.start;
  EXPECT_TRUE(fs::exists(fs::path(o.out_dir) / "state.yaml"));
  ASSERT_EQ(r.cases.size(), 1u);
  ASSERT_EQ(r.cases[0].status, CaseStatus::completed) << r.cases[0].message;
  EXPECT_GT(r.cases[0].error, 0.0);
  EXPECT_LT(r.cases[0].error, 3e-2);

  TaskSpec t;
  t.src = load_scene_source(kEngine, {});
  t.settings = read_scene(kEngine).integrator;
  const SceneInfo info = probe_scene(t.src);
  for (const std::string& name : r.info.channels)
    for (std::size_t i = 0; i < info.channels.size(); ++i)
      if (info.channels[i].name == name) t.channels.push_back(static_cast<int>(i));
  ASSERT_EQ(t.channels.size(), r.info.channels.size());
  t.periodic = "projected";
  const RunData p = run_task(t);
  ASSERT_EQ(p.status, CaseStatus::completed) << p.message;
  ASSERT_EQ(p.rows(), 720);
  for (long c = 0; c < p.y.cols(); ++c) {
    const double scale = r.reference.y.col(c).cwiseAbs().maxCoeff();
    EXPECT_LT((p.y.col(c) - r.reference.y.col(c).head(720)).cwiseAbs().maxCoeff(), 2e-3 * scale)
        << r.info.channels[static_cast<std::size_t>(c)];
    // and it is periodic: one period on, the channel is where it started
    EXPECT_LT(std::abs(r.reference.y(720, c) - r.reference.y(0, c)), 2e-3 * scale)
        << r.info.channels[static_cast<std::size_t>(c)];
  }
}

// --initial FILE: the state written by the steady study starts the runs; the
// scene's end time stays. Bad input names the option and the file.
TEST(SteadyStudy, InitialFileAndRefusals) {
  Options o = steady_options("refused");
  o.t_end = 0.1;
  EXPECT_THROW(work_precision(o, {{"ida rtol=1e-4", ""}}), InputError);
  o = steady_options("missing");
  o.start.initial_file = "/nonexistent/state.yaml";
  try {
    work_precision(o, {{"ida rtol=1e-4", ""}});
    FAIL() << "a missing state file was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/state.yaml"), std::string::npos) << e.what();
  }
  o = steady_options("tol");
  o.start.tol = 0.0;
  EXPECT_THROW(work_precision(o, {{"ida rtol=1e-4", ""}}), InputError);
}

}  // namespace
}  // namespace evas::study
