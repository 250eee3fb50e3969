// The test set's published runs (published.h), as printed in its report.
#include "problems/published.h"

namespace evas::problems {

const char* published_source() {
  return "F. Mazzia, C. Magherini, Test Set for IVP Solvers, release 2.4 (Bari, 2008), part II, "
         "tables Run characteristics (rtol = atol)";
}

std::vector<PublishedRun> published_runs(const std::string& problem) {
  // problem, solver, rtol = atol, mescd, scd, steps
  static const std::vector<PublishedRun> all = {
      {"andrews", "MEBDFI", 1e-4, -1.11, 0.37, 118},
      {"andrews", "RADAU", 1e-4, -0.84, 1.36, 96},
      {"andrews", "PSIDE-1", 1e-4, 0.22, 2.95, 92},
      {"andrews", "BIMD", 1e-4, 0.27, 3.05, 46},
      {"andrews", "MEBDFI", 1e-7, 1.25, 3.50, 300},
      {"andrews", "RADAU", 1e-7, 0.47, 4.45, 114},
      {"andrews", "PSIDE-1", 1e-7, 2.10, 4.98, 113},
      {"andrews", "BIMD", 1e-7, 2.82, 5.38, 122},
      {"car-axis", "MEBDFI", 1e-4, 0.88, -0.23, 280},
      {"car-axis", "RADAU", 1e-4, 1.34, 0.19, 98},
      {"car-axis", "PSIDE-1", 1e-4, 0.83, -0.28, 55},
      {"car-axis", "BIMD", 1e-4, 2.19, 0.34, 71},
      {"car-axis", "MEBDFI", 1e-7, 4.65, 3.34, 650},
      {"car-axis", "RADAU", 1e-7, 3.73, 2.51, 289},
      {"car-axis", "PSIDE-1", 1e-7, 4.41, 2.27, 179},
      {"car-axis", "BIMD", 1e-7, 5.47, 3.34, 138},
      {"car-axis", "MEBDFI", 1e-10, 4.21, 2.08, 1393},
      {"car-axis", "RADAU", 1e-10, 5.99, 4.22, 179},
      {"car-axis", "PSIDE-1", 1e-10, 7.25, 4.86, 625},
      {"car-axis", "BIMD", 1e-10, 8.01, 5.35, 235},
      {"fekete", "RADAU", 1e-2, 3.43, 1.97, 33},
      {"fekete", "MEBDFI", 1e-2, 3.56, 2.10, 60},
      {"fekete", "PSIDE-1", 1e-2, 3.66, 2.20, 73},
      {"fekete", "RADAU", 1e-3, 4.11, 2.65, 43},
      {"fekete", "MEBDFI", 1e-3, 4.58, 3.23, 129},
      {"fekete", "RADAU", 1e-4, 5.36, 4.29, 61},
      {"fekete", "MEBDFI", 1e-4, 5.81, 4.81, 218},
      {"fekete", "BIMD", 1e-4, 6.69, 5.33, 65},
      {"crank", "MEBDFI", 1e-4, 0.22, 1.49, 250},
      {"crank", "RADAU", 1e-4, 0.20, 1.90, 104},
      {"crank", "PSIDE-1", 1e-4, -0.05, 0.93, 45},
      {"crank", "MEBDFI", 1e-6, 0.03, 3.03, 3328},
      {"crank", "RADAU", 1e-6, 0.14, 2.89, 132},
      {"crank", "PSIDE-1", 1e-6, 0.16, 2.43, 259},
      {"crank", "MEBDFI", 1e-8, 2.72, 5.71, 6316},
      {"crank", "RADAU", 1e-8, 1.65, 4.65, 420},
      {"crank", "PSIDE-1", 1e-8, 1.66, 4.66, 1639},
      {"chemakzo", "DDASSL", 1e-10, 10.04, 8.33, 522},
      {"chemakzo", "RADAU", 1e-10, 10.71, 8.39, 43},
      {"chemakzo", "MEBDFI", 1e-10, 11.42, 9.76, 274},
      {"transamp", "DDASSL", 1e-4, 4.60, 3.08, 9759},
      {"transamp", "MEBDFI", 1e-4, 5.06, 4.80, 1580},
      {"transamp", "PSIDE-1", 1e-4, 5.02, 4.76, 516},
      {"transamp", "DDASSL", 1e-7, 7.24, 5.49, 40810},
      {"transamp", "RADAU", 1e-7, 7.11, 6.83, 1775},
      {"transamp", "MEBDFI", 1e-7, 7.25, 6.99, 3628},
  };
  std::vector<PublishedRun> out;
  for (const auto& r : all)
    if (r.problem == problem) out.push_back(r);
  return out;
}

}  // namespace evas::problems
