// The published results of the IVP Test Set's solvers on the problems of the
// library, shown beside evas's in `evas study work-precision problem:NAME`
// (and docs/problems.md): F. Mazzia, C. Magherini, "Test Set for Initial
// Value Problem Solvers", release 2.4, University of Bari, February 2008,
// part II, the tables "Run characteristics" of each problem (andrews II.13.3,
// car axis II.17.2, fekete II.18.2, crank II.19.3, chemakzo II.12.2, transamp
// II.14.3), runs at rtol = atol. Their mescd is over every component of their
// formulation, evas's over q and v (docs/problems.md says where they differ).
#pragma once

#include <string>
#include <vector>

namespace evas::problems {

struct PublishedRun {
  std::string problem, solver;
  double tol = 0.0;  ///< rtol = atol
  double mescd = 0.0, scd = 0.0;
  long steps = 0;
};

/// The published runs on `problem` (empty when the report has none).
std::vector<PublishedRun> published_runs(const std::string& problem);

/// Where the figures come from (one line).
const char* published_source();

}  // namespace evas::problems
