// `evas study sweep` end to end on the paper's engine (validation/engine):
// the sweep file, identical files from one process, forked workers and MPI
// ranks, a killed worker, an interrupted and resumed sweep, batch array jobs
// (--point, --merge) and the input errors of a sweep.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "io/hdf5_util.h"
#include "post/order_spectrum.h"
#include "run_faults_support.h"

using namespace run_faults;

namespace {

const std::string kEngine = std::string(EVAS_SOURCE_DIR) + "/validation/engine/engine.yaml";
// 3000 to 4000 rpm, 0.06 s: 1.5 to 2 engine cycles per point, a spectrum of the last
const std::vector<std::string> kSweep = {"study",
                                         "sweep",
                                         kEngine,
                                         "--t-end",
                                         "0.06",
                                         "--sweep",
                                         "crank.lof.speed=314.16..418.88:52.36",
                                         "--channels",
                                         "main*.fx,main*.fy",
                                         "--no-plot"};

std::vector<std::string> with(std::vector<std::string> a, const std::vector<std::string>& more) {
  a.insert(a.end(), more.begin(), more.end());
  return a;
}

// A stability study on the engine over oil viscosities (the paper's method,
// effective-mass iteration, fixed steps).
std::vector<std::string> stability_args(const std::string& viscosities,
                                        const std::string& bisections) {
  return {"study",
          "stability",
          kEngine,
          "--t-end",
          "0.004",
          "--case",
          "linear-acceleration step_control=fixed iteration=effective-mass",
          "--step-range",
          "2e-6:1e-4",
          "--sweep",
          viscosities,
          "--bisections",
          bisections,
          "--channels",
          "main*.fy",
          "--reference",
          "ida rtol=1e-6 atol=1e-10",
          "--no-plot"};
}

// Raw bytes of a dataset (doubles, integers or strings), for exact comparison.
std::string dataset_bytes(hid_t f, const std::string& name) {
  std::vector<hsize_t> dims;
  if (name.find("status") != std::string::npos || name.find("label") != std::string::npos ||
      name.find("names") != std::string::npos || name.find("value0") != std::string::npos) {
    std::string all;
    for (const auto& s : h5::read_strings(f, name)) all += s + '\n';
    return all;
  }
  const std::vector<double> v = h5::read_doubles(f, name, dims);
  std::string out(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(double));
  for (auto d : dims) out += "|" + std::to_string(d);
  return out;
}

// The datasets of a sweep file that must not depend on how it was run: every
// task's channels, status and counts, the spectra, the grid, the Campbell data.
std::vector<std::string> sweep_datasets(int tasks) {
  std::vector<std::string> names = {"grid/value0",           "channels/names",
                                    "tasks/status",          "tasks/rows",
                                    "tasks/stats/steps",     "tasks/stats/residual_evals",
                                    "tasks/stats/last_step", "tasks/mean_rpm",
                                    "orders/order",          "orders/amplitude",
                                    "campbell/frequency"};
  for (int k = 0; k < tasks; ++k) {
    char g[32];
    std::snprintf(g, sizeof g, "channels/%04d/", k);
    for (const char* d : {"time", "crank_angle", "values"}) names.push_back(g + std::string(d));
  }
  return names;
}

void expect_same_files(const fs::path& a, const fs::path& b, const std::vector<std::string>& sets) {
  h5::Handle fa = h5::open_file(a.string()), fb = h5::open_file(b.string());
  for (const auto& s : sets) {
    const std::string x = dataset_bytes(fa, s), y = dataset_bytes(fb, s);
    EXPECT_TRUE(x == y) << s << " differs (" << x.size() << " and " << y.size() << " bytes)";
  }
}

std::string attribute(const fs::path& file, const std::string& name) {
  h5::Handle f = h5::open_file(file.string());
  return h5::read_string_attribute(f, name);
}

}  // namespace

