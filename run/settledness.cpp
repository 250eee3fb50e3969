// Whether a run has settled (settledness.h).
#include "run/settledness.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "io/text_escape.h"

namespace evas::run {

CycleTracker::CycleTracker(long rows_per_period, std::string why_not)
    : n_(rows_per_period), why_not_(std::move(why_not)) {}

void CycleTracker::begin(const std::vector<Channel>& channels) {
  channels_ = channels;
  width_ = static_cast<long>(channels.size());
  rows_ = 0;
  if (n_ > 0) ring_.assign(static_cast<std::size_t>(2 * n_ * width_), 0.0);
}

void CycleTracker::row(const double* values) {
  if (n_ > 0) {
    const long slot = rows_ % (2 * n_);
    std::copy(values, values + width_, ring_.begin() + slot * width_);
  }
  ++rows_;
}

bool CycleTracker::at_cycle_end() const {
  return n_ > 0 && rows_ > 2 * n_ && (rows_ - 1) % n_ == 0;
}

Settledness CycleTracker::measure() const {
  Settledness s;
  if (n_ <= 0) {
    s.why_not = why_not_;
    return s;
  }
  if (rows_ < 2 * n_) {
    s.why_not = "the run holds " + format_number(static_cast<double>(rows_ - 1) / n_) +
                " cycles; two whole cycles are needed to compare";
    s.rows_per_period = n_;
    s.cycles = static_cast<double>(rows_ - 1) / static_cast<double>(n_);
    return s;
  }
  // the last N rows in order, and the N before them
  std::vector<double> last(static_cast<std::size_t>(n_ * width_)),
      prev(static_cast<std::size_t>(n_ * width_));
  for (long j = 0; j < n_; ++j) {
    const long r_last = rows_ - n_ + j, r_prev = rows_ - 2 * n_ + j;
    const auto* a = ring_.data() + (r_last % (2 * n_)) * width_;
    const auto* b = ring_.data() + (r_prev % (2 * n_)) * width_;
    std::copy(a, a + width_, last.begin() + j * width_);
    std::copy(b, b + width_, prev.begin() + j * width_);
  }
  s = compare_cycles(channels_, last.data(), prev.data(), n_, width_);
  s.rows_per_period = n_;
  s.cycles = static_cast<double>(rows_ - 1) / static_cast<double>(n_);
  return s;
}

std::string settledness_json(const Settledness& s, const std::string& indent) {
  std::ostringstream o;
  const std::string in = indent + "  ";
  o << "{\n";
  o << in << "\"measured\": " << (s.measured ? "true" : "false") << ",\n";
  if (!s.measured) {
    o << in << "\"reason\": " << json_string(s.why_not) << ",\n";
  }
  o << in << "\"period_s\": " << json_number(s.period_s) << ",\n";
  o << in << "\"period_deg\": " << json_number(s.period_deg) << ",\n";
  o << in << "\"cycles\": " << json_number(s.cycles) << ",\n";
  o << in << "\"tolerance\": " << json_number(s.tolerance);
  if (s.measured) {
    o << ",\n" << in << "\"settled\": " << (s.settled() ? "true" : "false") << ",\n";
    o << in << "\"max_difference\": " << json_number(s.max_difference) << ",\n";
    o << in << "\"worst_channel\": " << json_string(s.worst_channel) << ",\n";
    o << in << "\"measure\": "
      << json_string(
             "max over the last cycle of |y(t) - y(t - T)| / max(max |y| over both cycles, "
             "1e-3 x the largest max |y| of the same unit); angles modulo a turn; the angles of an "
             "extremum (*_angle) listed but not in max_difference")
      << ",\n";
    o << in << "\"channels\": {";
    for (std::size_t c = 0; c < s.channels.size(); ++c)
      o << (c ? ", " : "") << json_string(s.channels[c].name) << ": "
        << json_number(s.channels[c].difference);
    o << "}";
  }
  o << "\n" << indent << "}";
  return o.str();
}

}  // namespace evas::run
