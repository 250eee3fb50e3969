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
//   element      a finer element model where one exists (none yet: said so).
//
// Each error is the study's measure (study/measure.h) over the base's last
// cycle (or the whole output without a crank-angle grid), relative to the
// variation's amplitude of the channel. With each source its cost: the
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
  double tighten = 100.0;           ///< rtol, atol (or a fixed step) divided by this
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
  int dominant = -1;  ///< index of the source with the largest error (-1: none measured)
};

/// Runs the budget (Options as for every study: --param, --channels, --out,
/// --quiet; the window is always the base's last cycle). Throws ReferenceFailed
/// when the base run fails, InputError for bad input. Writes DIR/budget.csv
/// (per channel), DIR/budget_sources.csv and DIR/budget.md.
BudgetResult budget(const Options& opt, const BudgetOptions& bo);

/// The scene text with the `modes:` cuts of every body removed (max_frequency,
/// elastic, quasi_static_above): the bodies' whole files. `changed` names the
/// bodies edited ("" when none).
std::string without_mode_cuts(const std::string& text, std::string& changed);

}  // namespace evas::study