// One process against two forked workers: the same file, bit for bit; the
// sweep file holds what it claims.
TEST(StudySweep, ForkedWorkersWriteTheSerialFile) {
  TempFolder tmp;
  const Outcome serial = run_evas(
      with(kSweep, {"--jobs", "1", "--out", (tmp.path() / "s").string()}), tmp.path() / "s.log");
  ASSERT_EQ(serial.code, 0) << serial.log;
  const Outcome forked = run_evas(
      with(kSweep, {"--jobs", "2", "--out", (tmp.path() / "j").string()}), tmp.path() / "j.log");
  ASSERT_EQ(forked.code, 0) << forked.log;
  const fs::path a = tmp.path() / "s" / "sweep.h5", b = tmp.path() / "j" / "sweep.h5";
  expect_same_files(a, b, sweep_datasets(3));
  EXPECT_EQ(attribute(a, "runner"), "serial");
  EXPECT_EQ(attribute(b, "runner"), "2 local worker processes");
  EXPECT_EQ(attribute(b, "status"), "completed");

  h5::Handle f = h5::open_file(a.string());
  std::vector<hsize_t> dims;
  // the mean speed of each point is the swept speed (rad/s) in rpm
  const auto rpm = h5::read_doubles(f, "tasks/mean_rpm", dims);
  ASSERT_EQ(rpm.size(), 3u);
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(rpm[k], (314.16 + 52.36 * k) * 60.0 / (2.0 * M_PI), 1e-6 * rpm[k]);
  // the spectra are those of the stored channels: order 1 of main1.fx at point 2
  const auto names = h5::read_strings(f, "channels/names");
  const auto order = h5::read_doubles(f, "orders/order", dims);
  const auto amp = h5::read_doubles(f, "orders/amplitude", dims);
  ASSERT_EQ(dims.size(), 3u);
  ASSERT_EQ(dims[1], names.size());
  const auto theta = h5::read_doubles(f, "channels/0002/crank_angle", dims);
  const auto values = h5::read_doubles(f, "channels/0002/values", dims);
  std::vector<double> fx;
  for (std::size_t r = 0; r < theta.size(); ++r) fx.push_back(values[r * names.size()]);
  const OrderSpectrum sp = order_spectrum(theta, fx, 1);
  ASSERT_EQ(order[2], 1.0);
  EXPECT_EQ(amp[(2 * names.size() + 0) * order.size() + 2], sp.amplitude[2]);
  EXPECT_GT(sp.amplitude[2], 0.0);
  // Campbell data: the six mount modes of Case 1 first, then elastic modes
  const auto kind = h5::read_strings(f, "campbell/kind");
  ASSERT_GE(kind.size(), 7u);
  for (int k = 0; k < 6; ++k) EXPECT_EQ(kind[k], "mount");
  EXPECT_EQ(kind[6], "elastic");
  EXPECT_TRUE(fs::exists(tmp.path() / "s" / "points" / "0002.h5"));
  EXPECT_TRUE(fs::exists(tmp.path() / "s" / "sweep.csv"));
}

