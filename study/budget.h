// `evas study budget SCENE`: the error budget of a scene's answer. Beside the
// run as the scene sets it up (the base), one variation per source of error,
// each removing that source, and per channel the difference it makes:
//
//   integration  the same scene with the integrator tightened (rtol and atol
//                divided by --tighten, or a fixed step divided by it);
//   start-up     the base run's last cycle against the scene's periodic cycle
//                (evas periodic's projected method, the base integrator), or,
//                when that does not converge, against the cycle before it;
//   basis        the scene on a richer modal basis: the edits of --richer
//                (e.g. crank.file=richer.h5), or else every mode of the body
//                files that the scene's `modes:` options leave out;
//   element      finer element models: the edits of --finer, or else every
//                journal bearing on a film coarser than Reynolds' equation
//                (short, finite) on film reynolds (tabulated where it can be);
//
// Each error is the study's measure (study/measure.h) over the base's last
// cycle (or the whole output without a crank-angle grid), relative to the
// variation's amplitude of the channel; with --orders N, of the last cycle's
// engine orders up to N only (the low orders the loads' sharing sets, apart
// from the fast film events). With each source its cost: the
// variation's wall time and steps, and their ratio to the base's, i.e. what
// removing that source would cost. The source with the largest error
// dominates. A source that cannot be measured on the scene is not measured,
// with the reason; nothing is hidden as a zero.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "study/study.h"

namespace evas::study {

struct BudgetOptions {
  std::vector<std::string> richer;  ///< ITEM.KEY=VALUE edits of the richer basis
  std::vector<std::string> finer;   ///< ITEM.KEY=VALUE edits of the finer element models
  double tighten = 100.0;           ///< rtol, atol (or a fixed step) divided by this
  /// > 0: the errors of the engine orders up to this only (the last cycle's
  /// Fourier series of base and variation; a crank-angle grid)
  double orders = 0.0;
};

struct BudgetSource {
  std::string name;       ///< integration, start-up, basis, element
  std::string variation;  ///< what was run to measure it ("" when not measured)
  bool measured = false;
  std::string note;                   ///< why not measured, or how it was measured
  std::vector<double> channel_error;  ///< per selected channel (NaN: not measured)
  double error = std::numeric_limits<double>::quiet_NaN();  ///< the largest channel's
  int channel = -1;                                         ///< that channel (index)
  double wall = std::numeric_limits<double>::quiet_NaN();   ///< the variation's wall [s]
  long steps = 0;
};

struct BudgetResult {
  StudyInfo info;
  std::vector<std::string> units;
  double base_wall = std::numeric_limits<double>::quiet_NaN();
  long base_steps = 0;
  std::string base_label;
  std::vector<BudgetSource> sources;
  int dominant = -1;    ///< index of the source with the largest error (-1: none measured)
  double orders = 0.0;  ///< BudgetOptions::orders
};

/// One 720-deg cycle of samples at equal angle steps (no repeated end point)
/// kept up to engine order `orders`: its Fourier series, harmonic k of the
/// cycle being order k / 2.
Vec low_orders(const Vec& x, double orders);

/// Runs the budget (Options as for every study: --param, --channels, --out,
/// --quiet; the window is always the base's last cycle). Throws ReferenceFailed
/// when the base run fails, InputError for bad input. Writes DIR/budget.csv
/// (per channel), DIR/budget_sources.csv and DIR/budget.md.
BudgetResult budget(const Options& opt, const BudgetOptions& bo);

/// The edits that put every journal bearing of the scene text on a film finer
/// than its own: `short` or `finite` -> `reynolds` (solve: table, or grid when
/// the bearing has cavitation: none); `changed` names the elements ("" when
/// none).
std::vector<std::string> finer_element_edits(const std::string& text, std::string& changed);

/// The scene text with the `modes:` cuts of every body removed (max_frequency,
/// elastic, quasi_static_above): the bodies' whole files. `changed` names the
/// bodies edited ("" when none).
std::string without_mode_cuts(const std::string& text, std::string& changed);

}  // namespace evas::study
