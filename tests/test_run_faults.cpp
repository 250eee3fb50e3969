// `evas run` under faults, part one: a disk that fills up (injected, and a real
// small tmpfs when the test runs as root), signals, a wall-time limit, rows
// flushed on a timer, the end time and the progress line. The tests run the
// real `evas` program (found next to the tests folder of the build) in
// temporary folders (helpers: run_faults_support.h; part two:
// test_run_faults_output.cpp).
#include "run_faults_support.h"

// ---------------------------------------------------------------------------
// 1. Full disk

// A completed run reports its peak memory (VmHWM of the evas process) in
// summary.json: a positive number of megabytes, and not the test's own.
TEST(RunFaults, SummaryReportsPeakMemory) {
  TempFolder tmp;
  write_text(tmp.path() / "s.yaml", demo_scene("mem", "0.05", "1e-3"));
  const fs::path out = tmp.path() / "out";
  const Outcome o = run_evas({"run", (tmp.path() / "s.yaml").string(), "--out", out.string(), "-q"},
                             tmp.path() / "log");
  ASSERT_EQ(o.code, 0) << o.log;
  const std::string json = read_text(out / "summary.json");
  const std::string key = "\"peak_memory_mb\": ";
  const auto p = json.find(key);
  ASSERT_NE(p, std::string::npos) << json;
  const double mb = std::stod(json.substr(p + key.size()));
  std::printf("[ measured ] demo scene: peak memory %.1f MB\n", mb);
  EXPECT_GT(mb, 1.0);
  EXPECT_LT(mb, 2048.0);
}

TEST(RunFaults, InjectedFullDiskKeepsFlushedRows) {
  // The disk is "full" once 300 rows are on disk: the space the writer keeps
  // allocated beyond the end of the file cannot be renewed, and every write
  // beyond the space the file owns fails with ENOSPC.
  TempFolder tmp;
  write_text(tmp.path() / "s.yaml", demo_scene("full", "0.6", "5e-4"));  // 1201 rows
  const fs::path out = tmp.path() / "out";
  const Outcome o = run_evas({"run", (tmp.path() / "s.yaml").string(), "--out", out.string(), "-q"},
                             tmp.path() / "log", {"EVAS_FAULT_WRITE_AFTER_ROWS=300"});
  EXPECT_EQ(o.code, 2) << o.log;
  EXPECT_TRUE(contains(o.log, "evas run: FAILED: results file " + (out / "results.h5").string() +
                                  ": cannot write: No space left on device"))
      << o.log;
  const ResultsData d = read_results((out / "results.h5").string());
  EXPECT_EQ(d.status.rfind("failed: results file ", 0), 0u) << d.status;
  EXPECT_TRUE(contains(d.status, "No space left on device")) << d.status;
  // every row flushed before the disk filled (flushes of 256 rows, or on the 1 s timer)
  EXPECT_GE(d.time.size(), 300u);
  EXPECT_LT(d.time.size(), 1201u);
  EXPECT_TRUE(contains(o.log, "the file keeps " + std::to_string(d.time.size()) + " rows"))
      << o.log;
  for (std::size_t i = 0; i < d.time.size(); ++i) ASSERT_NEAR(d.time[i], 5e-4 * i, 1e-12);
  std::printf("[ measured ] injected ENOSPC: exit %d, %zu of 1201 rows kept\n", o.code,
              d.time.size());
  const std::string json = read_text(out / "summary.json");
  EXPECT_TRUE(contains(json, "\"status\": \"failed: results file")) << json;
  EXPECT_TRUE(contains(json, "\"rows\": " + std::to_string(d.time.size()))) << json;
  expect_no_leftovers(out);
}