// mpirun with 2 and 3 ranks (3 on 2 cores: oversubscribed): the serial files,
// for a sweep and for a work-precision study.
TEST(StudySweep, MpiRanksWriteTheSerialFiles) {
#ifndef EVAS_TEST_MPI
  GTEST_SKIP() << "evas was built without MPI (libopenmpi-dev); the build of `make test` has it";
#else
  TempFolder tmp;
  const std::string evas = evas_binary().string();
  auto mpirun = [&](int ranks, const std::vector<std::string>& args, const std::string& log) {
    std::string cmd =
        "mpirun --allow-run-as-root --oversubscribe -n " + std::to_string(ranks) + " " + evas;
    for (const auto& a : args) cmd += " '" + a + "'";
    cmd += " >" + (tmp.path() / log).string() + " 2>&1";
    const int st = std::system(cmd.c_str());
    return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  };
  const Outcome serial = run_evas(
      with(kSweep, {"--jobs", "1", "--out", (tmp.path() / "s").string()}), tmp.path() / "s.log");
  ASSERT_EQ(serial.code, 0) << serial.log;
  for (int ranks : {2, 3}) {
    SCOPED_TRACE(ranks);
    const std::string out = (tmp.path() / ("m" + std::to_string(ranks))).string();
    ASSERT_EQ(mpirun(ranks, with(kSweep, {"--out", out}), "m.log"), 0)
        << read_text(tmp.path() / "m.log");
    expect_same_files(tmp.path() / "s" / "sweep.h5", fs::path(out) / "sweep.h5", sweep_datasets(3));
    EXPECT_EQ(attribute(fs::path(out) / "sweep.h5", "runner"),
              "MPI, " + std::to_string(ranks) + " ranks");
  }
  const std::vector<std::string> wp = {"study",
                                       "work-precision",
                                       kEngine,
                                       "--t-end",
                                       "0.02",
                                       "--window",
                                       "all",
                                       "--channels",
                                       "main*.fy",
                                       "--case",
                                       "ida rtol=1e-3,1e-4,1e-5",
                                       "--case",
                                       "generalized-alpha step=2e-5",
                                       "--reference",
                                       "ida rtol=1e-7 atol=1e-11",
                                       "--no-plot"};
  const Outcome wp_serial =
      run_evas(with(wp, {"--out", (tmp.path() / "wps").string()}), tmp.path() / "wps.log");
  ASSERT_EQ(wp_serial.code, 0) << wp_serial.log;
  const std::string out = (tmp.path() / "wpm").string();
  ASSERT_EQ(mpirun(3, with(wp, {"--out", out}), "wpm.log"), 0) << read_text(tmp.path() / "wpm.log");
  expect_same_files(tmp.path() / "wps" / "study.h5", fs::path(out) / "study.h5",
                    {"cases/label", "cases/status", "cases/error", "cases/rows",
                     "cases/stats/steps", "cases/stats/residual_evals", "reference/values"});
  const std::vector<std::string> st = stability_args("main*.viscosity=0.005,0.01,0.02", "2");
  const Outcome st_serial =
      run_evas(with(st, {"--out", (tmp.path() / "sts").string()}), tmp.path() / "sts.log");
  ASSERT_EQ(st_serial.code, 0) << st_serial.log;
  const std::string stm = (tmp.path() / "stm").string();
  ASSERT_EQ(mpirun(2, with(st, {"--out", stm}), "stm.log"), 0) << read_text(tmp.path() / "stm.log");
  EXPECT_EQ(read_text(tmp.path() / "sts" / "stability.csv"),
            read_text(fs::path(stm) / "stability.csv"));
#endif
}

// kill -9 of one worker: its point is recorded as failed with the signal, the
// other points complete, the study ends normally; a --merge keeps the reason.
TEST(StudySweep, AKilledWorkerIsRecordedAndTheOthersComplete) {
  TempFolder tmp;
  const pid_t pid = spawn_evas(
      {"study", "sweep", kEngine, "--t-end", "0.5", "--sweep", "crank.lof.speed=300,320,340",
       "--channels", "main1.fx", "--jobs", "2", "--no-plot", "--out", (tmp.path() / "k").string()},
      tmp.path() / "k.log");
  // a worker: a child that lives on (evas also forks short-lived readers of
  // HDF5 string attributes while it reads the scenes)
  pid_t victim = -1;
  ASSERT_GE(wait_for(
                [&] {
                  const auto before = children_of(pid);
                  std::this_thread::sleep_for(std::chrono::milliseconds(300));
                  for (pid_t k : children_of(pid))
                    if (std::find(before.begin(), before.end(), k) != before.end() &&
                        ::kill(k, SIGKILL) == 0) {
                      victim = k;
                      return true;
                    }
                  return false;
                },
                60.0),
            0.0);
  EXPECT_EQ(wait_code(pid), 0) << read_text(tmp.path() / "k.log");
  const std::string csv = read_text(tmp.path() / "k" / "sweep.csv");
  const std::string md = read_text(tmp.path() / "k" / "sweep.md");
  EXPECT_TRUE(contains(md, "worker pid " + std::to_string(victim) + " died of signal 9")) << md;
  int completed = 0;
  for (std::size_t p = csv.find(",completed,"); p != std::string::npos;
       p = csv.find(",completed,", p + 1))
    ++completed;
  EXPECT_EQ(completed, 2) << csv;
  // --merge rebuilds the files from points/: the reason stays
  const Outcome merged = run_evas(
      {"study", "sweep", kEngine, "--t-end", "0.5", "--sweep", "crank.lof.speed=300,320,340",
       "--channels", "main1.fx", "--no-plot", "--merge", "--out", (tmp.path() / "k").string()},
      tmp.path() / "m.log");
  ASSERT_EQ(merged.code, 0) << merged.log;
  EXPECT_TRUE(contains(read_text(tmp.path() / "k" / "sweep.md"),
                       "worker pid " + std::to_string(victim) + " died of signal 9"));
}

