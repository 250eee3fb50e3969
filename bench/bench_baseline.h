// evas_bench, side by side with the code of 2026-11-24 (issue 12's starting
// point, built by bench/baseline.sh): both `evas run` programs on the
// same scenes in turn (old, new, old, new, ...), so that a drift of the shared
// machine's speed falls on both. Each pair gives the ratio of the integrators'
// microseconds per step (summary.json: stats.wall_seconds / stats.steps) and of
// the whole processes' wall times; the table gives the medians over the pairs.
#pragma once

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include "bench_engine.h"
#include "bench_scaling.h"

namespace evas::bench {

// Issue 12's own figure for the code of 2026-11-24: `evas run` of Case 1 at IDA
// rtol 1e-5, 3.3 s integrator wall for 45,160 steps.
constexpr double kIssueUsPerStep = 73.1;

struct ProcessRun {
  long steps = 0;
  double integrator_wall = 0;  // stats.wall_seconds [s]
  double process_wall = 0;     // the child, start to exit [s]
};

/// `evas run SCENE --out OUT --quiet EXTRA...` in a child; its summary.json.
inline ProcessRun timed_run(const std::string& evas, const std::string& scene,
                            const std::string& out, const std::vector<std::string>& extra) {
  std::vector<std::string> args = {evas, "run", scene, "--out", out, "--quiet"};
  args.insert(args.end(), extra.begin(), extra.end());
  const auto t0 = std::chrono::steady_clock::now();
  run_child(args);
  ProcessRun r;
  r.process_wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const YAML::Node s = YAML::LoadFile(out + "/summary.json");  // (JSON is YAML)
  if (s["status"].as<std::string>() != "completed")
    throw RunError(scene + ": " + s["status"].as<std::string>());
  r.steps = s["stats"]["steps"].as<long>();
  r.integrator_wall = s["stats"]["wall_seconds"].as<double>();
  return r;
}

inline double median(std::vector<double> x) {
  std::sort(x.begin(), x.end());
  const std::size_t n = x.size();
  return n % 2 ? x[n / 2] : 0.5 * (x[n / 2 - 1] + x[n / 2]);
}

/// The scenes of `engine_path` (Case 1 and Case 2, engine_cases) written to dir
/// with absolute body and data paths; {label, path}.
inline std::vector<std::pair<std::string, std::string>> scene_files(
    const std::string& engine_path, const std::filesystem::path& dir, const std::string& tag) {
  namespace fs = std::filesystem;
  std::vector<std::pair<std::string, std::string>> files;
  for (const auto& c : engine_cases(engine_path)) {
    const std::string text = with_absolute_paths(c.src.text, engine_path);
    const fs::path p = dir / (tag + "-" + replace_all(c.label, " ", "") + ".yaml");
    std::ofstream(p) << text;
    files.push_back({c.label, p.string()});
  }
  return files;
}

/// The side-by-side table; old_evas empty: a line saying why it is missing.
inline std::string baseline_table(const std::string& engine_path, const std::string& evas,
                                  const std::string& old_evas, const std::string& old_engine,
                                  int pairs = 3) {
  namespace fs = std::filesystem;
  if (old_evas.empty() || !fs::exists(old_evas))
    return "Not measured in this run: no build of the 2026-11-24 code (`bench/baseline.sh` "
           "builds it from this clone's history; a shallow clone lacks it).\n";
  char tmpl[] = "/tmp/evas-baseline.XXXXXX";
  if (!mkdtemp(tmpl)) throw RunError("cannot create a temporary folder");
  const fs::path tmp(tmpl);
  struct Cleanup {
    fs::path dir;
    ~Cleanup() {
      std::error_code ec;
      fs::remove_all(dir, ec);
    }
  } cleanup{tmp};
  const auto olds = scene_files(old_engine, tmp, "old");
  const auto news = scene_files(engine_path, tmp, "new");
  std::ostringstream os;
  os << "| case | run (2026-11-24 → today) | rtol | steps | us per step | ratio | whole process "
        "[s] | ratio | real-time factor (today, whole process) |\n"
     << "|---|---|---:|---:|---:|---:|---:|---:|---:|\n";
  struct Row {
    std::string label;
    double rtol;
    std::vector<std::string> new_args;  // today's settings (empty: the old run's)
  };
  double machine = 0;  // the old code's us per step, Case 1, rtol 1e-5
  const double gstep = M_PI / 180.0 / 314.159 / 6.0;  // 1/6 deg at 3000 rpm
  std::ostringstream gs;
  gs << std::setprecision(17) << gstep;
  const std::vector<Row> rows = {
      {"IDA (KLU → second-order solver)", 1e-3, {}},
      {"IDA (KLU → second-order solver)", 1e-5, {}},
      {"IDA rtol 1e-5 → generalized-α 1°/6",
       1e-5,
       {"--integrator", "generalized-alpha", "--step", gs.str(), "--set",
        "iteration=effective-mass", "--rtol", "3e-5", "--atol", "1e-9"}}};
  for (std::size_t c = 0; c < olds.size() && c < news.size(); ++c) {
    for (const Row& r : rows) {
      std::ostringstream tol;
      tol << std::setprecision(3) << r.rtol;
      std::ostringstream atol;
      atol << std::setprecision(3) << r.rtol * 1e-4;
      const std::vector<std::string> old_args = {"--rtol", tol.str(), "--atol", atol.str()};
      const std::vector<std::string>& new_args = r.new_args.empty() ? old_args : r.new_args;
      std::vector<double> us_ratio, wall_ratio, us_old, us_new, w_old, w_new;
      long s_old = 0, s_new = 0;
      for (int k = 0; k < pairs; ++k) {
        const ProcessRun a =
            timed_run(old_evas, olds[c].second, (tmp / "old-out").string(), old_args);
        const ProcessRun b = timed_run(evas, news[c].second, (tmp / "new-out").string(), new_args);
        s_old = a.steps;
        s_new = b.steps;
        const double ua = a.integrator_wall / a.steps * 1e6, ub = b.integrator_wall / b.steps * 1e6;
        us_old.push_back(ua);
        us_new.push_back(ub);
        us_ratio.push_back(ua / ub);
        w_old.push_back(a.process_wall);
        w_new.push_back(b.process_wall);
        wall_ratio.push_back(a.process_wall / b.process_wall);
      }
      os << "| " << olds[c].first << " | " << r.label << " | " << std::scientific
         << std::setprecision(0) << r.rtol << " | " << s_old << " → " << s_new << " | "
         << std::fixed << std::setprecision(1) << median(us_old) << " → " << median(us_new) << " | "
         << std::setprecision(2) << median(us_ratio) << " | " << median(w_old) << " → "
         << median(w_new) << " | " << median(wall_ratio) << " | " << median(w_new) / 0.24 << " |\n";
      if (c == 0 && r.rtol == 1e-5 && r.new_args.empty()) machine = median(us_old);
      std::cerr << "baseline " << olds[c].first << " " << r.label << " done\n";
    }
  }
  if (machine > 0)
    os << "\nThe code of 2026-11-24 took " << std::fixed << std::setprecision(1) << machine
       << " us per step here (Case 1, rtol 1e-5), against the " << kIssueUsPerStep
       << " us (3.3 s, 45,160 steps) issue 12 recorded when it was filed: this machine ran it "
       << std::setprecision(2) << machine / kIssueUsPerStep
       << " times as slowly as the one the issue was measured on.\n";
  return os.str();
}

}  // namespace evas::bench
