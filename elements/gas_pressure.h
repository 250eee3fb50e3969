// Cylinder gas pressure over one four-stroke cycle (720 deg of crank angle).
//
// A PressureTable holds measured or synthetic points (cycle angle, pressure)
// and interpolates them periodically with a monotone piecewise-cubic Hermite
// curve (Fritsch-Carlson / Fritsch-Butland slopes, the PCHIP of MATLAB and
// SciPy, wrapped around the period): C1, local, and free of overshoot, so a
// steep combustion rise never rings and the curve stays within the range of
// its neighbouring data (docs/elements-piston-motor.md explains the choice).
//
// Cycle angle convention: 0 = firing TDC of the cylinder; the curve has
// period 720 deg. Angles passed in are in radians (period 4 pi); pressures in
// Pa; slopes in Pa/rad.
//
// Text file format (docs/elements-piston-motor.md):
//     # unit: bar            <- required before the first data line: bar, kPa, MPa or Pa,
//                               optionally followed by "gauge" (pressures relative to
//                               the atmosphere; absolute otherwise)
//     # any other comment
//     0.0    1.85            <- crank_angle_deg  pressure, any spaces/tabs
//     0.5    1.86
//     ...
// Angles strictly increasing, the first in [0, max_gap], the last below 720
// (a final row at first + 720 is accepted if its pressure repeats the first),
// no spacing (wrap-around included) above max_gap. Absolute pressures must not
// be negative, gauge pressures not below -1 atm (-101325 Pa); no pressure may
// exceed kMaxPressure in magnitude. The file must be a regular file of at most
// kMaxFileBytes (a device or pipe such as /dev/zero is refused before reading).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "model/types.h"

namespace evas {

class PressureTable {
 public:
  /// Largest accepted spacing between table angles (wrap-around included) [deg].
  static constexpr double kDefaultMaxGap = 10.0;
  /// Largest accepted |pressure| [Pa] (1e5 bar): anything above is a wrong unit or a corrupt table.
  static constexpr double kMaxPressure = 1e10;
  /// Largest accepted table file [bytes] (64 MiB).
  static constexpr long long kMaxFileBytes = 64LL << 20;

  PressureTable() = default;
  /// From points (angles in deg, pressures in Pa). `where` names the source in
  /// error messages. Same checks as the file reader.
  PressureTable(std::vector<double> angle_deg, std::vector<double> p_Pa, const std::string& where,
                double max_gap_deg = kDefaultMaxGap);

  /// Reads the text format above; throws InputError naming file and line.
  static PressureTable read(const std::string& path, double max_gap_deg = kDefaultMaxGap);
  /// read(path, max_gap_deg), parsed once per process while the file's state
  /// (model/file_state.h) is unchanged, and shared: a study or sweep parses
  /// its scene once per point and run. Thread-safe; errors are not kept.
  static std::shared_ptr<const PressureTable> read_cached(const std::string& path,
                                                          double max_gap_deg = kDefaultMaxGap);
  /// Writes the text format (unit bar, one row per point).
  void write(const std::string& path, const std::string& comment) const;

  /// Pressure [Pa] at cycle angle theta [rad] (any real value, period 4 pi); if
  /// dp_dtheta is given, the slope [Pa/rad] there.
  double operator()(double theta, double* dp_dtheta = nullptr) const;

  bool empty() const { return angle_.empty(); }
  const std::vector<double>& angles_deg() const { return angle_; }
  const std::vector<double>& pressures() const { return p_; }
  double max_pressure() const;

 private:
  void build();
  std::vector<double> angle_, p_, slope_;  // slope_: dp/dangle [Pa/deg] at the knots
  double step_ = 0.0;  // the angle step of a uniform table [deg] (0: not uniform)
};

/// Synthetic direct-injection diesel cycle (references.md section 3): single
/// zone, double Wiebe heat release, polytropic compression and expansion between
/// inlet valve closing and exhaust valve opening, smooth gas-exchange pressures
/// elsewhere. Defaults: one cylinder of a 4.1 L in-line four at 3000 rpm, full
/// load (peak about 14 MPa about 10 deg after TDC).
struct DieselCycle {
  double bore = 0.106;    ///< [m]
  double stroke = 0.116;  ///< [m]
  double conrod = 0.190;  ///< [m]
  double compression_ratio = 17.5;
  double p_intake = 2.0e5;      ///< boost pressure, also the pressure at IVC [Pa]
  double p_exhaust = 2.2e5;     ///< exhaust back pressure [Pa]
  double ivc_deg = -145.0;      ///< inlet valve closing, cycle deg (firing TDC = 0)
  double evo_deg = 130.0;       ///< exhaust valve opening
  double n_compression = 1.36;  ///< polytropic exponent before combustion
  double n_expansion = 1.30;    ///< polytropic exponent of the burnt charge
  double soc_deg = -2.0;        ///< start of combustion
  double wiebe_a = 6.9;
  double premixed_fraction = 0.15;
  double premixed_duration_deg = 8.0;
  double premixed_m = 2.0;
  double diffusion_duration_deg = 55.0;
  double diffusion_m = 0.8;
  /// Net heat released per cycle [J]; if target_peak > 0 it is found by bisection
  /// so that the peak pressure equals target_peak.
  double heat_release = 2.0e3;
  double target_peak = 14.0e6;  ///< [Pa], <= 0 to use heat_release as given
  double step_deg = 0.5;        ///< table spacing
};

/// Table of the synthetic cycle on [0, 720) with spacing `step_deg`; `used_heat`
/// receives the heat release used [J].
PressureTable synthetic_diesel_cycle(const DieselCycle& c, double* used_heat = nullptr);

/// The cycle `ref` (calibrated at `ref_rpm` and full load, its heat release
/// `ref_heat` [J], e.g. what synthetic_diesel_cycle found for its target peak)
/// moved to speed `rpm` and load `load` (fuel per cycle as a fraction of full
/// load, 0 < load <= 1.5):
///  - combustion durations (premixed and diffusion) in crank degrees scale
///    with (n / n_ref)^0.5 and the diffusion shape exponent m with
///    (n_ref / n)^0.3 (Woschni & Anisits, "Experimental investigation and
///    mathematical presentation of rate of heat release in diesel engines
///    dependent upon engine operating conditions", SAE 740086, 1974, at equal
///    air-fuel ratio and ignition delay);
///  - heat release per cycle = load x ref_heat (a flat full-load torque curve:
///    the same fuel per cycle at every speed) and no target peak;
///  - boost pressure above ambient (1 bar) scales with (n / n_ref)^2 up to
///    `ref`'s at n_ref and stays there above it (a turbocharger with
///    wastegate), the exhaust back pressure keeping its excess over the boost
///    in proportion; the start of combustion stays at ref.soc_deg (an
///    injection map that holds it). These last two are assumptions of this
///    model, not of the paper.
/// Throws InputError for rpm <= 0 or a load outside (0, 1.5].
DieselCycle diesel_cycle_at(const DieselCycle& ref, double ref_rpm, double ref_heat, double rpm,
                            double load);

}  // namespace evas
