// What `evas report` reads of a results file (report_run.h).
#include "plot/report_run.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <sstream>

#include "io/hdf5_util.h"
#include "model/stats.h"
#include "model/types.h"
#include "post/order_tracking.h"

namespace evas::report {

namespace fs = std::filesystem;

namespace {

// A journal bearing: every channel the report's bearing figures read.
std::vector<std::string> find_bearings(const Run& run) {
  std::vector<std::string> out;
  for (const auto& n : run.ending(".eps")) {
    const std::string e = n.substr(0, n.size() - 4);
    bool all = true;
    for (const char* c : {"fx", "fy", "ex", "ey", "h_min", "p_max", "fx_journal", "fy_journal"})
      all = all && run.find(e + "." + c) >= 0;
    if (all) out.push_back(e);
  }
  return out;
}

}  // namespace

std::string fixed(double x, int digits) {
  std::ostringstream os;
  os << std::fixed << std::setprecision(digits) << x;
  return os.str();
}

std::string general(double x, int digits) {
  std::ostringstream os;
  os << std::setprecision(digits) << x;
  return os.str();
}

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() > tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

std::string file_word(const std::string& s) {
  std::string o = s;
  for (char& c : o)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.') c = '_';
  return o;
}

std::string listing(const std::vector<std::string>& names, std::size_t most) {
  std::string s;
  for (std::size_t i = 0; i < names.size() && i < most; ++i) s += (i ? ", " : "") + names[i];
  if (names.size() > most) s += ", ... (" + std::to_string(names.size()) + " in all)";
  return s.empty() ? "none" : s;
}

Run read_run(const std::string& path, int cycles) {
  Run run;
  run.path = path;
  run.d = read_results(path);
  run.crank = run.find("crank_angle");
  run.bearings = find_bearings(run);
  if (run.d.time.empty()) throw InputError(path + ": the results hold no output row");
  if (run.crank < 0)
    throw InputError(
        path + ": not an engine run on the crank-angle grid (output grid '" + run.d.grid +
        "'): the report reads its figures against crank angle and needs the crank_angle "
        "channel (the scene's output: grid: crank-angle); this file holds " +
        std::to_string(run.d.time.size()) + " rows of " + std::to_string(run.d.names.size()) +
        " channels (" + listing(run.d.names) + "), journal bearings: " + listing(run.bearings));
  const Eigen::Index n = run.rows();
  const double span = run.at(n - 1, run.crank) - run.at(0, run.crank);
  // n rows of a uniform crank-angle grid cover n steps (a cycle of 720 rows
  // at 1 deg is 0 .. 719 deg): whole cycles counted as evas spectrum counts
  // them, so 0 .. 4319 deg holds six and evas periodic's 0 .. 719 deg one
  const double step = n > 1 ? span / static_cast<double>(n - 1) : 0.0;
  run.whole_cycles = static_cast<int>(std::floor((span + step) / kCycle + 1e-9));
  if (cycles > run.whole_cycles)
    throw InputError("--cycles " + std::to_string(cycles) + ": " + path + " covers " +
                     fixed(span, 1) + " deg of crank angle, " + std::to_string(run.whole_cycles) +
                     " whole cycle(s) of 720 deg (give fewer, 0 for the whole record, or "
                     "run longer)");
  // the default, the last whole cycle, is that of evas spectrum, evas plot order and a sweep
  run.cycles = cycles >= 0 ? cycles : std::min(1, run.whole_cycles);
  if (run.cycles > 0) {
    const double first = run.at(n - 1, run.crank) - run.cycles * kCycle + 0.5 * step;
    Eigen::Index r = n - 1;
    while (r > 0 && run.at(r - 1, run.crank) > first) --r;
    run.r0 = r;
  }
  if (run.whole_cycles >= 2) {
    std::vector<double> th(static_cast<std::size_t>(n));
    for (Eigen::Index r = 0; r < n; ++r) th[static_cast<std::size_t>(r)] = run.at(r, run.crank);
    try {
      run.speed_spread = speed_spread(run.d.time, th, kCycle);
      if (run.runup()) {
        const OrderTrack tr = order_tracking(run.d.time, th, th, {}, kCycle);
        run.rpm_first = tr.rpm.front();
        run.rpm_last = tr.rpm.back();
      }
    } catch (const InputError&) {
      run.speed_spread = 0.0;  // a grid the tracking cannot use: read as one speed
    }
  }
  return run;
}

std::string scene_name(const Run& run) {
  try {
    const YAML::Node s = YAML::Load(run.d.scene);
    if (s.IsMap() && s["name"] && s["name"].IsScalar()) return s["name"].as<std::string>();
  } catch (const YAML::Exception&) {
  }
  return std::filesystem::absolute(run.path).parent_path().filename().string();
}

// The integrator's statistics of the file's /stats group (empty when the run
// did not finish).
std::vector<std::vector<std::string>> stats_rows(const std::string& path) {
  std::vector<std::vector<std::string>> rows;
  try {
    h5::Quiet quiet;
    const h5::Handle file = h5::open_file(path);
    if (!h5::exists(file, "stats")) return rows;
    const h5::Handle g = h5::open_group(file, "stats");
    for (const StatField& f : stat_fields()) {
      if (!h5::has_attribute(g, f.name)) continue;
      const std::string v = f.integer ? std::to_string(h5::read_int_attribute(g, f.name))
                                      : general(h5::read_double_attribute(g, f.name));
      rows.push_back({f.name, v, f.unit, f.meaning});
    }
  } catch (const h5::Failure&) {
  }
  return rows;
}

// summary.json beside the results file (JSON is YAML): the settings the
// integrator read, wall time and memory; empty rows when there is none.
std::vector<std::vector<std::string>> summary_rows(const std::string& path) {
  std::vector<std::vector<std::string>> rows;
  const fs::path json = fs::path(path).parent_path() / "summary.json";
  if (!fs::exists(json)) return rows;
  try {
    const YAML::Node s = YAML::LoadFile(json.string());
    std::vector<std::string> unread;
    if (s["settings_not_read"] && s["settings_not_read"].IsSequence())
      for (const auto& u : s["settings_not_read"]) unread.push_back(u.as<std::string>());
    if (s["settings"] && s["settings"].IsMap())
      for (const auto& kv : s["settings"]) {
        const std::string k = kv.first.as<std::string>();
        if (std::find(unread.begin(), unread.end(), k) == unread.end() && kv.second.IsScalar())
          rows.push_back({"setting " + k, kv.second.as<std::string>()});
      }
    for (const char* k : {"peak_memory_mb", "build_arch"})
      if (s[k] && s[k].IsScalar()) rows.push_back({k, s[k].as<std::string>()});
  } catch (const YAML::Exception& e) {
    rows.push_back({"summary.json", std::string("cannot be read: ") + e.what()});
  }
  return rows;
}

}  // namespace evas::report
