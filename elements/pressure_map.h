// Cylinder pressure at several operating points: a set of 720 deg tables
// (gas_pressure.h), one per engine speed and, optionally, per engine load.
// Within one load the tables are interpolated linearly in speed between the
// two that bracket the current crank speed:
//   p_j(theta, w) = (1 - s) p_j,k(theta) + s p_j,k+1(theta),  s = (w - w_k) / (w_k+1 - w_k);
// with loads, linearly in the load between the two loads that bracket the
// scene's operating_point.load L:
//   p(theta, w, L) = (1 - u) p_j(theta, w) + u p_j+1(theta, w),  u = (L - L_j) / (L_j+1 - L_j).
// One table: that table at every speed; one load: that load's tables at every
// load. Nothing is extrapolated: the piston checks the crank's whole speed
// range against every load's speeds when the scene is read (check_covers) and
// the load against the map's loads (check_load), and refuses a scene that
// leaves them, naming both ranges. The load is a coordinate only: evas
// interpolates in it and never interprets it (a fraction of full load, bmep
// in bar, ...: whatever unit the map's author chose).
//
// Map file format (a text file; relative table paths are relative to it):
// either every line `speed_rpm table_file` (no load) ...
//     # any comment
//     1500   cylinder_pressure_1500rpm.txt     <- speed [rpm]  table file
//     3000   cylinder_pressure_3000rpm.txt
// ... or every line `speed_rpm load table_file`, the lines of one load
// together, loads increasing from group to group:
//     1500   0.5   p_1500rpm_half.txt          <- speed [rpm]  load [map's unit]  table
//     3000   0.5   p_3000rpm_half.txt
//     1000   1.0   p_1000rpm_full.txt          (each load its own speeds)
//     3000   1.0   p_3000rpm_full.txt
// Speeds strictly increasing (within a load) and positive; loads finite.
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
  /// The tables of one load, speeds strictly increasing.
  struct Load {
    double load = 0.0;  ///< [the map's unit]
    std::vector<Entry> entries;
  };
  /// A map without loads. Speeds strictly increasing (> 0); `where` names the
  /// source in errors.
  PressureMap(std::vector<Entry> entries, const std::string& where);
  /// A map with loads: loads finite and strictly increasing, each with at least
  /// one table, its speeds strictly increasing (> 0).
  PressureMap(std::vector<Load> loads, const std::string& where);
  /// Reads the map file and its tables; throws InputError naming file and line.
  static PressureMap read(const std::string& path);

  /// True when the file has a load column (the pressure needs a load).
  bool has_loads() const { return has_loads_; }
  /// Pressure [Pa] at cycle angle theta [rad] and crank speed w [rad/s]
  /// (clamped to the map's range; see check_covers). A map without loads only.
  double operator()(double theta, double w) const;
  /// The same at load L (clamped to the map's loads; see check_load). A map
  /// with loads only.
  double operator()(double theta, double w, double L) const;
  /// The speeds every load covers: the largest first and the smallest last speed.
  double min_speed() const;
  double max_speed() const;
  double min_load() const { return loads_.front().load; }
  double max_load() const { return loads_.back().load; }
  /// The tables of a map without loads (of the first load otherwise).
  const std::vector<Entry>& entries() const { return loads_.front().entries; }
  const std::vector<Load>& loads() const { return loads_; }
  const std::string& source() const { return source_; }
  /// Throws InputError "<where>: ..." naming both ranges (in rpm, and the load
  /// with loads) when [w_lo, w_hi] is not inside the speeds of every load
  /// (relative tolerance 1e-4).
  void check_covers(double w_lo, double w_hi, const std::string& where) const;
  /// Throws InputError "<where>: ..." naming the load and the map's loads when
  /// L is outside them (relative tolerance 1e-9 of their span; one load: any L).
  void check_load(double L, const std::string& where) const;

 private:
  std::vector<Load> loads_;  // without loads: one, of load 0
  bool has_loads_ = false;
  std::string source_;
  void check_speeds(const std::vector<Entry>& entries, const std::string& where) const;
};

}  // namespace evas
