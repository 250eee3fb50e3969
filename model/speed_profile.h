// A shaft speed over time, omega(t), and its integral, the turned angle: the
// one description of an operating point's speed that the crank's spin LOF and
// every element that follows the crank (prescribed pistons, the motor's
// driver) share, so that they cannot disagree.
//
// omega(t) is constant (one knot) or passes through knots (t_i, omega_i) as a
// monotone cubic Hermite interpolant (Fritsch & Carlson, SIAM J. Numer. Anal.
// 17 (1980) 238-246): slopes zero at the ends and at local extrema, harmonic
// means elsewhere, so the speed is C1 and the angular acceleration continuous
// (a jump in it would cost the integrators their order). Before the first knot
// and after the last the speed is constant. The angle is the exact integral of
// the cubic pieces, angle(0) = 0.
#pragma once

#include <vector>

namespace evas {

class SpeedProfile {
 public:
  SpeedProfile() = default;
  /// Constant speed w [rad/s].
  static SpeedProfile constant(double w) { return SpeedProfile({0.0}, {w}); }
  /// Through the knots (times strictly increasing, one speed each). Throws InputError.
  SpeedProfile(std::vector<double> times, std::vector<double> speeds);

  /// Angle turned since t = 0 [rad].
  double angle(double t) const { return integral(t) - integral(0.0); }
  /// angle(t) + c, for a constant speed written as w t + c: the one rounding
  /// (or fused multiply-add) that a constant-speed element always computed,
  /// so that following a constant crank changes no result in its last bit.
  double angle_plus(double t, double c) const {
    return is_constant() ? speeds_[0] * t + c : angle(t) + c;
  }
  /// Angle turned since the first knot [rad].
  double integral(double t) const;
  double speed(double t) const;         ///< [rad/s]
  double acceleration(double t) const;  ///< [rad/s^2]
  bool is_constant() const { return times_.size() == 1; }
  const std::vector<double>& times() const { return times_; }
  const std::vector<double>& speeds() const { return speeds_; }
  /// Smallest and largest speed over all time (the interpolant stays between its knots).
  double min_speed() const;
  double max_speed() const;
  /// Same knots (a constant speed equals any one-knot profile of that speed).
  bool same_as(const SpeedProfile& o) const;

 private:
  std::vector<double> times_{0.0}, speeds_{0.0}, slopes_{0.0}, angles_{0.0};
};

}  // namespace evas
