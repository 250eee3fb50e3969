// The journal's orbit under a periodic load: see bearing_orbit.h.
#include "elements/bearing_orbit.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "elements/bearing_static.h"
#include "model/types.h"

namespace evas {

namespace {

using V2 = Eigen::Vector2d;

std::string deg_text(double deg) {
  std::ostringstream os;
  os.precision(6);
  os << deg;
  return os.str();
}

// de/dt at (t, e) from the film's balance with the load W: Newton on
// g(ed) = f(e, ed) + W with the film's d f / d ed, halving the step while |g|
// does not fall (the pi-film's force is only piecewise smooth in ed).
class Mobility {
 public:
  Mobility(const JournalBearing& b, double om, const LoadCycle& load, double deg_per_s)
      : b_(b), om_(om), load_(load), deg_per_s_(deg_per_s), scale_(load.peak()) {}

  // Newton from the last velocity; where that fails (a closed-form film's
  // force is not smooth where the film's effective spin om - 2 d(gamma)/dt
  // changes sign), again from rest and from the whirl at half the spin (where
  // the film is a pure squeeze film).
  V2 velocity(double t, const V2& e, V2& guess, long& solves) const {
    const V2 half_whirl = 0.5 * om_ * V2(-e.y(), e.x());
    double residual = 0.0;
    const double deg = t * deg_per_s_;
    for (const V2& start : {guess, V2(V2::Zero()), half_whirl}) {
      V2 ed = start;
      bool found = false;
      try {
        found = newton(t, e, ed, solves, residual);
      } catch (const RunError& err) {  // the film's own limit (eps_max), at this angle
        throw RunError("at crank angle " + deg_text(deg) + " deg: " + err.what());
      }
      if (found) {
        guess = ed;
        return ed;
      }
    }
    throw RunError("at crank angle " + deg_text(deg) + " deg (eccentricity ratio " +
                   deg_text(e.norm() / b_.params().clearance) +
                   ") no journal velocity balances the load: the film cannot carry it (force "
                   "left " +
                   deg_text(residual) + " N)");
  }

 private:
  bool newton(double t, const V2& e, V2& ed, long& solves, double& residual) const {
    const V2 W = load_.at(t * deg_per_s_);
    FilmForce ff = b_.film(t, e, ed, om_, 1.0, true);
    ++solves;
    V2 g = ff.f + W;
    const double tol = 1e-11 * scale_;
    for (int it = 0; it < 60; ++it) {
      if (g.norm() <= tol) return true;
      const V2 d = -ff.df_ded.fullPivLu().solve(g);
      if (!d.allFinite()) break;
      double lambda = 1.0;
      bool fell = false;
      for (int half = 0; half < 30 && !fell; ++half, lambda *= 0.5) {
        const V2 trial = ed + lambda * d;
        const FilmForce ft = b_.film(t, e, trial, om_, 1.0, true);
        ++solves;
        const V2 gt = ft.f + W;
        if (gt.norm() < g.norm() * (1.0 - 1e-4 * lambda)) {
          ed = trial, ff = ft, g = gt, fell = true;
        }
      }
      if (!fell) break;
    }
    residual = g.norm();
    return residual <= 1e-8 * scale_;  // as far as the film's own accuracy goes
  }

