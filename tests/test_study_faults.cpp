// Faults of a study's runs and workers, end to end: a run that crashes or
// hangs (the test plug-in's "crash-at-output" and "stuck-at-output",
// tests/plugins/bad_state.cpp) fails alone in forked workers and on MPI ranks;
// a stop that reaches rank 0 alone ends the whole MPI job at once; a signal to
// one worker rank fails its task only; mpirun refuses commands other than
// `evas study`; and a resumed sweep runs again what its edited scene changes.
#include <algorithm>
#include <cmath>

#include "io/hdf5_util.h"
#include "run_faults_support.h"

using namespace run_faults;

namespace {

const std::string kEngine = std::string(EVAS_SOURCE_DIR) + "/validation/engine/engine.yaml";

// A sweep of `points` speeds over `cases` (each "--case SPEC"), plug-in loaded.
std::vector<std::string> sweep_args(const std::string& t_end, const std::string& speeds,
                                    const std::vector<std::string>& cases, const fs::path& out) {
  std::vector<std::string> a = {"study",
                                "sweep",
                                kEngine,
                                "--t-end",
                                t_end,
                                "--sweep",
                                "crank.lof.speed=" + speeds,
                                "--channels",
                                "main1.fx",
                                "--no-plot",
                                "--out",
                                out.string(),
                                "--plugin",
                                EVAS_BAD_STATE_PLUGIN};
  for (const auto& c : cases) {
    a.push_back("--case");
    a.push_back(c);
  }
  return a;
}

std::vector<std::string> with(std::vector<std::string> a, const std::vector<std::string>& more) {
  a.insert(a.end(), more.begin(), more.end());
  return a;
}

int count(const std::string& s, const std::string& part) {
  int n = 0;
  for (auto p = s.find(part); p != std::string::npos; p = s.find(part, p + 1)) ++n;
  return n;
}

#ifdef EVAS_TEST_MPI
// Starts `mpirun -n RANKS evas ARGS...` (its output to `log`); returns mpirun's pid.
pid_t spawn_mpirun(int ranks, const std::vector<std::string>& args, const fs::path& log) {
  std::vector<std::string> argv_s = {"mpirun", "--allow-run-as-root", "--oversubscribe",
                                     "-n",     std::to_string(ranks), evas_binary().string()};
  argv_s.insert(argv_s.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_s) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    output_to(log);
    setpgid(0, 0);  // a group of its own: the test can end it whole
    for (int sig : {SIGHUP, SIGINT, SIGTERM}) signal(sig, SIG_DFL);
    execvp("mpirun", argv.data());
    _exit(127);
  }
  return pid;
}

// The pid of MPI rank `rank` among mpirun's children (-1 if not yet started).
pid_t rank_pid(pid_t mpirun, int rank) {
  const std::string want = "OMPI_COMM_WORLD_RANK=" + std::to_string(rank);
  for (pid_t k : children_of(mpirun)) {
    std::ifstream env("/proc/" + std::to_string(k) + "/environ");
    std::string entry;
    while (std::getline(env, entry, '\0'))
      if (entry == want) return k;
  }
  return -1;
}

// Waits up to `timeout` s for the process; its wait_code, or -2 after killing
// its whole group when it did not end in time.
int wait_code_within(pid_t pid, double timeout) {
  const auto t0 = Clock::now();
  int st = 0;
  while (seconds_since(t0) < timeout) {
    const pid_t r = waitpid(pid, &st, WNOHANG);
    if (r == pid) return WIFEXITED(st) ? WEXITSTATUS(st) : 1000 + WTERMSIG(st);
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  ::kill(-pid, SIGKILL);
  waitpid(pid, &st, 0);
  return -2;
}
#endif

}  // namespace

