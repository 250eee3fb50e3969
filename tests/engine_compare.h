// Comparing runs of the paper's engine (validation/engine/engine.yaml, Case
// 1) by their results.csv: the columns by channel name, a channel's largest
// difference as a fraction of the reference's swing (max - min), and a short
// run of the engine (to 0.01 s) with the options given (the evas binary, by
// run_faults_support.h).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "run_faults_support.h"

namespace engine_compare {

using Columns = std::map<std::string, std::vector<double>>;

// The columns of a results.csv by channel name (the header's unit dropped).
inline Columns read_csv_columns(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  std::istringstream head(line);
  for (std::string cell; std::getline(head, cell, ',');)
    names.push_back(cell.substr(0, cell.find('[')));
  Columns out;
  while (std::getline(in, line)) {
    std::istringstream row(line);
    std::size_t k = 0;
    for (std::string cell; std::getline(row, cell, ',') && k < names.size(); ++k)
      out[names[k]].push_back(std::stod(cell));
  }
  return out;
}

// max |ref - other| / (max ref - min ref) over channel `ch`; -1 when either
// run lacks it or their lengths differ.
inline double difference_of_swing(const Columns& ref, const Columns& other, const std::string& ch) {
  if (!ref.count(ch) || !other.count(ch)) return -1.0;
  const auto& x = ref.at(ch);
  const auto& y = other.at(ch);
  if (x.size() != y.size() || x.empty()) return -1.0;
  double lo = x[0], hi = x[0], diff = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    lo = std::min(lo, x[i]);
    hi = std::max(hi, x[i]);
    diff = std::max(diff, std::abs(x[i] - y[i]));
  }
  return diff / (hi - lo);
}

/// The engine to t = 0.01 s into out (CSV results) with the given `evas run`
/// options; code and log as run_evas gives them, the columns when it ran.
struct EngineRun {
  int code = -1;
  std::string log;
  Columns columns;
};

inline EngineRun run_engine_briefly(const std::filesystem::path& out,
                                    const std::vector<std::string>& options) {
  const std::string scene =
      (std::filesystem::path(EVAS_SOURCE_DIR) / "validation" / "engine" / "engine.yaml").string();
  std::vector<std::string> args = {"run",   scene,   "--param",   "time.end=0.01",
                                   "--csv", "--out", out.string()};
  args.insert(args.end(), options.begin(), options.end());
  const run_faults::Outcome o = run_faults::run_evas(args, out.string() + ".log");
  EngineRun r;
  r.code = o.code;
  r.log = o.log;
  if (o.code == 0) r.columns = read_csv_columns(out / "results.csv");
  return r;
}

/// IDA at rtol 1e-7, atol 1e-11: the reference of the short runs.
inline EngineRun run_engine_reference(const std::filesystem::path& out) {
  return run_engine_briefly(out, {"--set", "rtol=1e-7", "--set", "atol=1e-11"});
}

/// The main bearing loads main1.fx, main3.fy, main5.fy of `run` within
/// `bound` of their swing in `ref` (gtest expectations naming `what`).
inline void expect_main_bearings_within(const Columns& ref, const Columns& run, double bound,
                                        const std::string& what) {
  for (const std::string ch : {"main1.fx", "main3.fy", "main5.fy"}) {
    const double d = difference_of_swing(ref, run, ch);
    EXPECT_GE(d, 0.0) << what << ": " << ch << " missing or of another length";
    EXPECT_LT(d, bound) << what << ": " << ch;
  }
}

}  // namespace engine_compare
