// evas periodic on scenes (run/periodic_folder.h), the scene's period
// (run/period.h) and the settledness of every run (run/settledness.h): the
// validation engine's periodic cycle against a long transient, what the
// folder holds, refusals of scenes and periods.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/initial_state.h"
#include "io/results.h"
#include "run/folder_run.h"
#include "run/period.h"
#include "run/periodic.h"
#include "run/periodic_folder.h"
#include "run/run.h"
#include "run/settledness.h"
#include "study/sweep_chains.h"
#include "study/task.h"

namespace evas {
namespace {

namespace fs = std::filesystem;

fs::path work_dir() {
  static const fs::path dir = [] {
    const fs::path d = fs::temp_directory_path() / ("evas_periodic_" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
  }();
  return dir;
}

std::string slurp(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

Scene engine() {
  return read_scene(std::string(EVAS_SOURCE_DIR) + "/validation/engine/engine.yaml");
}

run::FolderOptions folder(const std::string& name) {
  run::FolderOptions fo;
  fo.dir = work_dir() / name;
  fo.quiet = true;
  fo.overwrite = true;
  return fo;
}

// max over the cycle of |a - b| / max |b|, the worst channel whose name starts
// with `prefix` and whose unit is N; b's rows from `first` on.
double worst_difference(const ResultsData& a, const ResultsData& b, long first,
                        const std::string& prefix, std::string& which) {
  double worst = 0.0;
  for (std::size_t c = 0; c < a.names.size(); ++c) {
    if (a.names[c].rfind(prefix, 0) != 0 || a.units[c] != "N") continue;
    double d = 0.0, s = 0.0;
    for (long r = 0; r < a.values.rows(); ++r) {
      d = std::max(d, std::abs(a.values(r, static_cast<long>(c)) -
                               b.values(first + r, static_cast<long>(c))));
      s = std::max(s, std::abs(b.values(first + r, static_cast<long>(c))));
    }
    if (s > 0 && d / s > worst) {
      worst = d / s;
      which = a.names[c];
    }
  }
  return worst;
}

TEST(PeriodicScene, EnginePeriodIsTheFourStrokeCycle) {
  const Scene s = engine();
  std::string why;
  const auto p = run::natural_period(s, why);
  ASSERT_TRUE(p.has_value()) << why;
  EXPECT_EQ(p->degrees, 720.0);
  EXPECT_NEAR(p->seconds, 4 * M_PI / 314.159, 1e-12);
  EXPECT_NE(p->basis.find("four-stroke pistons"), std::string::npos);
  // a whole multiple is taken, a part of the cycle is refused
  EXPECT_NEAR(run::scene_period(s, "1440deg").seconds, 2 * p->seconds, 1e-12);
  EXPECT_NEAR(run::scene_period(s, "0.08000006757s").degrees, 1440.0, 1e-4);
  try {
    run::scene_period(s, "360deg");
    FAIL() << "360 deg accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("whole multiple"), std::string::npos) << e.what();
  }
  EXPECT_THROW(run::scene_period(s, "720"), InputError);  // no unit
  EXPECT_THROW(run::scene_period(s, "-720deg"), InputError);
}

TEST(PeriodicScene, ASceneWithoutSpinHasNoPeriod) {
  Scene s = engine();
  s.model->bodies()[0].lof = Lof::fixed(Vec3::Zero(), Mat3::Identity());
  std::string why;
  EXPECT_FALSE(run::natural_period(s, why).has_value());
  EXPECT_NE(why.find("spin"), std::string::npos) << why;
  try {
    run::scene_period(s, "");
    FAIL() << "a scene without period accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--period"), std::string::npos) << e.what();
  }
  // a speed profile does not repeat
  Scene r = engine();
  Body& crank = r.model->bodies()[0];
  crank.lof =
      Lof::spin(Vec3::Zero(), Mat3::Identity(), Vec3::UnitX(), 0.0, {0.0, 1.0}, {100.0, 300.0});
  EXPECT_FALSE(run::natural_period(r, why).has_value());
  EXPECT_NE(why.find("speed that changes"), std::string::npos) << why;
}

TEST(PeriodicScene, EngineCycleMatchesALongTransientAndSaysSo) {
  const Scene s = engine();
  run::PeriodicOptions po;  // projected, the defaults
  const run::PeriodicFolderResult p =
      run::periodic_into_folder(s, s.integrator, po, "", folder("periodic"));
  ASSERT_EQ(p.exit_code, 0) << p.status;
  EXPECT_TRUE(p.periodic.converged);
  // today's: 7 cycle integrations (docs/periodic.md); a change that costs
  // more shows here
  EXPECT_LE(p.periodic.cycles, 9);
  const ResultsData per = read_results(p.results);
  ASSERT_EQ(per.time.size(), 720u);  // crank angle 0 .. 719 deg
  EXPECT_NEAR(per.values(0, 0), 0.0, 1e-9);
  EXPECT_NEAR(per.values(719, 0), 719.0, 1e-9);
  EXPECT_EQ(per.status, "completed");
  const std::string sum = slurp(p.summary);
  for (const char* key : {"\"periodic\"", "\"method\": \"projected\"", "\"floquet_multipliers\"",
                          "\"cycle_integrations\"", "\"iterations\"", "\"lives_in\""})
    EXPECT_NE(sum.find(key), std::string::npos) << key;
  // the slowest multipliers are the block's rocking on its mounts, inside the
  // unit circle but for the crank's axial float in its thrust bearing's gap (1)
  ASSERT_GE(p.periodic.multipliers.size(), 4u);
  EXPECT_NEAR(std::abs(p.periodic.multipliers[0].mu), 1.0, 1e-6);
  const double mu1 = std::abs(p.periodic.multipliers[1].mu);
  EXPECT_GT(mu1, 0.4);
  EXPECT_LT(mu1, 0.8);
  // a run from the periodic state (its state.yaml, `--initial`) is settled:
  // two cycles from it differ by less than the tolerance
  ASSERT_FALSE(p.state.empty());
  {
    Scene from = engine();
    apply_initial_state(*from.model, p.state);
    const Body& crank = from.model->bodies()[0];
    EXPECT_EQ(crank.q0, p.periodic.q.head(crank.n()));  // 17 digits read back to the bit
    const run::FolderResult two =
        run::run_into_folder(from, 2 * p.period.seconds, from.integrator, folder("from_state"));
    ASSERT_EQ(two.outcome.exit_code, 0) << two.outcome.message;
    EXPECT_TRUE(two.settledness.settled())
        << two.settledness.max_difference << " in " << two.settledness.worst_channel;
  }
  // against 20 cycles of the transient with the same settings (0.8 s): its
  // last cycle has settled to 2e-5 in the bearing loads (docs/periodic.md)
  Scene t = engine();
  t.t_end = 20 * p.period.seconds;
  const run::FolderResult tr = run::run_into_folder(t, t.t_end, t.integrator, folder("transient"));
  ASSERT_EQ(tr.outcome.exit_code, 0) << tr.outcome.message;
  const ResultsData tra = read_results(tr.results);
  // its last cycle from 13680 deg (the row at 14400 deg closes it)
  const long first = static_cast<long>(tra.time.size()) - 721;
  ASSERT_NEAR(std::fmod(tra.values(first, 0), 720.0), 0.0, 1e-6);
  std::string which;
  EXPECT_LT(worst_difference(per, tra, first, "main", which), 1e-3) << which;
  EXPECT_LT(worst_difference(per, tra, first, "mount", which), 1e-3) << which;
  // the transient says it settled (the default tolerance 1e-3)
  EXPECT_TRUE(tr.settledness.measured);
  EXPECT_TRUE(tr.settledness.settled())
      << tr.settledness.max_difference << " in " << tr.settledness.worst_channel;
  EXPECT_NE(slurp(tr.summary).find("\"settledness\""), std::string::npos);
}

// Case 2 without its thrust bearing and belt (validation/engine/scenes.sh's
// case7.yaml): the projected method's first step from the 180-step stepped
// linearization leaves the bearings' states even when halved four times; the
// linearization refined to one step per sample converges (it failed before).
TEST(PeriodicScene, ProjectedRefinesItsLinearizationWhenAStepLeavesTheStates) {
  const fs::path dir = work_dir() / "case7";
  fs::create_directories(dir);
  const std::string cmd = std::string("sh '") + EVAS_SOURCE_DIR +
                          "/validation/engine/scenes.sh' '" + dir.string() + "' > /dev/null";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  Scene scene = read_scene((dir / "case7.yaml").string());
  const run::ScenePeriod per = run::scene_period(scene, "");
  run::SceneRun sr(scene, scene.t_start + per.seconds);
  Vec q0, v0;
  sr.system().initial_state(q0, v0);
  std::vector<double> samples;  // the rows of the cycle, 0 .. 719 deg
  for (double t : sr.outputs().times())
    if (t < scene.t_start + per.seconds * (1.0 - 1e-9)) samples.push_back(t);
  const run::PeriodicResult r =
      run::find_periodic(sr.system(), scene.t_start, per.seconds, q0, v0, scene.integrator,
                         run::PeriodicOptions{}, samples);
  ASSERT_TRUE(r.converged) << r.message;
  bool refined = false;
  for (const auto& it : r.iterations)
    refined = refined || it.step.find("linearization refined to") != std::string::npos;
  EXPECT_TRUE(refined);
  EXPECT_LE(r.iterations.back().defect, 3e-4);
}

TEST(PeriodicScene, ASixCycleRunSaysItHasNotSettled) {
  Scene s = engine();
  const run::FolderResult r = run::run_into_folder(s, s.t_end, s.integrator, folder("six"));
  ASSERT_EQ(r.outcome.exit_code, 0);
  ASSERT_TRUE(r.settledness.measured);
  EXPECT_EQ(r.settledness.rows_per_period, 720);
  EXPECT_FALSE(r.settledness.settled());
  // the mounts are furthest from their steady cycle (0.29 in the table)
  EXPECT_GT(r.settledness.max_difference, 0.05);
  const std::string sum = slurp(r.summary);
  EXPECT_NE(sum.find("\"settled\": false"), std::string::npos);
  // until settled: stops at the first cycle whose difference from the one
  // before is within the tolerance
  run::FolderOptions fo = folder("until");
  fo.until_settled = 1e-2;
  const run::FolderResult u = run::run_into_folder(s, 40 * 0.04000003378658314, s.integrator, fo);
  ASSERT_EQ(u.outcome.exit_code, 0) << u.outcome.message;
  EXPECT_TRUE(u.settledness.settled());
  EXPECT_LE(u.settledness.max_difference, 1e-2);
  EXPECT_LT(u.t_reached, 20 * 0.04);  // long before the limit
  EXPECT_NEAR(std::remainder(u.settledness.cycles, 1.0), 0.0, 1e-9);
}

TEST(InitialState, RefusesAStateThatDoesNotFitTheScene) {
  const fs::path f = work_dir() / "state.yaml";
  auto expect_refused = [&](const std::string& text, const std::string& what) {
    std::ofstream(f) << text;
    Scene s = engine();
    try {
      apply_initial_state(*s.model, f.string());
      FAIL() << "accepted: " << text;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(f.string()), std::string::npos) << e.what();
    }
  };
  expect_refused("scene: x\n", "lists 'bodies'");
  expect_refused("bodies:\n  - {name: rotor, q: [1], v: [1]}\n", "no body 'rotor'");
  expect_refused("bodies:\n  - {name: crank, q: [1, 2], v: [1, 2]}\n", "numbers, one per mode");
  Scene s = engine();
  const Vec q = Vec::Zero(s.model->size()), v = Vec::Zero(s.model->size());
  std::string text = initial_state_text(*s.model, q, v, "engine-case1", 0.0, "zeros");
  // only the crank: the block is left out
  text = text.substr(0, text.find("  - {name: block"));
  expect_refused(text, "leaves out body 'block'");
  std::string bad = initial_state_text(*s.model, q, v, "x", 0.0, "");
  bad.replace(bad.find("q: [0") + 4, 1, "nan");
  expect_refused(bad, "is not a finite number");
}

TEST(Settledness, ComparesCyclesModuloATurnAndFloorsStillChannels) {
  std::vector<Channel> ch = {{"crank_angle", "deg"},
                             {"a.fx", "N"},
                             {"a.fy", "N"},
                             {"a.attitude", "rad"},
                             {"a.h_min_angle", "rad"}};
  // two cycles of two rows: a.fx 1000 N moving by 1 N, a.fy 1e-2 N moving by
  // 1e-2 N (a still channel: floored at 1e-3 x 1000 N), the attitude across pi
  const double prev[] = {0, 1000, 0.01, 3.14, 0.0, 360, -1000, 0.0, 3.1, 0.0};
  const double last[] = {720, 1001, 0.02, -3.14, 3.0, 1080, -1000, 0.0, 3.1, 0.0};
  const run::Settledness s = run::compare_cycles(ch, last, prev, 2, 5);
  ASSERT_EQ(s.channels.size(), 4u);  // crank_angle left out
  EXPECT_NEAR(s.channels[0].difference, 1.0 / 1001.0, 1e-12);
  EXPECT_NEAR(s.channels[1].difference, 0.01 / 1.001, 1e-12);  // floor 1e-3 x 1001 N
  EXPECT_NEAR(s.channels[2].difference, (2 * M_PI - 6.28) / 3.14, 1e-9);
  EXPECT_NEAR(s.channels[3].difference, 3.0 / 3.0, 1e-12);  // listed ...
  EXPECT_EQ(s.worst_channel, "a.fy");                       // ... not in the verdict
  EXPECT_NEAR(s.max_difference, 0.01 / 1.001, 1e-12);
  std::string why;
  EXPECT_EQ(run::rows_per_period(true, 1.0, 0.04, 720.0, why), 720);
  EXPECT_EQ(run::rows_per_period(false, 5e-4, 2 * M_PI / 300, 360.0, why), 0);
  EXPECT_NE(why.find("does not divide"), std::string::npos) << why;
}

}  // namespace
}  // namespace evas