// A run that dies of SIGSEGV in a forked worker: that task fails with the
// signal, every other task completes, and the study ends normally.
TEST(StudyFaults, ACrashingRunFailsAloneInForkedWorkers) {
  TempFolder tmp;
  const fs::path out = tmp.path() / "c";
  const Outcome o =
      run_evas(with(sweep_args("0.01", "300,320",
                               {"generalized-alpha step=2e-5", "crash-at-output step=2e-5"}, out),
                    {"--jobs", "2"}),
               tmp.path() / "c.log");
  ASSERT_EQ(o.code, 0) << o.log;
  const std::string md = read_text(out / "sweep.md");
  EXPECT_EQ(count(md, "died of signal 11"), 2) << md;
  EXPECT_EQ(count(read_text(out / "sweep.csv"), ",completed,"), 2) << md;
}

// A run that never returns (and never looks at the stop flag) is killed at the
// hard limit of its --max-wall (1.5 x 2 + 10 s); the other task completes.
TEST(StudyFaults, AStuckRunIsKilledAtTheHardLimit) {
  TempFolder tmp;
  const fs::path out = tmp.path() / "s";
  const Outcome o =
      run_evas(with(sweep_args("0.01", "300",
                               {"generalized-alpha step=2e-5", "stuck-at-output step=2e-5"}, out),
                    {"--jobs", "2", "--max-wall", "2"}),
               tmp.path() / "s.log");
  ASSERT_EQ(o.code, 0) << o.log;
  const std::string md = read_text(out / "sweep.md");
  EXPECT_EQ(count(md, "timed out: the worker was killed after"), 1) << md;
  EXPECT_EQ(count(read_text(out / "sweep.csv"), ",completed,"), 1) << md;
  EXPECT_LT(o.seconds, 60.0);
}

// A resumed sweep keeps a task file only when the task computes the same: after
// an edit (--t-end here) every task runs again.
TEST(StudyFaults, AResumedSweepRunsAgainWhatAnEditChanged) {
  TempFolder tmp;
  const fs::path out = tmp.path() / "r";
  auto args = [&](const std::string& t_end) {
    return std::vector<std::string>{"study",
                                    "sweep",
                                    kEngine,
                                    "--t-end",
                                    t_end,
                                    "--sweep",
                                    "crank.lof.speed=300,320",
                                    "--channels",
                                    "main1.fx",
                                    "--no-plot",
                                    "--jobs",
                                    "1",
                                    "--out",
                                    out.string()};
  };
  ASSERT_EQ(run_evas(args("0.01"), tmp.path() / "1.log").code, 0);
  const Outcome same = run_evas(with(args("0.01"), {"--resume"}), tmp.path() / "2.log");
  ASSERT_EQ(same.code, 0) << same.log;
  EXPECT_TRUE(contains(same.log, "0 to run")) << same.log;
  // a different --max-wall computes the same: still nothing to run
  const Outcome limit =
      run_evas(with(args("0.01"), {"--resume", "--max-wall", "100"}), tmp.path() / "3.log");
  ASSERT_EQ(limit.code, 0) << limit.log;
  EXPECT_TRUE(contains(limit.log, "0 to run")) << limit.log;
  const Outcome edited = run_evas(with(args("0.012"), {"--resume"}), tmp.path() / "4.log");
  ASSERT_EQ(edited.code, 0) << edited.log;
  EXPECT_TRUE(contains(edited.log, "2 to run")) << edited.log;
}

#ifdef EVAS_TEST_MPI

// On MPI ranks: the crashing runs fail alone (in the ranks' forked workers)
// and a stuck one is killed at the hard limit.
TEST(StudyFaults, CrashingAndStuckRunsFailAloneOnMpiRanks) {
  TempFolder tmp;
  const fs::path out = tmp.path() / "m";
  const pid_t pid =
      spawn_mpirun(2,
                   with(sweep_args("0.01", "300,320",
                                   {"generalized-alpha step=2e-5", "crash-at-output step=2e-5",
                                    "stuck-at-output step=2e-5"},
                                   out),
                        {"--max-wall", "2"}),
                   tmp.path() / "m.log");
  ASSERT_EQ(wait_code_within(pid, 120.0), 0) << read_text(tmp.path() / "m.log");
  const std::string md = read_text(out / "sweep.md");
  EXPECT_EQ(count(md, "died of signal 11"), 2) << md;
  EXPECT_EQ(count(md, "timed out: the worker was killed after"), 2) << md;
  EXPECT_EQ(count(read_text(out / "sweep.csv"), ",completed,"), 2) << md;
}

