// The difference of a record's last two cycles (cycle_difference.h).
#include "post/cycle_difference.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace evas {

namespace {
constexpr double kPi = 3.14159265358979323846;
bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}
}  // namespace

Settledness compare_cycles(const std::vector<Channel>& channels, const double* last,
                           const double* previous, long rows, long width) {
  Settledness s;
  s.measured = true;
  std::vector<double> scale(static_cast<std::size_t>(width), 0.0);
  std::vector<double> diff(static_cast<std::size_t>(width), 0.0);
  // angles (an attitude angle in (-pi, pi]) are compared modulo a turn
  std::vector<double> turn(static_cast<std::size_t>(width), 0.0);
  for (long c = 0; c < width; ++c) {
    const std::string& u = channels[static_cast<std::size_t>(c)].unit;
    turn[static_cast<std::size_t>(c)] = u == "rad" ? 2.0 * kPi : u == "deg" ? 360.0 : 0.0;
  }
  for (long r = 0; r < rows; ++r)
    for (long c = 0; c < width; ++c) {
      const double a = last[r * width + c], b = previous[r * width + c];
      auto k = static_cast<std::size_t>(c);
      scale[k] = std::max({scale[k], std::abs(a), std::abs(b)});
      const double d = turn[k] > 0.0 ? std::remainder(a - b, turn[k]) : a - b;
      diff[k] = std::max(diff[k], std::abs(d));
    }
  std::map<std::string, double> unit_max;
  for (long c = 0; c < width; ++c) {
    const Channel& ch = channels[static_cast<std::size_t>(c)];
    if (ch.name == "crank_angle") continue;
    double& m = unit_max[ch.unit];
    m = std::max(m, scale[static_cast<std::size_t>(c)]);
  }
  for (long c = 0; c < width; ++c) {
    const Channel& ch = channels[static_cast<std::size_t>(c)];
    if (ch.name == "crank_angle") continue;
    const auto k = static_cast<std::size_t>(c);
    const bool location = ends_with(ch.name, "_angle");
    const double sc = std::max(scale[k], kSettleFloor * unit_max[ch.unit]);
    const double d = sc > 0.0 ? diff[k] / sc : 0.0;
    s.channels.push_back({ch.name, d});
    if (location) continue;  // listed, not in the verdict
    if (s.worst_channel.empty() || d > s.max_difference) {
      s.max_difference = d;
      s.worst_channel = ch.name;
    }
  }
  return s;
}

long rows_per_period(bool crank_angle_grid, double grid_step, double period_s, double period_deg,
                     std::string& why) {
  const double per = crank_angle_grid ? period_deg : period_s;
  if (!(grid_step > 0.0) || !(per > 0.0)) {
    why = "no period";
    return 0;
  }
  const double n = per / grid_step;
  const double rounded = std::round(n);
  if (rounded < 1.0 || std::abs(n - rounded) > 1e-6 * n) {
    why = "the output step (" + format_number(grid_step) + (crank_angle_grid ? " deg" : " s") +
          ") does not divide the period (" + format_number(per) +
          (crank_angle_grid ? " deg" : " s") + ")";
    return 0;
  }
  // two cycles of rows are kept in memory: refuse beyond 2^26 rows (about 1 GB
  // for eight channels)
  if (rounded > 33554432.0) {
    why = "the period holds " + format_number(rounded) + " output rows, too many to keep two";
    return 0;
  }
  return static_cast<long>(rounded);
}

}  // namespace evas
