// evas_bench, the steady cycle (docs/periodic.md, issue 52): `evas periodic`
// of the validation engine's Case 1 against `evas run` of the same scene to its
// 0.24 s (six cycles from rest), as whole processes in turn (run, periodic,
// run, periodic, ...: 5 pairs, medians, the ratio pair by pair); each method
// of evas periodic once (cycle integrations, its own wall time); and the
// bench's 8-point sweep (1500-5000 rpm) on periodic points against the same
// sweep of 0.12-s runs, serial, whole processes (2 pairs).
#pragma once

#include <yaml-cpp/yaml.h>

#include <chrono>
#include <filesystem>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include "bench_baseline.h"

namespace evas::bench {

inline double child_seconds(const std::vector<std::string>& args) {
  const auto t0 = std::chrono::steady_clock::now();
  run_child(args);
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

inline std::string periodic_table(const std::string& engine, const std::string& evas) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("evas_bench_periodic_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string run_out = (dir / "run").string(), per_out = (dir / "periodic").string();
  std::vector<double> w_run, w_per, ratio;
  for (int k = 0; k < 5; ++k) {
    const double a =
        child_seconds({evas, "run", engine, "--out", run_out, "--quiet", "--overwrite"});
    const double b =
        child_seconds({evas, "periodic", engine, "--out", per_out, "--quiet", "--overwrite"});
    w_run.push_back(a);
    w_per.push_back(b);
    ratio.push_back(b / a);
  }
  std::ostringstream os;
  os << std::setprecision(3);
  os << "| command | whole process [s] (median of 5) | periodic / run (median of the pairs) |\n"
        "|---|---:|---:|\n"
     << "| `evas run` 0.24 s (six cycles from rest) | " << median(w_run) << " | |\n"
     << "| `evas periodic` (projected) | " << median(w_per) << " | " << median(ratio) << " |\n\n";
  os << "| method | cycle integrations | steps | its own wall [s] | converged |\n"
        "|---|---:|---:|---:|---|\n";
  for (const char* m : {"projected", "anderson", "fixed-point"}) {
    const std::string out = (dir / m).string();
    run_child({evas, "periodic", engine, "--out", out, "--quiet", "--overwrite", "--method", m});
    const YAML::Node s = YAML::LoadFile(out + "/summary.json");  // (JSON is YAML)
    os << "| " << m << " | " << s["periodic"]["cycle_integrations"].as<long>() << " | "
       << s["stats"]["steps"].as<long>() << " | " << s["periodic"]["wall_seconds"].as<double>()
       << " | " << (s["periodic"]["converged"].as<bool>() ? "yes" : "no") << " |\n";
  }
  const std::vector<std::string> sweep = {evas,      "study",
                                          "sweep",   engine,
                                          "--sweep", "crank.lof.speed=157.08..523.6:52.36",
                                          "--jobs",  "1",
                                          "--quiet", "--order-channels",
                                          "main3.fy"};
  std::vector<double> s_run, s_per, s_ratio;
  for (int k = 0; k < 2; ++k) {
    std::vector<std::string> a = sweep, b = sweep;
    const std::string da = (dir / ("sweep_run" + std::to_string(k))).string(),
                      db = (dir / ("sweep_per" + std::to_string(k))).string();
    a.insert(a.end(), {"--t-end", "0.12", "--out", da});
    b.insert(b.end(), {"--periodic", "projected", "--out", db});
    const double ta = child_seconds(a), tb = child_seconds(b);
    s_run.push_back(ta);
    s_per.push_back(tb);
    s_ratio.push_back(tb / ta);
  }
  os << "\n| sweep, 8 points, serial | whole process [s] (median of 2) | periodic / 0.12 s "
        "(median of the pairs) |\n|---|---:|---:|\n"
     << "| 0.12-s runs from rest | " << median(s_run) << " | |\n"
     << "| periodic points (`--periodic`) | " << median(s_per) << " | " << median(s_ratio)
     << " |\n";
  std::filesystem::remove_all(dir);
  return os.str();
}

}  // namespace evas::bench
