// Whether a run has settled: its last two cycles compared channel by channel
// as the rows come (post/cycle_difference.h gives the measure), and the
// summary's "settledness" member.
#pragma once

#include <string>
#include <vector>

#include "model/element.h"
#include "post/cycle_difference.h"

namespace evas::run {

using evas::ChannelDifference;
using evas::compare_cycles;
using evas::kSettleFloor;
using evas::rows_per_period;
using evas::Settledness;

/// Keeps the last two cycles of a run's rows and compares them.
class CycleTracker {
 public:
  /// `rows_per_period` = N > 0 (0: nothing is kept, measure() says why_not).
  CycleTracker(long rows_per_period, std::string why_not = "");
  void begin(const std::vector<Channel>& channels);
  void row(const double* values);
  long rows() const { return rows_; }
  /// True when the last row closes a cycle and two whole cycles are kept.
  bool at_cycle_end() const;
  /// The last N rows against the N before them (measured = false when the
  /// run holds less than two cycles).
  Settledness measure() const;

 private:
  long n_ = 0;
  std::string why_not_;
  std::vector<Channel> channels_;
  long width_ = 0;
  std::vector<double> ring_;  // 2N rows
  long rows_ = 0;
};

/// summary.json's "settledness" member (the value alone).
std::string settledness_json(const Settledness& s, const std::string& indent);

}  // namespace evas::run
