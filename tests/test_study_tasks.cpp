// The study's tasks (study/task.h) and their runners (study/task_runner.h):
// exact byte forms, forked workers giving the same digits as this process,
// the wall-clock limits, the stop request, and the sweep grammar
// (parse_sweep). The runs are of the paper's engine (validation/engine), a
// few milliseconds of it, so that the forked workers carry a real model.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>

#include "integrators/settings.h"
#include "model/types.h"
#include "study/study.h"

using namespace evas;
using namespace evas::study;

namespace {

const std::string kEngine = std::string(EVAS_SOURCE_DIR) + "/validation/engine/engine.yaml";

// Tasks on the engine: `n` cases of IDA at different tolerances, `t_end` seconds.
std::vector<TaskSpec> engine_tasks(int n, double t_end, double max_wall = 0.0) {
  const SceneSource src = load_scene_source(kEngine, {}, t_end);
  const SceneInfo info = probe_scene(src);
  std::vector<int> channels;
  for (std::size_t i = 0; i < info.channels.size(); ++i)
    if (info.channels[i].name.rfind("main", 0) == 0) channels.push_back(static_cast<int>(i));
  std::vector<TaskSpec> tasks;
  for (int k = 0; k < n; ++k) {
    TaskSpec t;
    t.src = src;
    t.settings = info.integrator;
    t.settings.rtol = 1e-4 / (1 << k);
    t.channels = channels;
    t.max_wall = max_wall;
    tasks.push_back(t);
  }
  return tasks;
}

// Bit-for-bit equality of two runs (the wall time aside).
void expect_same_run(const RunData& a, const RunData& b) {
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.message, b.message);
  ASSERT_EQ(a.time.size(), b.time.size());
  ASSERT_EQ(a.y.rows(), b.y.rows());
  ASSERT_EQ(a.y.cols(), b.y.cols());
  EXPECT_EQ(0, std::memcmp(a.time.data(), b.time.data(), a.time.size() * sizeof(double)));
  EXPECT_EQ(0, std::memcmp(a.crank.data(), b.crank.data(), a.crank.size() * sizeof(double)));
  EXPECT_EQ(0, std::memcmp(a.y.data(), b.y.data(), a.y.size() * sizeof(double)));
  EXPECT_EQ(a.stats.steps, b.stats.steps);
  EXPECT_EQ(a.stats.residual_evals, b.stats.residual_evals);
  EXPECT_EQ(a.stats.last_step, b.stats.last_step);
}

std::vector<RunData> run_all(TaskRunner& r, const std::vector<TaskSpec>& tasks,
                             std::vector<std::string>* workers = nullptr,
                             const std::function<bool()>& stop = nullptr) {
  std::vector<RunData> out(tasks.size());
  std::vector<int> todo;
  for (std::size_t i = 0; i < tasks.size(); ++i) todo.push_back(static_cast<int>(i));
  if (workers) workers->assign(tasks.size(), "");
  r.run(
      tasks, todo,
      [&](const TaskEnd& e) {
        EXPECT_TRUE(e.ran);
        out[static_cast<std::size_t>(e.index)] = e.run;
        if (workers) (*workers)[static_cast<std::size_t>(e.index)] = e.worker;
      },
      stop);
  return out;
}

}  // namespace

