// The difference of a record's last two cycles, channel by channel, on a grid
// whose rows repeat in phase every period (a crank-angle grid whose step
// divides the period, or a time grid whose step does): whether a run has
// settled (run/settledness.h keeps a run's last two cycles; evas report
// reads them from a results file).
//
// The difference of a channel is max over the cycle of |y(t) - y(t - T)|
// divided by the channel's scale: its largest |y| over the two cycles, but
// never less than 1e-3 of the largest |y| of the channels of the same unit (so
// that a channel that barely moves, a lateral force of 1e-2 N beside bearing
// loads of 30 kN, is not what sets the answer). The crank-angle channel, which
// grows by the period every cycle, is left out; angles (unit rad or deg) are
// compared modulo a turn, so that an attitude angle passing from pi to -pi
// is no difference. The angles at which an extremum sits (channels named
// *_angle: a bearing's h_min_angle, p_max_angle) jump where two extrema trade
// places, a jump no tolerance separates from a change: they are listed with
// their difference but left out of the verdict (max_difference).
#pragma once

#include <string>
#include <vector>

#include "model/element.h"

namespace evas {

/// The floor of a channel's scale, relative to the largest of its unit.
constexpr double kSettleFloor = 1e-3;

struct ChannelDifference {
  std::string name;
  double difference = 0.0;
};

struct Settledness {
  bool measured = false;
  std::string why_not;          ///< when not measured
  double period_s = 0.0;        ///< T [s]
  double period_deg = 0.0;      ///< T in crank degrees (0: no crank)
  long rows_per_period = 0;     ///< N
  double cycles = 0.0;          ///< cycles in the run (rows - 1) / N
  double tolerance = 1e-3;      ///< settled when max_difference <= tolerance
  double max_difference = 0.0;  ///< the largest channel difference
  std::string worst_channel;
  std::vector<ChannelDifference> channels;  ///< every channel compared, in file order
  bool settled() const { return measured && max_difference <= tolerance; }
};

/// Differences of two cycles of `rows` rows each, row-major with `width`
/// values per row: `last` against `previous` at the same phases. Channels
/// named "crank_angle" are left out.
Settledness compare_cycles(const std::vector<Channel>& channels, const double* last,
                           const double* previous, long rows, long width);

/// Rows per period of an output grid, or 0 with the reason: `grid_step` is the
/// output step (degrees on a crank-angle grid, seconds on a time grid).
long rows_per_period(bool crank_angle_grid, double grid_step, double period_s, double period_deg,
                     std::string& why);

}  // namespace evas
