// Helpers of the journal-bearing tests (test_journal_bearing.cpp,
// test_journal_bearing_rotor.cpp): base parameters, the Ocvirk film force,
// load capacity, the Sommerfeld quartic, Friswell's coefficients and the
// static equilibrium (references in test_journal_bearing.cpp).
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>

#include "elements/journal_bearing.h"
#include "integrators/integrator.h"
#include "solver/system.h"

using namespace evas;
using V2 = Eigen::Vector2d;
using M2 = Eigen::Matrix2d;

namespace jb_support {

JournalBearingParams base_params(bool closed_form = true, int n_delta = 64, int halves = 1) {
  JournalBearingParams p;
  p.radius = 0.025;
  p.width = 0.02;
  p.clearance = 50e-6;
  p.viscosity = 0.02;
  p.closed_form = closed_form;
  p.n_delta = n_delta;
  p.halves = halves;
  return p;
}

JournalBearing make_bearing(const JournalBearingParams& p, const std::string& name = "jb") {
  return JournalBearing(name, {0, 1}, p);
}

// references.md s.1: forces on the journal in the line-of-centres frame (r along e,
// t at +90 deg in the direction of rotation), pi-film over delta in (0, pi).
V2 ocvirk_reference(const JournalBearingParams& p, const V2& e, const V2& ed, double om) {
  const double c = p.clearance, en = e.norm(), eps = en / c;
  const V2 r = e / en, t(-r.y(), r.x());
  const double epsd = ed.dot(r) / c, gd = ed.dot(t) / en;
  const double k = p.viscosity * p.radius * std::pow(p.width, 3) / (2 * c * c), s = 1 - eps * eps;
  const double Fr = -k * (2 * (om - 2 * gd) * eps * eps / (s * s) +
                          M_PI * epsd * (1 + 2 * eps * eps) / std::pow(s, 2.5));
  const double Ft =
      k * (M_PI * (om - 2 * gd) * eps / (2 * std::pow(s, 1.5)) + 4 * eps * epsd / (s * s));
  return Fr * r + Ft * t;
}

// Steady load capacity (references.md s.1).
double load_capacity(const JournalBearingParams& p, double om, double eps) {
  const double c = p.clearance;
  return p.viscosity * om * p.radius * std::pow(p.width, 3) / (4 * c * c) * eps *
         std::sqrt(M_PI * M_PI * (1 - eps * eps) + 16 * eps * eps) / std::pow(1 - eps * eps, 2);
}

// Root in (0, 1) of the quartic in x = eps^2 for the modified Sommerfeld number.
double eps_from_quartic(double Ss) {
  const double pi2 = M_PI * M_PI;
  auto f = [&](double x) {
    return (((x - 4) * x + (6 - Ss * Ss * (16 - pi2))) * x - (4 + pi2 * Ss * Ss)) * x + 1;
  };
  double lo = 0.0, hi = 1.0;  // f(0) = 1 > 0, f(1) = -Ss^2 pi^2 - Ss^2 (16 - pi^2) < 0
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) > 0 ? lo : hi) = mid;
  }
  return std::sqrt(0.5 * (lo + hi));
}

// Friswell et al. short-bearing coefficients (references.md s.1): K = (W/c) a, C = (W/(c om)) b.
void friswell(double eps, M2& a, M2& b) {
  const double e2 = eps * eps, pi2 = M_PI * M_PI, s = 1 - e2, rs = std::sqrt(s);
  const double h0 = std::pow(pi2 * s + 16 * e2, -1.5);
  a(0, 0) = 4 * h0 * (pi2 * (2 - e2) + 16 * e2);
  a(0, 1) = M_PI * h0 * (pi2 * s * s - 16 * e2 * e2) / (eps * rs);
  a(1, 0) = -M_PI * h0 * (pi2 * s * (1 + 2 * e2) + 32 * e2 * (1 + e2)) / (eps * rs);
  a(1, 1) = 4 * h0 * (pi2 * (1 + 2 * e2) + 32 * e2 * (1 + e2) / s);
  b(0, 0) = 2 * M_PI * h0 * rs * (pi2 * (1 + 2 * e2) - 16 * e2) / eps;
  b(0, 1) = b(1, 0) = -8 * h0 * (pi2 * (1 + 2 * e2) - 16 * e2);
  b(1, 1) = 2 * M_PI * h0 * (pi2 * s * s + 48 * e2) / (eps * rs);
}

// Static equilibrium of the journal under the load (0, -W): Newton on
// f(e) + (0, -W) = 0 with the element's analytic derivative df/de.
V2 equilibrium(const JournalBearing& jb, double om, double W, int* iterations = nullptr) {
  const double c = jb.params().clearance;
  V2 e(0.3 * c, -0.3 * c);
  int it = 0;
  for (; it < 100; ++it) {
    const FilmForce f = jb.hydro(e, V2::Zero(), om, 1.0, true, jb.params().closed_form);
    const V2 r = f.f + V2(0.0, -W);
    V2 de = -f.df_de.lu().solve(r);
    // Keep the iterate inside the clearance circle.
    double lam = 1.0;
    while ((e + lam * de).norm() > 0.999 * c) lam *= 0.5;
    e += lam * de;
    if (de.norm() < 1e-15 * c) break;
  }
  if (iterations) *iterations = it;
  return e;
}

}  // namespace jb_support

using namespace jb_support;
