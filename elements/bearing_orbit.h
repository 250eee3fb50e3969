// The journal's orbit in one bearing under a periodic load (`evas bearing
// --load-cycle`): the journal massless, so that at every instant the film's
// force balances the load, f(e, de/dt, om) + W(t) = 0. That balance is solved
// for the journal's velocity de/dt (Newton on the film's damping -df/d(de/dt))
// and the velocity integrated over the cycle (an embedded Runge-Kutta pair):
// the idea of Booker's mobility method (J. Basic Eng. 87, 1965), here with
// the element's own film (any film model, the same code as at run time)
// instead of a fitted mobility map. Cycles repeat until the orbit settles.
// Frame: the bearing's (x, y in its plane, the journal spinning from x to y).
#pragma once

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "elements/journal_bearing.h"

namespace evas {

/// A load on the journal over one period of the crank's angle: rows of angle
/// [deg], increasing, the last one period after the first with the first's load
/// (a closed cycle); linear between rows.
struct LoadCycle {
  std::vector<double> angle_deg;  ///< [deg]
  std::vector<double> fx, fy;     ///< load on the journal [N], bearing frame
  /// Last angle minus the first [deg].
  double period_deg() const { return angle_deg.back() - angle_deg.front(); }
  /// The load at crank angle `deg` (any angle: the cycle repeats).
  Eigen::Vector2d at(double deg) const;
  /// Largest load magnitude of the rows [N].
  double peak() const;
};

/// Throws InputError naming `where` when the cycle is not usable (fewer than
/// three rows, angles not increasing, a load not finite, an open cycle, no load).
void check_load_cycle(const LoadCycle& c, const std::string& where);

struct OrbitOptions {
  int samples = 360;         ///< output points per cycle
  int max_cycles = 30;       ///< cycles at most (at least 2: settling compares two)
  double settle_tol = 1e-4;  ///< settled: the orbit moved less than this x c in a cycle
  double tolerance = 1e-7;   ///< local error of a step, x c
};

struct OrbitPoint {
  double angle_deg = 0.0, time = 0.0;
  Eigen::Vector2d e = Eigen::Vector2d::Zero();  ///< journal centre from the bearing's [m]
  Eigen::Vector2d load = Eigen::Vector2d::Zero();
  double eccentricity = 0.0;  ///< |e| / c
  double min_film = 0.0;      ///< c - |e| [m]
  double max_pressure = 0.0;  ///< mid-plane peak [Pa] (finite film: estimate)
};

struct BearingOrbit {
  /// the last cycle, `samples` + 1 points (both ends); after a failure the
  /// points of the cycle it broke off
  std::vector<OrbitPoint> cycle;
  std::string failure;  ///< why the orbit broke off (crank angle, state), empty if it did not
  int cycles = 0;       ///< cycles run
  double change = 0.0;  ///< largest move of an orbit point over the last cycle, x c
  bool settled = false;
  long steps = 0, rejected = 0, film_solves = 0;
};

/// The orbit of the journal of `b` spinning at om [rad/s] (crank angle = om t)
/// under `load`, from the static position of the load at the cycle's first
/// angle (or near the centre when that load is zero). When the film cannot
/// carry the load (the journal at the wall) the orbit breaks off: `failure`
/// names the crank angle and the state, `cycle` holds the points reached.
BearingOrbit bearing_orbit(const JournalBearing& b, double om, const LoadCycle& load,
                           const OrbitOptions& opt);

}  // namespace evas
