// Order tracking of a run-up: each engine order's amplitude against speed.
//
// On the crank-angle output grid a run whose speed changes (a crank LOF
// `speed_profile`) is still sampled uniformly in angle, so the order spectrum
// of each single 720-deg cycle (post/order_spectrum.h, one cycle) resolves the
// orders in steps of 0.5 without leakage from the angle grid; what it cannot
// resolve is the speed's own change within the cycle, which smears a
// resonance crossed during it. Each cycle's speed is its mean,
//     n = (720 / 360) x 60 / (t_end - t_start)  [rpm],
// t_end the time one 720-deg step after the cycle's first sample (the last
// sample plus one angle step, extrapolated from the last two samples), and the
// change within it
//     dn / n = (n_last - n_first) / n,
// n_first, n_last from the first and last two samples of the cycle. Cycles
// are counted from the record's first sample; an incomplete last cycle is
// left out.
#pragma once

#include <string>
#include <vector>

namespace evas {

struct OrderTrack {
  std::vector<double> orders;  ///< the orders tracked (as found on the 0.5 grid)
  std::vector<double> rpm;     ///< mean speed per cycle [rpm]
  std::vector<double> change;  ///< (n_last - n_first) / n per cycle
  std::vector<double> t0, t1;  ///< first and last sample time per cycle [s]
  /// amplitude[cycle][order index]
  std::vector<std::vector<double>> amplitude;
};

/// Tracks `orders` of y over the whole cycles of (time, theta_deg). Throws
/// InputError for unequal lengths, fewer than one whole cycle, an angle grid
/// that is not uniform or does not divide the cycle, an order that is not a
/// multiple of 360 / cycle_deg, or non-finite samples.
OrderTrack order_tracking(const std::vector<double>& time, const std::vector<double>& theta_deg,
                          const std::vector<double>& y, const std::vector<double>& orders,
                          double cycle_deg = 720.0);

/// The spread of the speed over the record's whole cycles: (max - min) / mean
/// of the per-cycle mean speeds (0 for a constant speed or fewer than 2
/// cycles). A record is a run-up (or run-down) for the report when it exceeds
/// 0.02.
double speed_spread(const std::vector<double>& time, const std::vector<double>& theta_deg,
                    double cycle_deg = 720.0);

/// "" at a constant speed (or a grid the tracking cannot read), else "the
/// speed runs from N1 to N2 rpm over its whole cycles" (first and last cycle).
std::string runup_text(const std::vector<double>& time, const std::vector<double>& theta_deg,
                       double cycle_deg = 720.0);

}  // namespace evas