TEST(StudyTask, TaskAndRunBytesAreExact) {
  TaskSpec t = engine_tasks(1, 0.002).front();
  t.settings.name = "generalized-alpha";
  t.settings.step = 1.0 / 3.0 * 1e-5;  // a number with every bit in use
  t.repeats = 3;
  t.max_wall = 0.1;
  const TaskSpec u = unpack_task(pack_task(t));
  EXPECT_EQ(u.src.path, t.src.path);
  EXPECT_EQ(u.src.text, t.src.text);
  EXPECT_EQ(u.src.edited, t.src.edited);
  EXPECT_EQ(settings_label(u.settings), settings_label(t.settings));
  EXPECT_EQ(u.settings.step, t.settings.step);
  EXPECT_EQ(u.channels, t.channels);
  EXPECT_EQ(u.repeats, 3);
  EXPECT_EQ(u.max_wall, 0.1);

  const RunData d = run_task(engine_tasks(1, 0.002).front());
  ASSERT_EQ(d.status, CaseStatus::completed) << d.message;
  const RunData e = unpack_run(pack_run(d));
  expect_same_run(d, e);
  EXPECT_EQ(e.wall, d.wall);

  const std::string bytes = pack_run(d);
  EXPECT_THROW(unpack_run(bytes.substr(0, bytes.size() - 1)), std::runtime_error);
  EXPECT_THROW(unpack_run(bytes + "x"), std::runtime_error);
  EXPECT_THROW(unpack_run(pack_task(t)), std::runtime_error);
  EXPECT_THROW(unpack_task(bytes), std::runtime_error);
}

// Forked workers run the same code on the same bytes: the same digits.
TEST(StudyTask, WorkerProcessesGiveTheSerialRunsBitForBit) {
  const auto tasks = engine_tasks(3, 0.01);
  const auto serial = run_all(*serial_runner(), tasks);
  std::vector<std::string> workers;
  const auto forked = run_all(*process_runner(2), tasks, &workers);
  for (std::size_t i = 0; i < tasks.size(); ++i) {
    SCOPED_TRACE(i);
    ASSERT_EQ(serial[i].status, CaseStatus::completed) << serial[i].message;
    expect_same_run(serial[i], forked[i]);
    EXPECT_EQ(workers[i].rfind("worker pid ", 0), 0u) << workers[i];
  }
  // one worker runs the list one task after another (it is kept, warm)
  std::vector<std::string> one;
  const auto pooled = run_all(*process_runner(1), tasks, &one);
  for (std::size_t i = 0; i < tasks.size(); ++i) {
    expect_same_run(serial[i], pooled[i]);
    EXPECT_EQ(one[i], one[0]);
  }
}

// The statistics' bytes: every field, no padding, and back exactly.
TEST(StudyTask, StatisticsBytesHoldEveryField) {
  IntegratorStats s;
  long n = 1;
  for (long* f :
       {&s.steps, &s.residual_evals, &s.jacobian_evals, &s.linear_setups, &s.linear_solves,
        &s.nonlinear_iterations, &s.error_test_failures, &s.convergence_failures, &s.restarts,
        &s.refused_states, &s.substeps, &s.max_step_iterations})
    *f = ++n * 1000003;
  s.wall_seconds = 0.1;
  s.last_step = 1e-5;
  s.min_step = 1e-9;
  s.max_step = 1e-3;
  s.last_order = 5;
  s.max_constraint = 1e-12;
  s.max_constraint_rate = 3e-10;
  const std::string b = stats_to_bytes(s);
  EXPECT_EQ(b.size(), 12 * sizeof(long) + 6 * sizeof(double) + sizeof(int));
  const IntegratorStats t = stats_from_bytes(b);
  EXPECT_EQ(stats_to_bytes(t), b);
  for (const auto& f : stat_fields()) EXPECT_EQ(f.get(t), f.get(s)) << f.name;
  EXPECT_THROW(stats_from_bytes(b + "x"), std::runtime_error);
}

// --max-wall: the run stops itself at the limit (cooperatively, between steps).
TEST(StudyTask, MaxWallEndsALongRunAsTimedOut) {
  const TaskSpec t = engine_tasks(1, 1.0, 0.05).front();  // 1 s of engine: seconds of work
  const RunData d = run_task(t);
  EXPECT_EQ(d.status, CaseStatus::failed);
  EXPECT_NE(d.message.find("timed out: wall time above --max-wall 0.05 s"), std::string::npos)
      << d.message;
  // stopped on the way (the rows reached, if any, are kept)
  EXPECT_TRUE(d.time.empty() || d.time.back() < 1.0 - 1e-9);
}