TEST(RunFaults, InjectedWriteErrorDoesNotCrash) {
  // Once 300 rows are on disk every write fails with EIO: HDF5 1.10 would crash
  // closing such a file; the writer moves it into memory instead, and the file
  // on disk keeps the rows of the flushes before.
  TempFolder tmp;
  write_text(tmp.path() / "s.yaml", demo_scene("eio", "0.6", "5e-4"));
  const fs::path out = tmp.path() / "out";
  const Outcome o =
      run_evas({"run", (tmp.path() / "s.yaml").string(), "--out", out.string(), "-q"},
               tmp.path() / "log", {"EVAS_FAULT_WRITE_AFTER_ROWS=300", "EVAS_FAULT_WRITE_EIO=1"});
  EXPECT_EQ(o.code, 2) << o.log;  // not 1011 (SIGSEGV)
  EXPECT_TRUE(contains(o.log, "results file " + (out / "results.h5").string() +
                                  ": cannot write: Input/output error"))
      << o.log;
  EXPECT_TRUE(contains(o.log, "could not be completed")) << o.log;
  const ResultsData d = read_results((out / "results.h5").string());
  EXPECT_EQ(d.status, "running");  // the status could not be written
  EXPECT_GE(d.time.size(), 300u);
  EXPECT_LT(d.time.size(), 1201u);
  for (std::size_t i = 0; i < d.time.size(); ++i) ASSERT_NEAR(d.time[i], 5e-4 * i, 1e-12);
  std::printf("[ measured ] injected EIO: exit %d, %zu rows readable\n", o.code, d.time.size());
  const std::string json = read_text(out / "summary.json");
  EXPECT_TRUE(contains(json, "\"status\": \"failed: results file")) << json;
}

TEST(RunFaults, RealFullTmpfs) {
  if (geteuid() != 0) GTEST_SKIP() << "needs root to mount a small tmpfs";
  TempFolder tmp;
  const fs::path mnt = tmp.path() / "small";
  fs::create_directory(mnt);
  if (mount("tmpfs", mnt.c_str(), "tmpfs", 0, "size=512k") != 0)
    GTEST_SKIP() << "mount -t tmpfs -o size=512k failed: " << std::strerror(errno);
  struct Unmount {
    fs::path p;
    ~Unmount() { umount2(p.c_str(), MNT_DETACH); }
  } unmount{mnt};
  // 40 001 rows of 25 channels: far more than 512 kB even compressed
  write_text(tmp.path() / "s.yaml", demo_scene("tmpfs", "0.4", "1e-5"));
  const fs::path out = mnt / "out";
  const Outcome o = run_evas({"run", (tmp.path() / "s.yaml").string(), "--out", out.string(), "-q"},
                             tmp.path() / "log");
  EXPECT_EQ(o.code, 2) << o.log;
  EXPECT_TRUE(contains(o.log, "results file " + (out / "results.h5").string())) << o.log;
  EXPECT_TRUE(contains(o.log, "No space left on device")) << o.log;
  const ResultsData d = read_results((out / "results.h5").string());
  EXPECT_EQ(d.status.rfind("failed: results file ", 0), 0u) << d.status;
  EXPECT_GT(d.time.size(), 256u);
  for (std::size_t i = 0; i < d.time.size(); ++i) ASSERT_NEAR(d.time[i], 1e-5 * i, 1e-12);
  std::string why;
  if (have_python3()) {
    EXPECT_TRUE(json_valid(out / "summary.json", why)) << why;
  }
  EXPECT_TRUE(contains(read_text(out / "summary.json"), "\"status\": \"failed: results file"));
  std::printf("[ measured ] real full tmpfs (512 kB): exit %d, %zu rows kept\n", o.code,
              d.time.size());
  expect_no_leftovers(out);
}

// ---------------------------------------------------------------------------
// 2. Signals, 3. rows flushed on a timer, 4. wall-time limit

namespace {

// Starts a sparse run, waits until its first row is on disk, sends `sig`.
void expect_signal_stops_run(int sig, const std::string& name, const std::string& integrator) {
  TempFolder tmp;
  const fs::path out = tmp.path() / "out";
  const pid_t pid = spawn_evas({"run", sparse_scene(tmp.path()).string(), "--out", out.string(),
                                "-q", "--integrator", integrator},
                               tmp.path() / "log");
  const double waited = wait_for([&] { return rows_now(out / "results.h5") >= 1; }, 60.0);
  ASSERT_GE(waited, 0.0) << read_text(tmp.path() / "log");
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // well into the steps
  const auto t0 = Clock::now();
  kill(pid, sig);
  const int code = wait_code(pid);
  const double stop_seconds = seconds_since(t0);
  const std::string log = read_text(tmp.path() / "log");
  EXPECT_EQ(code, 128 + sig) << log;
  EXPECT_LT(stop_seconds, 5.0);
  EXPECT_TRUE(contains(log, "evas run: FAILED: interrupted (" + name + ") at t = ")) << log;
  const ResultsData d = read_results((out / "results.h5").string());
  EXPECT_EQ(d.status.rfind("failed: interrupted (" + name + ") at t = ", 0), 0u) << d.status;
  EXPECT_EQ(d.time.size(), 1u);
  const std::string json = read_text(out / "summary.json");
  EXPECT_TRUE(contains(json, "\"status\": \"failed: interrupted (" + name + ")")) << json;
  EXPECT_FALSE(contains(json, "\"steps\": 0,")) << json;
  std::printf("[ measured ] %s (%s): exit %d, stopped %.3f s after the signal\n", name.c_str(),
              integrator.c_str(), code, stop_seconds);
  expect_no_leftovers(out);
}

}  // namespace