// SIGTERM: the finished points stay (their files and a readable sweep file
// marked interrupted), exit 143; --resume runs only the rest, and the result
// equals an uninterrupted sweep's.
TEST(StudySweep, InterruptedSweepResumesWithoutRecomputing) {
  TempFolder tmp;
  const fs::path dir = tmp.path() / "r";
  const std::vector<std::string> args = with(kSweep, {"--jobs", "1", "--out", dir.string()});
  const pid_t pid = spawn_evas(args, tmp.path() / "r1.log");
  ASSERT_GE(wait_for([&] { return fs::exists(dir / "points" / "0000.h5"); }, 60.0), 0.0);
  ::kill(pid, SIGTERM);
  EXPECT_EQ(wait_code(pid), 143) << read_text(tmp.path() / "r1.log");
  EXPECT_EQ(attribute(dir / "sweep.h5", "status"), "interrupted");
  int kept = 0;
  for (const char* f : {"0000.h5", "0001.h5", "0002.h5"}) kept += fs::exists(dir / "points" / f);
  ASSERT_GE(kept, 1);
  ASSERT_LT(kept, 3) << "the sweep ended before the signal; the test needs a longer sweep";

  // a second sweep into the folder without --resume is refused
  const Outcome again = run_evas(args, tmp.path() / "r2.log");
  EXPECT_EQ(again.code, 1);
  EXPECT_TRUE(contains(again.log, "holds a sweep already")) << again.log;

  const Outcome resumed = run_evas(with(args, {"--resume"}), tmp.path() / "r3.log");
  ASSERT_EQ(resumed.code, 0) << resumed.log;
  EXPECT_TRUE(contains(resumed.log, std::to_string(3 - kept) + " to run")) << resumed.log;
  EXPECT_TRUE(
      contains(read_text(dir / "sweep.md"), std::to_string(kept) + " task(s) from an earlier run"));
  const Outcome fresh = run_evas(
      with(kSweep, {"--jobs", "1", "--out", (tmp.path() / "f").string()}), tmp.path() / "f.log");
  ASSERT_EQ(fresh.code, 0) << fresh.log;
  expect_same_files(dir / "sweep.h5", tmp.path() / "f" / "sweep.h5", sweep_datasets(3));
  EXPECT_EQ(attribute(dir / "sweep.h5", "status"), "completed");
}

// A batch array job: each task by --point, then --merge: the one-process file.
TEST(StudySweep, PointsAndMergeGiveTheSameFile) {
  TempFolder tmp;
  const fs::path dir = tmp.path() / "a";
  for (int i : {2, 0, 1}) {
    const Outcome o = run_evas(with(kSweep, {"--point", std::to_string(i), "--out", dir.string()}),
                               tmp.path() / "p.log");
    ASSERT_EQ(o.code, 0) << o.log;
    EXPECT_FALSE(fs::exists(dir / "sweep.h5"));
  }
  const Outcome bad =
      run_evas(with(kSweep, {"--point", "3", "--out", dir.string()}), tmp.path() / "p.log");
  EXPECT_EQ(bad.code, 1);
  EXPECT_TRUE(contains(bad.log, "--point 3: the sweep has 3 tasks (0 to 2)")) << bad.log;
  const Outcome merged =
      run_evas(with(kSweep, {"--merge", "--out", dir.string()}), tmp.path() / "m.log");
  ASSERT_EQ(merged.code, 0) << merged.log;
  const Outcome serial = run_evas(
      with(kSweep, {"--jobs", "1", "--out", (tmp.path() / "s").string()}), tmp.path() / "s.log");
  ASSERT_EQ(serial.code, 0) << serial.log;
  expect_same_files(dir / "sweep.h5", tmp.path() / "s" / "sweep.h5", sweep_datasets(3));
}