// A worker stuck beyond the hard limit is killed; the other tasks complete.
// The limit is set from the short task's own duration here (a sanitizer
// build runs 10x slower), the long task takes some 30 times as long.
TEST(StudyTask, HardWallKillsTheWorker) {
  auto tasks = engine_tasks(2, 0.005);
  const auto t0 = std::chrono::steady_clock::now();
  ASSERT_EQ(run_task(tasks[0]).status, CaseStatus::completed);
  const double shortest =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  tasks[1] = engine_tasks(1, 1.0).front();  // no limit of its own
  const auto out = run_all(*process_runner(2, 4.0 * shortest + 0.5), tasks);
  EXPECT_EQ(out[0].status, CaseStatus::completed) << out[0].message;
  EXPECT_EQ(out[1].status, CaseStatus::failed);
  EXPECT_NE(out[1].message.find("timed out: the worker was killed after"), std::string::npos)
      << out[1].message;
}

// A stop request: no task starts after it, running ones are not reported.
TEST(StudyTask, StopLeavesTheRestNotRun) {
  const auto tasks = engine_tasks(4, 0.01);
  for (const bool forked : {false, true}) {
    SCOPED_TRACE(forked);
    int reported = 0;
    bool stop = false;
    std::vector<int> todo = {0, 1, 2, 3};
    auto runner = forked ? process_runner(1) : serial_runner();
    runner->run(
        tasks, todo,
        [&](const TaskEnd&) {
          ++reported;
          stop = true;  // as a signal handler would
        },
        [&] { return stop; });
    EXPECT_EQ(reported, 1);
  }
}

TEST(StudyTask, AvailableCoresIsPositive) { EXPECT_GE(available_cores(), 1); }

// --sweep values: lists, log ranges A..B/N, linear ranges A..B:STEP.
TEST(StudySweepGrammar, ListsAndRanges) {
  const ParamSweep a = parse_sweep("crank.lof.speed=157.08..523.6:52.36");
  EXPECT_EQ(a.key, "crank.lof.speed");
  ASSERT_EQ(a.values.size(), 8u);
  EXPECT_EQ(a.values.front(), "157.08");
  // A + k S rounded once (fma), written with the decimals A and S have: the
  // value the user meant, within 1e-9 S of the double
  for (std::size_t k = 0; k < a.values.size(); ++k)
    EXPECT_NEAR(std::stod(a.values[k]), std::fma(static_cast<double>(k), 52.36, 157.08),
                1e-9 * 52.36);
  EXPECT_EQ(a.values[3], "314.16");
  EXPECT_EQ(a.values.back(), "523.6");
  // not 157.07999999999998 (the nearest double to 104.72 + 52.36 printed in full)
  EXPECT_EQ(parse_sweep("crank.lof.speed=104.72..418.88:52.36").values[1], "157.08");
  // an exponent gives no decimals to go by: the shortest exact text
  EXPECT_EQ(parse_sweep("x.y=1e-1..3e-1:1e-1").values.size(), 3u);
  const ParamSweep b = parse_sweep("main*.clearance=1e-5..1e-4/3,2e-4,[1, 2]");
  EXPECT_EQ(b.values,
            (std::vector<std::string>{"1e-5", "3.16227766e-05", "1e-4", "2e-4", "[1, 2]"}));
  EXPECT_EQ(parse_sweep("x.y=1..2:1").values, (std::vector<std::string>{"1", "2"}));
  for (const char* bad : {"x.y", "=1", "x.y=", "x.y=1,,2", "x.y=2..1:1", "x.y=1..2:0",
                          "x.y=1..2:-1", "x.y=a..2:1", "x.y=1..1e9:1e-3"}) {
    SCOPED_TRACE(bad);
    try {
      parse_sweep(bad);
      ADD_FAILURE() << "accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("--sweep"), std::string::npos) << e.what();
    }
  }
}