TEST(RunFaults, SigtermStopsBetweenOutputs) { expect_signal_stops_run(SIGTERM, "SIGTERM", "ida"); }
TEST(RunFaults, SighupStopsBetweenOutputs) { expect_signal_stops_run(SIGHUP, "SIGHUP", "cvode"); }
TEST(RunFaults, SigintStopsBetweenOutputs) { expect_signal_stops_run(SIGINT, "SIGINT", "ida"); }

TEST(RunFaults, RowsReachTheDiskOnATimer) {
  // The t = 0 row is the only one for minutes: it must be on disk within about
  // a second of being appended all the same.
  TempFolder tmp;
  const fs::path out = tmp.path() / "out";
  const pid_t pid = spawn_evas(
      {"run", sparse_scene(tmp.path()).string(), "--out", out.string(), "-q"}, tmp.path() / "log");
  const double created = wait_for([&] { return rows_now(out / "results.h5") >= 0; }, 60.0);
  ASSERT_GE(created, 0.0) << read_text(tmp.path() / "log");
  const double row = wait_for([&] { return rows_now(out / "results.h5") >= 1; }, 10.0);
  kill(pid, SIGTERM);
  EXPECT_EQ(wait_code(pid), 128 + SIGTERM);
  EXPECT_GE(row, 0.0) << "the first row never reached the disk";
  EXPECT_LT(row, 3.0);
  std::printf("[ measured ] first row on disk %.2f s after the file was created\n", row);
}

TEST(RunFaults, WallTimeLimit) {
  TempFolder tmp;
  const fs::path out = tmp.path() / "out";
  const Outcome o = run_evas(
      {"run", sparse_scene(tmp.path()).string(), "--out", out.string(), "-q", "--max-wall", "2"},
      tmp.path() / "log");
  EXPECT_EQ(o.code, 2) << o.log;
  EXPECT_TRUE(contains(o.log, "FAILED: wall-time limit 2 s reached at t = ")) << o.log;
  EXPECT_TRUE(contains(o.log, ", last step h = ")) << o.log;
  EXPECT_LT(o.seconds, 30.0);
  const ResultsData d = read_results((out / "results.h5").string());
  EXPECT_EQ(d.status.rfind("failed: wall-time limit 2 s reached at t = ", 0), 0u) << d.status;
  EXPECT_EQ(d.time.size(), 1u);
  std::printf("[ measured ] --max-wall 2: exit %d after %.2f s\n", o.code, o.seconds);
}

TEST(RunFaults, EndTimeMustBeFiniteAndAfterTheStart) {
  // NaN failed the ordering test with a message about the start time; inf
  // reached the output grid's row limit. Both now name what is wrong.
  TempFolder tmp;
  const std::string scene = sparse_scene(tmp.path()).string();
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"nan", "--t-end: nan is not a finite time"},
      {"inf", "--t-end: inf is not a finite time"},
      {"-1", "--t-end must be after the start time"}};
  for (const auto& [value, message] : cases) {
    const fs::path out = tmp.path() / ("out" + value);
    const Outcome o =
        run_evas({"run", scene, "--out", out.string(), "-q", "--t-end", value}, tmp.path() / "log");
    EXPECT_EQ(o.code, 1) << value << ": " << o.log;
    EXPECT_TRUE(contains(o.log, message)) << value << ": " << o.log;
    EXPECT_FALSE(fs::exists(out / "results.h5")) << value;
  }
}

TEST(RunFaults, ProgressShowsTheStep) {
  TempFolder tmp;
  write_text(tmp.path() / "s.yaml", demo_scene("progress", "0.01", "5e-4"));
  const Outcome o =
      run_evas({"run", (tmp.path() / "s.yaml").string(), "--out", (tmp.path() / "out").string()},
               tmp.path() / "log");
  EXPECT_EQ(o.code, 0) << o.log;
  EXPECT_TRUE(contains(o.log, " steps  step ")) << o.log;
}

// ---------------------------------------------------------------------------
// 5. Two runs into one folder
