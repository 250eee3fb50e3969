// One run of a library problem (apps/cmd_problem.cpp) and the work-precision
// sweep over integrators and formulations behind `evas problem --work-precision`.
#pragma once

#include <filesystem>
#include <string>

#include "integrators/integrator.h"
#include "problems/library.h"

namespace evas::cli {

struct ProblemRun {
  Vec q, v, lambda;  ///< end point (lambda empty when the integrator has none)
  Vec y;             ///< end point of a first-order implicit problem (q, v, lambda empty)
  problems::Score score;
  IntegratorStats stats;
  double wall = 0.0;    ///< init + integration [s]
  double g_end = 0.0;   ///< max |g| at the end
  std::string failure;  ///< empty: completed
};

/// Runs `lp` from 0 to its t_end with settings `s`; integration failures are
/// returned in `failure`, bad settings throw InputError. A first-order implicit
/// problem (lp.implicit()) runs with ida on its own residual M y' - f; other
/// integrators and formulations are refused for it.
ProblemRun run_problem(const problems::LibraryProblem& lp, const IntegratorSettings& s);

/// IDA in every formulation and Radau IIA in index-3, index-2 and index-1 over
/// rtol 1e-3 ... 1e-10 and generalized-alpha over eight halvings of its step (a
/// first-order implicit problem: IDA and Radau IIA over rtol 1e-3 ... 1e-12): a table on stdout,
/// DIR/work_precision.csv, and DIR/work_precision.png (digits against wall time) when gnuplot is
/// there.
void problem_work_precision(const problems::LibraryProblem& lp, const std::filesystem::path& dir);

}  // namespace evas::cli
