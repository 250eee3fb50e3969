// Cylinder pressure at several operating points: a set of 720 deg tables
// (gas_pressure.h), one per engine speed, interpolated linearly in speed
// between the two tables that bracket the current crank speed:
//   p(theta, w) = (1 - s) p_k(theta) + s p_k+1(theta),  s = (w - w_k) / (w_k+1 - w_k).
// One table: that table at every speed. A speed outside [w_first, w_last] is
// not extrapolated: the piston checks the crank's whole speed range against
// the map when the scene is read (check_covers) and refuses a scene that
// leaves it, naming both ranges.
//
// Map file format (a text file; relative table paths are relative to it):
//     # any comment
//     1500   cylinder_pressure_1500rpm.txt     <- speed [rpm]  table file
//     3000   cylinder_pressure_3000rpm.txt
// Speeds strictly increasing and positive.
#pragma once

#include <string>
#include <vector>

#include "elements/gas_pressure.h"

namespace evas {

class PressureMap {
 public:
  struct Entry {
    double speed = 0.0;  ///< [rad/s]
    PressureTable table;
  };
  /// Speeds strictly increasing (> 0); `where` names the source in errors.
  PressureMap(std::vector<Entry> entries, const std::string& where);
  /// Reads the map file and its tables; throws InputError naming file and line.
  static PressureMap read(const std::string& path);

  /// Pressure [Pa] at cycle angle theta [rad] and crank speed w [rad/s]
  /// (clamped to the map's range; see check_covers).
  double operator()(double theta, double w) const;
  double min_speed() const { return entries_.front().speed; }
  double max_speed() const { return entries_.back().speed; }
  const std::vector<Entry>& entries() const { return entries_; }
  /// Throws InputError "<where>: ..." naming both ranges (in rpm) when
  /// [w_lo, w_hi] is not inside the map's speeds (relative tolerance 1e-4).
  void check_covers(double w_lo, double w_hi, const std::string& where) const;

 private:
  std::vector<Entry> entries_;
  std::string source_;
};

}  // namespace evas
