// The problem library behind `evas problem`: test problems in the general
// form of solver/problem.h with published reference solutions, scored as the
// Test Set for IVP Solvers scores them (F. Mazzia, C. Magherini, University of
// Bari, "Test Set for IVP Solvers", release 2.4, 2008): mixed-error significant
// correct digits at the end point,
//     mescd = -log10 max_i |y_i - ref_i| / (atol/rtol + |ref_i|),
// and the relative version scd = -log10 max_i |y_i - ref_i| / |ref_i| (over the
// components whose reference exceeds 1e-6 of the largest), both over positions
// and velocities; the multipliers, where a reference has them, apart.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "model/implicit_dae.h"
#include "model/problem.h"

namespace evas::problems {

struct LibraryProblem {
  std::string name;         ///< e.g. "car-axis"
  std::string description;  ///< one line, with the source
  double t_end = 0.0;       ///< end point of the reference [s]
  /// Reference at t_end: positions then velocities (2 n values), then, where
  /// published, the multipliers in evas's sign (may be empty).
  std::vector<double> reference_qv, reference_lambda;
  std::string source;  ///< where the reference comes from
  std::function<std::unique_ptr<Problem>()> make;
  /// A first-order implicit problem M y' = f(t, y) (model/implicit_dae.h) is
  /// made here instead of by `make`, and its reference at t_end (every
  /// component of y) is in reference_y.
  std::function<std::unique_ptr<ImplicitDae>()> make_implicit;
  std::vector<double> reference_y;
  bool implicit() const { return bool(make_implicit); }
};

/// All problems of the library, in a fixed order.
const std::vector<LibraryProblem>& library();
/// The problem named `name`; throws InputError listing the names.
const LibraryProblem& library_problem(const std::string& name);

struct Score {
  double mescd = 0.0, scd = 0.0;  ///< over positions and velocities
  double mescd_lambda = 0.0;      ///< over the multipliers (NaN without a reference)
  int worst = -1;                 ///< the component that sets mescd
};

/// Scores the end point y of a first-order implicit problem over all its
/// components (as the test set scores them; mescd_lambda is NaN).
Score score_implicit(const LibraryProblem& p, const Vec& y, double rtol, double atol);

/// Scores the end point (q, v, lambda) against the reference with the ratio
/// atol/rtol of the test set's formula.
Score score(const LibraryProblem& p, const Vec& q, const Vec& v, const Vec& lambda, double rtol,
            double atol);

}  // namespace evas::problems