// SIGTERM to rank 0 alone (as a scheduler may send it): rank 0 cancels what
// the other rank runs, so the job ends at once, not when that run would end
// (about a minute here); the finished points are kept, the sweep is marked
// interrupted.
TEST(StudyFaults, AStopOfRankZeroAloneEndsTheMpiJob) {
  TempFolder tmp;
  const fs::path out = tmp.path() / "z";
  const pid_t pid =
      spawn_mpirun(2, sweep_args("30", "300,320,340", {"generalized-alpha step=2e-5"}, out),
                   tmp.path() / "z.log");
  pid_t r0 = -1, r1 = -1;
  // both ranks run: each has its forked worker
  ASSERT_GE(wait_for(
                [&] {
                  r0 = rank_pid(pid, 0);
                  r1 = rank_pid(pid, 1);
                  return r0 > 0 && r1 > 0 && !children_of(r0).empty() && !children_of(r1).empty();
                },
                60.0),
            0.0)
      << read_text(tmp.path() / "z.log");
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  const auto t0 = Clock::now();
  ::kill(r0, SIGTERM);
  const int code = wait_code_within(pid, 20.0);
  EXPECT_NE(code, -2) << "the job did not end within 20 s of the stop\n"
                      << read_text(tmp.path() / "z.log");
  EXPECT_NE(code, 0);
  EXPECT_LT(seconds_since(t0), 20.0);
  h5::Handle f = h5::open_file((out / "sweep.h5").string());
  EXPECT_EQ(h5::read_string_attribute(f, "status"), "interrupted");
}

// SIGTERM to worker rank 1 alone: its task fails with the signal, rank 0 runs
// the rest, the study ends normally.
TEST(StudyFaults, ASignalToOneWorkerRankFailsItsTaskOnly) {
  TempFolder tmp;
  const fs::path out = tmp.path() / "w";
  const pid_t pid =
      spawn_mpirun(2, sweep_args("1.0", "300,320,340", {"generalized-alpha step=2e-5"}, out),
                   tmp.path() / "w.log");
  pid_t r1 = -1;
  ASSERT_GE(wait_for(
                [&] {
                  r1 = rank_pid(pid, 1);
                  return r1 > 0 && !children_of(r1).empty();
                },
                60.0),
            0.0)
      << read_text(tmp.path() / "w.log");
  ::kill(r1, SIGTERM);
  ASSERT_EQ(wait_code_within(pid, 180.0), 0) << read_text(tmp.path() / "w.log");
  const std::string md = read_text(out / "sweep.md");
  EXPECT_TRUE(contains(md, "rank 1 was stopped by signal 15")) << md;
  EXPECT_EQ(count(read_text(out / "sweep.csv"), ",completed,"), 2) << md;
}

// Only `evas study` runs over ranks: any other command under mpirun is refused
// (it would run once per rank).
TEST(StudyFaults, MpirunRefusesOtherCommands) {
  TempFolder tmp;
  const pid_t pid =
      spawn_mpirun(2, {"run", kEngine, "--out", (tmp.path() / "o").string()}, tmp.path() / "o.log");
  const int code = wait_code_within(pid, 60.0);
  const std::string log = read_text(tmp.path() / "o.log");
  EXPECT_NE(code, 0) << log;
  EXPECT_NE(code, -2) << log;
  EXPECT_EQ(count(log, "`evas run` does not use MPI ranks"), 1) << log;
  EXPECT_FALSE(fs::exists(tmp.path() / "o"));
}

#endif
