// Closed-form film of a journal bearing of finite width for dynamic loads:
// H.-J. Butenschoen, "Das hydrodynamische, zylindrische Gleitlager endlicher
// Breite unter instationaerer Belastung", Dissertation, Universitaet Karlsruhe
// (1976), as summarised by the hydrodynamic plain bearing of MBDyn
// (Politecnico di Milano). Holland's superposition of a rotation part (the
// film carried round by the effective speed om - 2 d(delta)/dt) and a squeeze
// part (the journal's radial speed), each a Sommerfeld number fitted to the
// Reynolds solution with the Reynolds cavitation condition over the width
// ratio B/D = b/d and the eccentricity ratio:
//   So_D = (b/d)^2 eps sqrt(pi^2 (1 - eps^2) + 16 eps^2) / (2 (1 - eps^2)^2)
//          a1 (eps - 1) / (a2 + eps)
//   So_V = 4 (b/d)^2 (1 - eps^2)^(-5/2) ((pi/2 - acos(eps)/2) (1 + 2 eps^2)
//          + 3/2 eps sqrt(1 - eps^2)) a8 (1 - eps) / (-a9 - eps)
// (eps carrying the sign of the radial speed in So_V: an approaching journal
// squeezes the film on its own side, a receding one the other half), the
// rotation force at beta(eps) behind the line of centres, and
// F = So B D eta omega / psi^2, psi = c / R. a1..a9 are polynomials in b/d
// (docs/elements-journal-bearing.md, "Film models", gives them and the
// accuracy measured against Raimondi & Boyd's tables and the Reynolds film).
//
// Derivatives are exact: the force is evaluated in forward-mode automatic
// differentiation (Eigen's AutoDiffScalar) over (e, ed, om).
#pragma once

#include "elements/film_force.h"

namespace evas {

/// Width ratios B/D over which the fit is offered (docs: its accuracy).
constexpr double kFiniteFilmMinWidthRatio = 0.125;
constexpr double kFiniteFilmMaxWidthRatio = 1.0;

/// Force on the journal of a bearing of radius R, width B, radial clearance c,
/// viscosity eta for eccentricity e, its rate ed and relative spin om (bearing
/// components, elements/journal_bearing.h); the derivatives when `derivs`.
/// The caller checks |e| < c.
FilmForce finite_film(double R, double B, double c, double eta, const Eigen::Vector2d& e,
                      const Eigen::Vector2d& ed, double om, bool derivs);

}  // namespace evas
