// Static operating point of a journal bearing: see bearing_static.h.
#include "elements/bearing_static.h"

#include <cmath>
#include <sstream>

#include "elements/film_reynolds.h"
#include "model/types.h"

namespace evas {

namespace {

using V2 = Eigen::Vector2d;

// The journal's offset at eccentricity ratio eps for which the film's force
// (returned in *ff, without derivatives) points along -x, so that the load lies along +x. The load
// is -f: the line of centres sits at the attitude angle from x. The film of a
// plain bearing turns with e (the Reynolds grid only to its accuracy), one of a
// grooved bearing does not: the angle is found by secant steps on the force's
// direction.
// With `none` given, a film that no direction aligns with the load (a feed's
// own push outweighing the film at small eps) sets *none and returns; else that
// is an error.
V2 offset_against_load(const JournalBearing& b, double om, double eps, FilmForce* ff,
                       bool* none = nullptr) {
  const JournalBearingParams& p = b.params();
  auto off = [&](double a, V2* e) {  // angle of the load, from x
    *e = eps * p.clearance * V2(std::cos(a), std::sin(a));
    *ff = b.hydro(*e, V2::Zero(), om, 1.0, false, p.closed_form);
    return std::atan2(-ff->f.y(), -ff->f.x());
  };
  V2 e;
  double a0 = 0.0, o0 = off(a0, &e);
  if (std::abs(o0) < 1e-13) return e;
  double a1 = -o0, o1 = off(a1, &e);
  for (int it = 0; it < 30 && std::abs(o1) >= 1e-13; ++it) {
    double slope = (o1 - o0) / (a1 - a0);
    if (!(slope > 0.2 && slope < 5.0)) slope = 1.0;  // the plain bearing's 1
    a0 = a1, o0 = o1;
    a1 -= std::remainder(o1, 2.0 * M_PI) / slope;
    o1 = off(a1, &e);
  }
  if (std::abs(o1) < 1e-13) return e;
  // The force's direction jumps where a cell of the grid changes state: no
  // secant root. Bisect a bracket of the sign change down to the jump.
  FilmForce f_hi = *ff;  // at a1
  double lo = a1, hi = a1, olo = o1, step = 1e-3;
  while (olo * o1 > 0.0 && step < 1.0) {  // the load turns the other way with the angle
    lo = a1 - (o1 > 0.0 ? step : -step);
    olo = off(lo, &e);
    step *= 2.0;
  }
  if (olo * o1 > 0.0 && none) {
    *none = true;
    return e;
  }
  if (olo * o1 > 0.0)
    throw RunError("no journal position at eccentricity ratio " + std::to_string(eps) +
                   " carries the load along its line");
  double ohi = o1;
  FilmForce f_lo = *ff;  // at lo
  for (int it = 0; it < 60 && std::abs(hi - lo) > 1e-15; ++it) {
    const double mid = 0.5 * (lo + hi), omid = off(mid, &e);
    if (omid * ohi > 0.0)
      hi = mid, ohi = omid, f_hi = *ff;
    else
      lo = mid, olo = omid, f_lo = *ff;
  }
  // the end with the smaller remainder, its force kept (no solve again)
  const bool low = std::abs(olo) < std::abs(ohi);
  const double left = low ? olo : ohi;
  *ff = low ? f_lo : f_hi;
  e = eps * p.clearance * V2(std::cos(low ? lo : hi), std::sin(low ? lo : hi));
  if (none && std::abs(left) > 0.5 * M_PI) {  // the bracket held the turn through +-pi
    *none = true;
    return e;
  }
  if (std::abs(left) > 2e-3)
    throw RunError("at eccentricity ratio " + std::to_string(eps) + " the film's force turns by " +
                   std::to_string(std::abs(left)) +
                   " rad where a cell of the grid changes state: refine grid_phi");
  return e;
}

// Film force magnitude at eccentricity ratio eps, the load along x; 0 where
// no direction carries a load along its line (a fed oil hole or groove pushes
// the journal harder than the film at small eps: a larger eps is needed).
double carried(const JournalBearing& b, double om, double eps) {
  FilmForce ff;
  bool none = false;
  offset_against_load(b, om, eps, &ff, &none);
  return none ? 0.0 : ff.f.norm();
}

}  // namespace

BearingOperatingPoint bearing_at_eccentricity(const JournalBearing& b, double om, double eps) {
  const JournalBearingParams& p = b.params();
  if (!(eps > 0.0 && eps < 1.0))
    throw InputError("eccentricity ratio " + std::to_string(eps) + " must lie in (0, 1)");
  if (!(om > 0.0)) throw InputError("the journal's speed must be above 0");
  const double c = p.clearance;
  FilmForce ff;
  const V2 e = offset_against_load(b, om, eps, &ff);
  ff = b.hydro(e, V2::Zero(), om, 1.0, true, p.closed_form);  // with K and C
  BearingOperatingPoint r;
  r.eccentricity = eps;
  r.load = ff.f.norm();
  r.attitude_deg = std::abs(std::atan2(e.y(), e.x())) * 180.0 / M_PI;
  const double N = om / (2.0 * M_PI), P = r.load / (2.0 * p.radius * p.width);
  r.sommerfeld = (p.radius / c) * (p.radius / c) * p.viscosity * N / P;
  r.friction_torque = std::abs(b.friction_torque(e, om, ff.f, 1.0));
  r.friction_variable = r.friction_torque / (c * r.load);
  r.power_loss = r.friction_torque * om;
  r.min_film = c * (1.0 - eps);
  double angle = 0.0;
  r.max_pressure = b.peak_pressure(e, V2::Zero(), om, &angle);
  r.max_pressure_angle_deg = angle * 180.0 / M_PI;
  const V2 W = -0.5 * om * V2(-e.y(), e.x());
  if (p.film == "short") {
    r.side_flow = 2.0 * p.radius * p.width * W.norm();  // B g at each end over g > 0
  } else if (const ReynoldsFilm* film = b.reynolds_film(); film && film->grid().mass_conserving) {
    const ReynoldsSolution s = film->solve_mass_conserving(e, V2::Zero(), om, false);
    r.side_flow = s.side_flow;
    r.feed_flow = s.feed_flow;
    r.film_fraction_min = s.theta_min;
  } else if (film) {
    r.side_flow = film->solve(e, W, false).side_flow;
  }
  r.K = -ff.df_de;
  r.C = -ff.df_ded;
  return r;
}

BearingOperatingPoint bearing_at_load(const JournalBearing& b, double om, double load) {
  if (!(load > 0.0)) throw InputError("the load must be above 0 N");
  if (!(om > 0.0)) throw InputError("the journal's speed must be above 0");
  double lo = 0.0, hi = 0.999;
  const double cap = carried(b, om, hi);
  if (load > cap) {
    std::ostringstream os;
    os << "a load of " << load << " N is beyond the film's capacity at this speed (" << cap
       << " N at eccentricity ratio 0.999)";
    throw InputError(os.str());
  }
  // The film force grows monotonically with eps: regula falsi with the Illinois
  // modification (Dowell & Jarratt, BIT 11 (1971) 168-174) on carried - load,
  // bracketed by [0, 0.999]; superlinear where bisection took 40 films
  double glo = -load, ghi = cap - load, x = hi;
  int side = 0;
  for (int it = 0; it < 200 && hi - lo > 1e-12; ++it) {
    x = (lo * ghi - hi * glo) / (ghi - glo);
    if (!(x > lo && x < hi)) x = 0.5 * (lo + hi);
    const double g = carried(b, om, x) - load;
    if (std::abs(g) <= 1e-13 * load) break;
    if (g < 0.0) {
      lo = x, glo = g;
      if (side == -1) ghi *= 0.5;
      side = -1;
    } else {
      hi = x, ghi = g;
      if (side == 1) glo *= 0.5;
      side = 1;
    }
  }
  if (hi - lo <= 1e-12) x = 0.5 * (lo + hi);
  return bearing_at_eccentricity(b, om, x);
}

}  // namespace evas
