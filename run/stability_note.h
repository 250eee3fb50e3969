// A conditionally stable method's step against the model's highest frequency:
// said before a fixed-step run (a warning) and when one fails (appended to the
// failure), in the terms a researcher reads: the step, the highest frequency
// of the model linearized at that state, h omega against the method's limit
// (IntegratorCapabilities::stability_limit: 2 sqrt 3 for linear
// acceleration, 2 for the central difference, (gamma/2 - beta)^(-1/2) for
// Newmark's beta, gamma), and what set it: the coordinate that moves most in
// that mode and the share of its stiffness that comes from the elements' forces
// (bearing films, mounts, couplings) rather than the bodies' own modes.
//
// The frequency: omega^2 the largest |eigenvalue| of K = df/dq of qdd + f = 0
// (every coordinate at unit modal mass), from a dense eigen-decomposition
// (Eigen's EigenSolver) up to 1500 coordinates; problems with a mass matrix
// or constraints are not assessed ("" returned).
#pragma once

#include <string>

#include "integrators/integrator.h"
#include "model/model.h"
#include "model/problem.h"

namespace evas {

struct HighestFrequency {
  double omega = 0.0;          ///< [rad/s]; 0 when not assessed
  int coordinate = -1;         ///< the coordinate that moves most in that mode
  double element_share = 0.0;  ///< x^T (K - K_bodies) x / x^T K x of that mode
};

/// The highest frequency of `p` linearized at (t, q, v) (see above).
HighestFrequency highest_frequency(Problem& p, double t, const Vec& q, const Vec& v);

/// "" unless `s` takes fixed steps with a method whose stability limit is
/// finite and settings.step times the highest frequency at (t, q, v) exceeds
/// it; then one sentence saying so (step, h omega, limit, frequency, its
/// coordinate, the elements' share, the largest stable step).
std::string stability_limit_note(Problem& p, const IntegratorSettings& s, double t, const Vec& q,
                                 const Vec& v);

/// The same before a run of `model` from its initial state at t0 (a warning).
std::string stability_limit_warning(Model& model, const IntegratorSettings& s, double t0);

}  // namespace evas
