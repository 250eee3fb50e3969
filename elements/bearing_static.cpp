// Static operating point of a journal bearing: see bearing_static.h.
#include "elements/bearing_static.h"

#include <cmath>
#include <sstream>

#include "elements/film_reynolds.h"
#include "model/types.h"

namespace evas {

namespace {

using V2 = Eigen::Vector2d;

// Film force magnitude at eccentricity ratio eps along the bearing's x axis.
double carried(const JournalBearing& b, double om, double eps) {
  return bearing_at_eccentricity(b, om, eps).load;
}

}  // namespace

BearingOperatingPoint bearing_at_eccentricity(const JournalBearing& b, double om, double eps) {
  const JournalBearingParams& p = b.params();
  if (!(eps > 0.0 && eps < 1.0))
    throw InputError("eccentricity ratio " + std::to_string(eps) + " must lie in (0, 1)");
  if (!(om > 0.0)) throw InputError("the journal's speed must be above 0");
  const double c = p.clearance;
  // The load is -f. Turn the bearing frame so that the load lies along +x: the
  // line of centres then sits at the attitude angle from x. (The Reynolds
  // film's grid is fixed in the bearing, so its force turns with e only to
  // the grid's accuracy: the angle is corrected until the force lies along -x.)
  double attitude = 0.0;
  V2 e;
  FilmForce ff;
  for (int it = 0; it < 8; ++it) {
    e = eps * c * V2(std::cos(attitude), std::sin(attitude));
    ff = b.hydro(e, V2::Zero(), om, 1.0, true, p.closed_form);
    const double off = std::atan2(-ff.f.y(), -ff.f.x());  // of the load, from x
    attitude -= off;
    if (std::abs(off) < 1e-13) break;
  }
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
  } else if (p.film == "reynolds") {
    ReynoldsGrid g;
    g.n_phi = p.grid_phi;
    g.n_axial = p.grid_axial;
    g.cavitation = p.cavitation;
    r.side_flow = ReynoldsFilm(p.radius, p.width, c, p.viscosity, g).solve(e, W, false).side_flow;
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
  // bisection: the film force grows monotonically with eps
  for (int it = 0; it < 100 && hi - lo > 1e-13; ++it) {
    const double mid = 0.5 * (lo + hi);
    (carried(b, om, mid) < load ? lo : hi) = mid;
  }
  return bearing_at_eccentricity(b, om, 0.5 * (lo + hi));
}

}  // namespace evas
