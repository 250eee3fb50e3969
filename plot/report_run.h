// What `evas report` (plot/report_page.h) reads of a results file: the rows
// on the crank-angle grid, the journal bearings (found by their channels), the
// cycles analysed, the scene's name, the integrator statistics of /stats and
// the settings of summary.json beside the file; and number formatting.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "io/results.h"

namespace evas::report {

constexpr double kCycle = 720.0;  // a four-stroke engine's cycle [deg]

std::string fixed(double x, int digits);
std::string general(double x, int digits = 6);
bool ends_with(const std::string& s, const std::string& tail);
/// A name usable in a file name: letters, digits, '-', '_' and '.' kept.
std::string file_word(const std::string& s);
/// "a, b, c" of at most `most` names (then "... (N in all)"), or "none".
std::string listing(const std::vector<std::string>& names, std::size_t most = 24);

/// The results file and what the report reads of it.
struct Run {
  std::string path;
  ResultsData d;
  int crank = -1;
  std::vector<std::string> bearings;
  int whole_cycles = 0;
  int cycles = 0;       // the cycles drawn and analysed (0: the whole record)
  Eigen::Index r0 = 0;  // their first row
  // (max - min) / mean of the whole cycles' mean speeds (post/order_tracking.h)
  double speed_spread = 0.0;
  double rpm_first = 0.0, rpm_last = 0.0;  // mean speed of the first and last whole cycle
  /// A run-up or run-down: the speed changes by more than 2 % over the record.
  bool runup() const { return speed_spread > 0.02; }
  Eigen::Index rows() const { return d.values.rows(); }
  int find(const std::string& name) const {
    for (std::size_t i = 0; i < d.names.size(); ++i)
      if (d.names[i] == name) return static_cast<int>(i);
    return -1;
  }
  double at(Eigen::Index r, int c) const { return d.values(r, c); }
  double angle(Eigen::Index r) const { return std::fmod(at(r, crank), kCycle); }
  std::vector<std::string> ending(const std::string& tail) const {
    std::vector<std::string> out;
    for (const auto& n : d.names)
      if (ends_with(n, tail)) out.push_back(n);
    return out;
  }
  std::string span_text() const {
    return cycles > 0 ? "the last " + std::to_string(cycles) + " cycle(s) of 720 deg"
                      : "the whole record";
  }
};

/// Reads the results file; InputError when it is no crank-angle engine run
/// (naming its grid, channels and journal bearings) or holds fewer whole
/// cycles than `cycles` (-1: the last one, or the whole record when it holds none).
Run read_run(const std::string& path, int cycles);

/// The scene's name (from the scene text the file keeps; else its folder).
std::string scene_name(const Run& run);
/// The integrator's statistics of the file's /stats group: name, value, unit,
/// meaning (empty when the run did not finish).
std::vector<std::vector<std::string>> stats_rows(const std::string& path);
/// summary.json beside the results file: the settings the integrator read,
/// peak memory, build; empty when there is none.
std::vector<std::vector<std::string>> summary_rows(const std::string& path);

}  // namespace evas::report
