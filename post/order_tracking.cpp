#include "post/order_tracking.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>

#include "model/types.h"
#include "post/order_spectrum.h"

namespace evas {

namespace {

// Samples per cycle on a uniform angle grid; throws for a grid it cannot use.
long per_cycle(const std::vector<double>& theta, double cycle_deg) {
  if (theta.size() < 2) throw InputError("order tracking: fewer than 2 samples");
  const double step = theta[1] - theta[0];
  if (!(step > 0.0)) throw InputError("order tracking: the crank angle does not increase");
  const double m = cycle_deg / step;
  if (std::abs(m - std::round(m)) > 1e-6 * m)
    throw InputError("order tracking: the angle step " + std::to_string(step) +
                     " deg does not divide the cycle of " + std::to_string(cycle_deg) + " deg");
  return std::lround(m);
}

// Mean speed over cycle [i0, i0 + m) [rpm], and its change within it.
void cycle_speed(const std::vector<double>& t, const std::vector<double>& th, long i0, long m,
                 double cycle_deg, double& rpm, double& change) {
  const auto a = static_cast<std::size_t>(i0), b = static_cast<std::size_t>(i0 + m - 1);
  const double t_end = t[b] + (t[b] - t[b - 1]);  // one step on from the last sample
  const double revs = cycle_deg / 360.0;
  rpm = revs * 60.0 / (t_end - t[a]);
  const double n_first = (th[a + 1] - th[a]) / 6.0 / (t[a + 1] - t[a]);  // deg/s -> rpm
  const double n_last = (th[b] - th[b - 1]) / 6.0 / (t[b] - t[b - 1]);
  change = (n_last - n_first) / rpm;
}

}  // namespace

double speed_spread(const std::vector<double>& time, const std::vector<double>& theta_deg,
                    double cycle_deg) {
  if (time.size() != theta_deg.size() || time.size() < 4) return 0.0;
  const long m = per_cycle(theta_deg, cycle_deg);
  const long n = static_cast<long>(time.size()) / m;
  if (n < 2 || m < 3) return 0.0;
  double lo = 1e300, hi = -1e300, sum = 0.0;
  for (long c = 0; c < n; ++c) {
    double rpm = 0.0, change = 0.0;
    cycle_speed(time, theta_deg, c * m, m, cycle_deg, rpm, change);
    lo = std::min(lo, rpm);
    hi = std::max(hi, rpm);
    sum += rpm;
  }
  return (hi - lo) / (sum / static_cast<double>(n));
}

OrderTrack order_tracking(const std::vector<double>& time, const std::vector<double>& theta_deg,
                          const std::vector<double>& y, const std::vector<double>& orders,
                          double cycle_deg) {
  if (time.size() != theta_deg.size() || y.size() != time.size())
    throw InputError("order tracking: time, crank angle and signal differ in length");
  const long m = per_cycle(theta_deg, cycle_deg);
  const long n = static_cast<long>(time.size()) / m;
  if (n < 1 || m < 3)
    throw InputError("order tracking: the record holds no whole cycle of " +
                     std::to_string(cycle_deg) + " deg");
  const double resolution = 360.0 / cycle_deg;
  for (double o : orders)
    if (!(o >= 0.0) || std::abs(o / resolution - std::round(o / resolution)) > 1e-9)
      throw InputError("order tracking: order " + std::to_string(o) + " is not a multiple of " +
                       std::to_string(resolution) + " (the orders a cycle of " +
                       std::to_string(cycle_deg) + " deg resolves)");
  const double top = orders.empty() ? 0.0 : *std::max_element(orders.begin(), orders.end());
  OrderTrack out;
  out.orders = orders;
  for (long c = 0; c < n; ++c) {
    const auto a = time.begin() + c * m;
    const std::vector<double> th(theta_deg.begin() + c * m, theta_deg.begin() + (c + 1) * m);
    const std::vector<double> yy(y.begin() + c * m, y.begin() + (c + 1) * m);
    const OrderSpectrum s = order_spectrum(th, yy, 1, cycle_deg, std::max(top, resolution));
    double rpm = 0.0, change = 0.0;
    cycle_speed(time, theta_deg, c * m, m, cycle_deg, rpm, change);
    out.rpm.push_back(rpm);
    out.change.push_back(change);
    out.t0.push_back(*a);
    out.t1.push_back(*(a + m - 1));
    std::vector<double> amp;
    for (double o : orders) {
      double a_o = 0.0;
      for (std::size_t j = 0; j < s.order.size(); ++j)
        if (std::abs(s.order[j] - o) < 1e-9) a_o = s.amplitude[j];
      amp.push_back(a_o);
    }
    out.amplitude.push_back(std::move(amp));
  }
  return out;
}

std::string runup_text(const std::vector<double>& time, const std::vector<double>& theta_deg,
                       double cycle_deg) {
  try {
    if (speed_spread(time, theta_deg, cycle_deg) <= 0.02) return "";
    const std::vector<double> zero(theta_deg.size(), 0.0);
    const OrderTrack tr = order_tracking(time, theta_deg, zero, {}, cycle_deg);
    std::ostringstream os;
    os << std::setprecision(5) << "the speed runs from " << tr.rpm.front() << " to "
       << tr.rpm.back() << " rpm over its whole cycles";
    return os.str();
  } catch (const InputError&) {
    return "";
  }
}

}  // namespace evas