// Input errors of a sweep: named, before anything runs.
TEST(StudySweep, BadSweepsAreInputErrors) {
  TempFolder tmp;
  struct Bad {
    std::vector<std::string> args;
    std::string says;
  };
  const std::vector<Bad> bad = {
      {{"--sweep", "krank.lof.speed=100,200"}, "krank"},
      {{"--sweep", "crank.lof.speed=100,200", "--sweep", "crank.lof.speed=3"}, "swept twice"},
      {{"--sweep", "crank.lof.speed=100..50:10"}, "needs B >= A"},
      {{"--sweep", "crank.lof.speed=100,-100"}, "must not be negative"},
      // the engine fires: a crank at rest is refused as such (elements/plausibility.h)
      {{"--sweep", "crank.lof.speed=0"},
       "the cylinder fires (pressure_file) but the crank turns "
       "at 0 rad/s"},
      {{"--window", "all", "--sweep", "crank.lof.speed=100"}, "does not apply to a sweep"},
      {{"--norm", "rms", "--sweep", "crank.lof.speed=100"}, "--norm does not apply to a sweep"},
      {{"--orders", "1.25", "--sweep", "crank.lof.speed=100"}, "not a multiple of 0.5"},
      {{}, "missing --sweep"},
  };
  for (const auto& b : bad) {
    SCOPED_TRACE(b.says);
    std::vector<std::string> args = {"study", "sweep",     kEngine, "--t-end",
                                     "0.01",  "--no-plot", "--out", (tmp.path() / "x").string()};
    args.insert(args.end(), b.args.begin(), b.args.end());
    const Outcome o = run_evas(args, tmp.path() / "b.log");
    EXPECT_EQ(o.code, 1) << o.log;
    EXPECT_TRUE(contains(o.log, b.says)) << o.log;
    EXPECT_FALSE(fs::exists(tmp.path() / "x" / "points" / "0000.h5"));
  }
}

// Every point's scene is read before any run: a speed table that does not
// increase in time, a ramp down to standstill and a pressure map that does not
// cover the swept speeds are input errors naming the point and the range.
TEST(StudySweep, EveryPointIsCheckedBeforeAnyRun) {
  TempFolder tmp;
  const fs::path src = fs::path(EVAS_SOURCE_DIR) / "validation";
  std::string scene = read_text(kEngine);
  auto replace_all = [&](const std::string& from, const std::string& to) {
    for (auto p = scene.find(from); p != std::string::npos; p = scene.find(from, p + to.size()))
      scene.replace(p, from.size(), to);
  };
  replace_all("../bodies/", (src / "bodies").string() + "/");
  replace_all("speed: 314.159}", "speed_profile: [[0, 250], [0.1, 300]]}");
  replace_all("pressure_file: ../data/cylinder_pressure_3000rpm.txt",
              "pressure_map: " + (tmp.path() / "map.txt").string());
  const std::string table = (src / "data" / "cylinder_pressure_3000rpm.txt").string();
  write_text(tmp.path() / "map.txt", "2000 " + table + "\n3500 " + table + "\n");
  write_text(tmp.path() / "ramp.yaml", scene);
  struct Bad {
    std::string sweep, says;
  };
  for (const Bad& b : std::vector<Bad>{
           {"crank.lof.speed_profile=[[0, 250], [0.01, 300]],[[0, 300], [0, 400]]",
            "'speed_profile' times must increase strictly"},
           // a ramp down to standstill leaves the map's range first (without a map:
           // "down to standstill", test_crank_speed.cpp)
           {"crank.lof.speed_profile=[[0, 300], [0.01, 0]]", "the crank turns at 0 .. 2864.79 rpm"},
           {"crank.lof.speed_profile=[[0, 300], [0.01, 380]]", "covers 2000 .. 3500 rpm"}}) {
    SCOPED_TRACE(b.sweep);
    const Outcome o =
        run_evas({"study", "sweep", (tmp.path() / "ramp.yaml").string(), "--t-end", "0.01",
                  "--sweep", b.sweep, "--no-plot", "--out", (tmp.path() / "x").string()},
                 tmp.path() / "b.log");
    EXPECT_EQ(o.code, 1) << o.log;
    EXPECT_TRUE(contains(o.log, b.says)) << o.log;
    EXPECT_TRUE(contains(o.log, "--sweep point")) << o.log;
  }
  // the same scene within the map's range runs (a run-up point)
  const Outcome ok = run_evas({"study", "sweep", (tmp.path() / "ramp.yaml").string(), "--t-end",
                               "0.01", "--sweep", "crank.lof.speed_profile=[[0, 250], [0.01, 300]]",
                               "--no-plot", "--out", (tmp.path() / "ok").string()},
                              tmp.path() / "ok.log");
  EXPECT_EQ(ok.code, 0) << ok.log;
}