  const JournalBearing& b_;
  double om_;
  const LoadCycle& load_;
  double deg_per_s_, scale_;
};

V2 start_position(const JournalBearing& b, double om, const V2& W) {
  const double c = b.params().clearance;
  if (W.norm() <= 0.0) return V2(1e-3 * c, 0.0);
  const BearingOperatingPoint p = bearing_at_load(b, om, W.norm());
  const double a = std::atan2(W.y(), W.x()) + p.attitude_deg * M_PI / 180.0;
  return p.eccentricity * c * V2(std::cos(a), std::sin(a));
}

}  // namespace

V2 LoadCycle::at(double deg) const {
  const double a0 = angle_deg.front(), T = period_deg();
  double x = a0 + std::fmod(deg - a0, T);
  if (x < a0) x += T;
  const auto it = std::upper_bound(angle_deg.begin(), angle_deg.end(), x);
  const std::size_t k = std::min<std::size_t>(
      static_cast<std::size_t>(std::max<std::ptrdiff_t>(it - angle_deg.begin(), 1)),
      angle_deg.size() - 1);
  const double s = (x - angle_deg[k - 1]) / (angle_deg[k] - angle_deg[k - 1]);
  return V2(fx[k - 1] + s * (fx[k] - fx[k - 1]), fy[k - 1] + s * (fy[k] - fy[k - 1]));
}

double LoadCycle::peak() const {
  double m = 0.0;
  for (std::size_t k = 0; k < fx.size(); ++k) m = std::max(m, std::hypot(fx[k], fy[k]));
  return m;
}

void check_load_cycle(const LoadCycle& c, const std::string& where) {
  const std::size_t n = c.angle_deg.size();
  if (n < 3 || c.fx.size() != n || c.fy.size() != n)
    throw InputError(where + ": a load cycle needs at least three rows (angle, fx, fy), got " +
                     std::to_string(n));
  for (std::size_t k = 0; k < n; ++k) {
    if (!std::isfinite(c.angle_deg[k]) || !std::isfinite(c.fx[k]) || !std::isfinite(c.fy[k]))
      throw InputError(where + ": row " + std::to_string(k + 1) + ": a value is not finite");
    if (k > 0 && !(c.angle_deg[k] > c.angle_deg[k - 1]))
      throw InputError(where + ": row " + std::to_string(k + 1) + ": angle " +
                       deg_text(c.angle_deg[k]) + " deg does not follow " +
                       deg_text(c.angle_deg[k - 1]) + " deg (angles must increase)");
  }
  const double peak = c.peak();
  if (!(peak > 0.0)) throw InputError(where + ": the load is zero at every row");
  if (std::hypot(c.fx.back() - c.fx.front(), c.fy.back() - c.fy.front()) > 1e-9 * peak)
    throw InputError(where + ": the last row (" + deg_text(c.angle_deg.back()) +
                     " deg) must repeat the first row's load: it closes the cycle of " +
                     deg_text(c.period_deg()) + " deg");
}

BearingOrbit bearing_orbit(const JournalBearing& b, double om, const LoadCycle& load,
                           const OrbitOptions& opt) {
  check_load_cycle(load, "load cycle");
  if (!(om > 0.0)) throw InputError("the journal's speed must be above 0");
  if (opt.samples < 4 || opt.max_cycles < 2 || !(opt.settle_tol > 0.0) || !(opt.tolerance > 0.0))
    throw InputError(
        "orbit options: samples >= 4, cycles >= 2 (settling compares two), tolerances above 0");
  if (const std::string why = b.run_refusal(); !why.empty()) throw InputError(why);
  const double c = b.params().clearance;
  const double deg_per_s = om * 180.0 / M_PI;
  const double a0 = load.angle_deg.front(), T = load.period_deg() / deg_per_s;
  const double t0 = a0 / deg_per_s, dt_sample = T / opt.samples;
  const Mobility mob(b, om, load, deg_per_s);

  BearingOrbit out;
  V2 e = start_position(b, om, load.at(a0)), guess = V2::Zero();
  // the points' velocities beside them: the peak pressure is computed for the
  // reported cycle's points only (a Reynolds film's solve each)
  std::vector<V2> vel, previous_vel;
  auto point = [&](double t, const V2& pos, const V2& ed) {
    OrbitPoint p;
    p.time = t;
    p.angle_deg = t * deg_per_s;
    p.e = pos;
    p.load = load.at(p.angle_deg);
    p.eccentricity = pos.norm() / c;
    p.min_film = c - pos.norm();
    vel.push_back(ed);
    return p;
  };
  auto finish = [&](std::vector<OrbitPoint>&& pts, const std::vector<V2>& ed) {
    for (std::size_t k = 0; k < pts.size(); ++k) {
      try {
        pts[k].max_pressure = b.peak_pressure(pts[k].e, ed[k], om);
      } catch (const RunError& err) {
        pts.resize(k);
        if (out.failure.empty()) out.failure = err.what();
        break;
      }
    }
    out.cycle = std::move(pts);
    return out;
  };
  // Bogacki & Shampine's 3(2) pair (Appl. Math. Lett. 2, 1989), first same as
  // last; the step from the local error of e against tolerance x c.
  double t = t0, h = dt_sample;
  V2 k1 = mob.velocity(t, e, guess, out.film_solves);
  std::vector<OrbitPoint> previous, pts;
  try {
    for (int cycle = 1; cycle <= opt.max_cycles; ++cycle) {
      vel.clear();
      pts.assign(1, point(t, e, k1));
      for (int s = 1; s <= opt.samples; ++s) {
        const double t_end = t0 + (cycle - 1 + static_cast<double>(s) / opt.samples) * T;
        while (t < t_end) {
          const bool last = t + h >= t_end - 1e-12 * T;
          const double step = last ? t_end - t : h;
          V2 g = guess, e1, k4;
          double r = 0.0;
          // A trial step that carries the journal to the wall (or past the
          // film's eps_max) is too long, not yet a failure: shorter, until the
          // step is 1e-9 of the cycle.
          try {
            const V2 k2 = mob.velocity(t + 0.5 * step, e + 0.5 * step * k1, g, out.film_solves);
            const V2 k3 = mob.velocity(t + 0.75 * step, e + 0.75 * step * k2, g, out.film_solves);
            e1 = e + step * (2.0 / 9.0 * k1 + 1.0 / 3.0 * k2 + 4.0 / 9.0 * k3);
            if (e1.norm() >= c)
              throw RunError("at crank angle " + deg_text((t + step) * deg_per_s) +
                             " deg the journal reaches the bearing's wall");
            k4 = mob.velocity(t + step, e1, g, out.film_solves);
            const V2 err =
                step * (-5.0 / 72.0 * k1 + 1.0 / 12.0 * k2 + 1.0 / 9.0 * k3 - 0.125 * k4);
            r = err.norm() / (opt.tolerance * c);
          } catch (const RunError&) {
            if (step <= 1e-9 * T) throw;
            ++out.rejected;
            h = 0.25 * step;
            continue;
          }
          if (r <= 1.0) {
            t = last ? t_end : t + step;
            e = e1, k1 = k4, guess = g;
            ++out.steps;
          } else {
            ++out.rejected;
          }
          const double grow = r > 0.0 ? 0.9 * std::pow(r, -1.0 / 3.0) : 5.0;
          h = std::clamp(grow, 0.2, 5.0) * step;
          if (!(h > 1e-12 * T))
            throw RunError("at crank angle " + deg_text(t * deg_per_s) +
                           " deg the orbit's step fell below 1e-12 of the cycle");
        }
        pts.push_back(point(t, e, k1));
      }
      out.cycles = cycle;
      if (!previous.empty()) {
        double move = 0.0;
        for (std::size_t k = 0; k < pts.size(); ++k)
          move = std::max(move, (pts[k].e - previous[k].e).norm() / c);
        out.change = move;
        if (move < opt.settle_tol) {
          out.settled = true;
          return finish(std::move(pts), vel);
        }
      }
      previous = std::move(pts);
      previous_vel = std::move(vel);
    }
  } catch (const RunError& err) {
    // the points of the cycle the journal was on when the film gave out
    out.failure = err.what();
    out.cycles += 1;
    return finish(std::move(pts), vel);
  }
  return finish(std::move(previous), previous_vel);
}

}  // namespace evas
