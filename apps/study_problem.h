// `evas study work-precision|convergence problem:NAME`: the studies on the
// problems of `evas problem` (problems/library.h) instead of a scene. Each
// case runs the problem to its end point and is scored as the IVP Test Set
// scores it (mescd, scd); the error of a case is 10^-mescd (--norm scd:
// 10^-scd), and the component that sets it is named. The work-precision
// table and figure show the test set's published solvers (problems/
// published.h) beside evas's cases.
#pragma once

#include <boost/program_options.hpp>
#include <string>
#include <vector>

#include "integrators/integrator.h"
#include "problems/library.h"
#include "study/checks.h"

namespace evas::cli {

namespace po = boost::program_options;

/// True when `target` (a SCENE argument) is "problem:NAME".
bool is_problem(const std::string& target);

/// The formulation a run of `s` on `lp` uses ("default" resolved: ida ggl,
/// radau and the Newmark family index-3; "M y' = f" for a first-order problem,
/// "none" without constraints).
std::string formulation_used(const problems::LibraryProblem& lp, const IntegratorSettings& s);

/// The case settings of a problem study: the spec over the base of `evas
/// problem` (rtol 1e-8, first step t_end / 2000), atol = rtol * atol_ratio
/// unless the spec sets atol.
IntegratorSettings problem_case_settings(IntegratorSettings s, const std::string& spec,
                                         double atol_ratio);

/// The studies on problem `target` ("problem:NAME") into `out` ("" = the
/// default folder), their checks into `report` (written by the caller);
/// bad input throws InputError.
void problem_work_precision_study(const po::variables_map& vm, const std::vector<std::string>& args,
                                  const std::string& target, const std::string& out,
                                  study::CheckReport& report);
/// The largest stable fixed step of one case on problem `target` in
/// [h_min, h_max]: a step is stable when the run completes and the end point's
/// largest |component| is at most `growth` times the published reference's
/// (a problem is judged at its end point). h_max first, then h_min, then
/// `bisections` bisections in log h. Writes stability.csv/.md.
void problem_stability(const po::variables_map& vm, const std::vector<std::string>& args,
                       const std::string& target, const std::string& out, double h_min,
                       double h_max, double growth, int bisections, study::CheckReport& report);
void problem_convergence(const po::variables_map& vm, const std::vector<std::string>& args,
                         const std::string& target, const std::string& out,
                         study::CheckReport& report);

}  // namespace evas::cli
