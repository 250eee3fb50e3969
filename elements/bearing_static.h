// The static answer of one journal bearing (`evas bearing`): for a journal
// spinning at om under a steady load, or at a given eccentricity ratio, the
// operating point and its linearized stiffness and damping, from the same film
// code the element uses at run time (JournalBearing::hydro). Frame: the
// bearing's, turned in its plane so that the load on the journal points along
// +x (y at +90 deg from it, the journal spinning from x towards y).
#pragma once

#include <Eigen/Dense>
#include <optional>

#include "elements/journal_bearing.h"

namespace evas {

struct BearingOperatingPoint {
  double load = 0.0;                    ///< load carried [N]
  double eccentricity = 0.0;            ///< eccentricity ratio eps = e / c [-]
  double attitude_deg = 0.0;            ///< angle from the load line to the line of centres [deg]
  double sommerfeld = 0.0;              ///< S = (R/c)^2 eta N / P, N [rev/s], P = W / (2 R B) [-]
  double friction_torque = 0.0;         ///< viscous torque on the journal [N m] (magnitude)
  double friction_variable = 0.0;       ///< (R/c) f, f = T / (R W) [-]
  double power_loss = 0.0;              ///< T om [W]
  double min_film = 0.0;                ///< c (1 - eps) [m]
  double max_pressure = 0.0;            ///< [Pa] (finite film: estimate, docs)
  double max_pressure_angle_deg = 0.0;  ///< from the load line, towards +y [deg]
  std::optional<double> side_flow;      ///< out of both ends [m^3/s] (none for finite)
  /// cavitation mass-conserving: flow out of the grooves into the film [m^3/s]
  /// (equal to the side flow: the film's mass balance) and the smallest film fraction
  std::optional<double> feed_flow, film_fraction_min;
  Eigen::Matrix2d K = Eigen::Matrix2d::Zero();  ///< -d f / d e [N/m], x along the load
  Eigen::Matrix2d C = Eigen::Matrix2d::Zero();  ///< -d f / d edot [N s/m]
};

/// The operating point at eccentricity ratio eps (0 < eps < 1), relative spin om [rad/s] > 0.
BearingOperatingPoint bearing_at_eccentricity(const JournalBearing& b, double om, double eps);
/// The operating point carrying `load` [N] > 0: eccentricity found by bisection;
/// a load beyond the film's capacity at eps = 0.999 is an InputError.
BearingOperatingPoint bearing_at_load(const JournalBearing& b, double om, double load);

}  // namespace evas