namespace evas::study {
namespace {

TEST(PeriodicSweepTask, PacksExactlyAndRunsOneSteadyCycle) {
  TaskSpec t;
  t.src.path = std::string(EVAS_SOURCE_DIR) + "/validation/engine/engine.yaml";
  t.src.text = read_scene_text(t.src.path);
  const Scene s = read_scene(t.src.path);
  t.settings = s.integrator;
  t.channels = {0, 1, 2};
  // a transient task's bytes are those of before periodic tasks: no trailer
  const std::string transient = pack_task(t);
  t.periodic = "projected";
  t.periodic_tol = 3e-4;
  const std::string periodic = pack_task(t);
  EXPECT_EQ(periodic.substr(0, transient.size()), transient);
  EXPECT_GT(periodic.size(), transient.size());
  const TaskSpec back = unpack_task(periodic);
  EXPECT_EQ(back.periodic, "projected");
  EXPECT_EQ(back.periodic_tol, 3e-4);
  EXPECT_EQ(pack_task(back), periodic);
  EXPECT_TRUE(unpack_task(transient).periodic.empty());
  EXPECT_NE(task_fingerprint(t), task_fingerprint(unpack_task(transient)));
  const RunData d = run_task(t);
  ASSERT_EQ(d.status, CaseStatus::completed) << d.message;
  ASSERT_EQ(d.rows(), 720);
  EXPECT_NEAR(d.crank.front(), 0.0, 1e-9);
  EXPECT_NEAR(d.crank.back(), 719.0, 1e-9);
  EXPECT_EQ(d.y.cols(), 3);
  // the cycle's start state comes back (every body's q then v), bit for bit
  // through the worker's bytes
  ASSERT_FALSE(d.state.empty());
  EXPECT_EQ(unpack_run(pack_run(d)).state, d.state);
  // a warm start from it: the same task (fingerprint), a search that starts
  // at the converged cycle and needs far fewer steps
  TaskSpec warm = t;
  warm.initial = d.state;
  EXPECT_EQ(task_fingerprint(warm), task_fingerprint(t));
  EXPECT_EQ(unpack_task(pack_task(warm)).initial, d.state);
  const RunData w = run_task(warm);
  ASSERT_EQ(w.status, CaseStatus::completed) << w.message;
  EXPECT_LT(w.stats.steps * 2, d.stats.steps);
  for (long c = 0; c < 3; ++c)
    EXPECT_LT((w.y.col(c) - d.y.col(c)).cwiseAbs().maxCoeff(),
              1e-3 * d.y.col(c).cwiseAbs().maxCoeff() + 1e-9);
  // a state of the wrong size fails the task and says so
  warm.initial.pop_back();
  const RunData wrong = run_task(warm);
  EXPECT_EQ(wrong.status, CaseStatus::failed);
  EXPECT_NE(wrong.message.find("initial state has"), std::string::npos) << wrong.message;
  // an unknown method fails the task with the names
  t.periodic = "shooting";
  const RunData bad = run_task(t);
  EXPECT_EQ(bad.status, CaseStatus::failed);
  EXPECT_NE(bad.message.find("projected, newton, anderson, fixed-point"), std::string::npos)
      << bad.message;
}

// The warm-start chains: one chain per worker, contiguous points, each point
// after the first of its chain started by the point before it (same case).
TEST(PeriodicSweepTask, WarmStartChainsAreAsWideAsTheRunner) {
  // 8 points, 1 case, serial: one chain 0 <- 1 <- ... <- 7
  std::vector<int> p = warm_predecessors(8, 1, 1);
  EXPECT_EQ(p, (std::vector<int>{-1, 0, 1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(chain_waves(p), (std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7}));
  // two workers: two chains of 4, 4 waves of 2
  p = warm_predecessors(8, 1, 2);
  EXPECT_EQ(p, (std::vector<int>{-1, 0, 1, 2, -1, 4, 5, 6}));
  EXPECT_EQ(chain_waves(p), (std::vector<int>{0, 1, 2, 3, 0, 1, 2, 3}));
  // 3 points x 2 cases, 2 workers: a chain per case (task = point * 2 + case)
  p = warm_predecessors(3, 2, 2);
  EXPECT_EQ(p, (std::vector<int>{-1, -1, 0, 1, 2, 3}));
  // more workers than points: every point a chain of its own
  p = warm_predecessors(3, 1, 8);
  EXPECT_EQ(p, (std::vector<int>{-1, -1, -1}));
  EXPECT_TRUE(warm_predecessors(0, 1, 2).empty());
  EXPECT_THROW(chain_waves({1, -1}), std::logic_error);
}

}  // namespace
}  // namespace evas::study