// The stability searches at the sweep values run side by side (--jobs 2, and
// under MPI in MpiRanksWriteTheSerialFiles): each makes the runs it makes alone.
TEST(StudySweep, StabilitySearchesInParallelGiveTheSerialTable) {
  TempFolder tmp;
  const std::vector<std::string> args = stability_args("main*.viscosity=0.005,0.02", "3");
  const Outcome serial =
      run_evas(with(args, {"--out", (tmp.path() / "s").string()}), tmp.path() / "s.log");
  ASSERT_EQ(serial.code, 0) << serial.log;
  const Outcome forked = run_evas(with(args, {"--jobs", "2", "--out", (tmp.path() / "j").string()}),
                                  tmp.path() / "j.log");
  ASSERT_EQ(forked.code, 0) << forked.log;
  const std::string a = read_text(tmp.path() / "s" / "stability.csv");
  EXPECT_EQ(a, read_text(tmp.path() / "j" / "stability.csv"));
  EXPECT_TRUE(contains(a, "bracketed") || contains(a, "stable up to HMAX")) << a;
  // one search per value: 1 reference + 2 + 3 bisections at most
  EXPECT_TRUE(contains(serial.log, "main*.viscosity = 0.02: h = ")) << serial.log;
}

// `evas plot waterfall|campbell|order-cuts SWEEP.h5` draws from the file what
// the sweep drew from its data: the same gnuplot script but for the output
// file's name (one code, plot/sweep_figures.h); and refuses what it cannot draw.
TEST(StudySweep, PlotDrawsTheSweepFiguresAgainFromTheFile) {
  TempFolder tmp;
  std::vector<std::string> args = kSweep;
  args.pop_back();  // draw the figures
  // the figure channels in the order asked for: main2.fy first, though main1.fx
  // comes first in the file
  const Outcome o = run_evas(
      with(args, {"--order-channels", "main2.fy,main1.fx", "--out", (tmp.path() / "s").string()}),
      tmp.path() / "s.log");
  ASSERT_EQ(o.code, 0) << o.log;
  const fs::path sweep = tmp.path() / "s" / "sweep.h5";
  auto text = [](const fs::path& p) {
    std::ifstream f(p);
    std::stringstream ss;
    ss << f.rdbuf();
    std::string t = ss.str();
    const auto at = t.find("set output ");
    if (at != std::string::npos) t.erase(at, t.find('\n', at) - at);
    return t;
  };
  for (const auto& [kind, extra] : std::vector<std::pair<std::string, std::vector<std::string>>>{
           {"waterfall", {"--channel", "main2.fy"}},
           {"campbell", {}},
           {"order-cuts", {"--channel", "main2.fy", "--channel", "main1.fx"}}}) {
    SCOPED_TRACE(kind);
    std::vector<std::string> p = {"plot", kind, sweep.string(), "--out",
                                  (tmp.path() / (kind + ".png")).string()};
    p.insert(p.end(), extra.begin(), extra.end());
    const Outcome r = run_evas(p, tmp.path() / "p.log");
    ASSERT_EQ(r.code, 0) << r.log;
    const std::string study = kind == "order-cuts" ? "order_cuts" : kind;
    const std::string drawn = text(tmp.path() / "s" / (study + ".gp"));
    ASSERT_FALSE(drawn.empty());
    EXPECT_EQ(text(tmp.path() / (kind + ".gp")), drawn);
    EXPECT_TRUE(fs::exists(tmp.path() / (kind + ".png")));
  }
  EXPECT_NE(text(tmp.path() / "s" / "waterfall.gp").find("waterfall: main2.fy"), std::string::npos);
  const Outcome bad_order = run_evas({"plot", "order-cuts", sweep.string(), "--order", "0.3",
                                      "--out", (tmp.path() / "x.png").string()},
                                     tmp.path() / "b.log");
  EXPECT_EQ(bad_order.code, 1);
  EXPECT_NE(bad_order.log.find("--order 0.3: the sweep's spectra hold orders 0.5 .. 12"),
            std::string::npos)
      << bad_order.log;
  const Outcome bad_channel = run_evas({"plot", "waterfall", sweep.string(), "--channel", "cyl1.fx",
                                        "--out", (tmp.path() / "x.png").string()},
                                       tmp.path() / "b.log");
  EXPECT_EQ(bad_channel.code, 1);
  EXPECT_NE(bad_channel.log.find("the sweep has no order spectra of 'cyl1.fx' (channels with "
                                 "spectra: main1.fx, main1.fy, main2.fx"),
            std::string::npos)
      << bad_channel.log;
}
