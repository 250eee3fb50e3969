#include "model/speed_profile.h"

#include <algorithm>

#include "model/types.h"

namespace evas {

namespace {
// Segment k of a profile containing t (times[k] <= t < times[k+1]) and s in [0, 1].
std::size_t segment(const std::vector<double>& T, double t, double& s) {
  const std::size_t k = std::upper_bound(T.begin(), T.end(), t) - T.begin() - 1;
  s = (t - T[k]) / (T[k + 1] - T[k]);
  return k;
}
}  // namespace

SpeedProfile::SpeedProfile(std::vector<double> times, std::vector<double> speeds)
    : times_(std::move(times)), speeds_(std::move(speeds)) {
  if (times_.empty() || times_.size() != speeds_.size())
    throw InputError("speed profile needs matching, non-empty time and speed lists");
  for (std::size_t i = 1; i < times_.size(); ++i)
    if (!(times_[i] > times_[i - 1]))
      throw InputError("speed profile times must increase strictly");
  const std::size_t K = times_.size();
  // Fritsch-Carlson slopes: zero at the ends and at local extrema, harmonic mean elsewhere.
  slopes_.assign(K, 0.0);
  for (std::size_t i = 1; i + 1 < K; ++i) {
    const double d0 = (speeds_[i] - speeds_[i - 1]) / (times_[i] - times_[i - 1]);
    const double d1 = (speeds_[i + 1] - speeds_[i]) / (times_[i + 1] - times_[i]);
    if (d0 * d1 > 0.0) slopes_[i] = 2.0 / (1.0 / d0 + 1.0 / d1);
  }
  angles_.assign(K, 0.0);
  for (std::size_t i = 1; i < K; ++i) {
    const double h = times_[i] - times_[i - 1];
    // integral of the cubic Hermite segment over its whole length
    angles_[i] = angles_[i - 1] + h * (0.5 * (speeds_[i - 1] + speeds_[i]) +
                                       h * (slopes_[i - 1] - slopes_[i]) / 12.0);
  }
}

double SpeedProfile::integral(double t) const {
  const auto& T = times_;
  if (t <= T.front()) return speeds_.front() * (t - T.front());
  if (t >= T.back()) return angles_.back() + speeds_.back() * (t - T.back());
  double x;
  const std::size_t k = segment(T, t, x);
  const double h = T[k + 1] - T[k], x2 = x * x, x3 = x2 * x, x4 = x3 * x;
  // integrals of the Hermite basis h00, h10, h01, h11 over [0, x]
  const double i00 = 0.5 * x4 - x3 + x, i10 = 0.25 * x4 - 2.0 * x3 / 3.0 + 0.5 * x2;
  const double i01 = -0.5 * x4 + x3, i11 = 0.25 * x4 - x3 / 3.0;
  return angles_[k] + h * (i00 * speeds_[k] + i10 * h * slopes_[k] + i01 * speeds_[k + 1] +
                           i11 * h * slopes_[k + 1]);
}

double SpeedProfile::speed(double t) const {
  if (t <= times_.front()) return speeds_.front();
  if (t >= times_.back()) return speeds_.back();
  double x;
  const std::size_t k = segment(times_, t, x);
  const double h = times_[k + 1] - times_[k], x2 = x * x, x3 = x2 * x;
  return (2 * x3 - 3 * x2 + 1) * speeds_[k] + (x3 - 2 * x2 + x) * h * slopes_[k] +
         (-2 * x3 + 3 * x2) * speeds_[k + 1] + (x3 - x2) * h * slopes_[k + 1];
}

double SpeedProfile::acceleration(double t) const {
  if (t <= times_.front() || t >= times_.back()) return 0.0;
  double x;
  const std::size_t k = segment(times_, t, x);
  const double h = times_[k + 1] - times_[k], x2 = x * x;
  return ((6 * x2 - 6 * x) * speeds_[k] + (3 * x2 - 4 * x + 1) * h * slopes_[k] +
          (-6 * x2 + 6 * x) * speeds_[k + 1] + (3 * x2 - 2 * x) * h * slopes_[k + 1]) /
         h;
}

double SpeedProfile::min_speed() const { return *std::min_element(speeds_.begin(), speeds_.end()); }
double SpeedProfile::max_speed() const { return *std::max_element(speeds_.begin(), speeds_.end()); }

bool SpeedProfile::same_as(const SpeedProfile& o) const {
  if (is_constant() && o.is_constant()) return speeds_[0] == o.speeds_[0];
  return times_ == o.times_ && speeds_ == o.speeds_;
}

}  // namespace evas
