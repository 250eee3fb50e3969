// The checks of `evas study` and `evas problem` for CI (study/checks.h): the
// options that state them (--expect-error, --expect-stable-to,
// --expect-digits; --expect of convergence is its own), the files they go to
// (--junit FILE, --json FILE) and the exit code 3 when one failed.
#pragma once

#include <boost/program_options.hpp>
#include <string>
#include <vector>

#include "study/checks.h"
#include "study/study.h"

namespace evas::cli {

namespace po = boost::program_options;

/// --junit FILE and --json FILE.
void add_report_options(po::options_description& o);

/// The command line as one string (the report's `command`).
std::string command_line(const std::string& command, const std::vector<std::string>& args);

/// Writes the report to --junit / --json when given, prints every failed
/// check to stderr; 3 when a check failed, else 0.
int finish_checks(const po::variables_map& vm, const std::vector<study::CheckReport>& r);
int finish_checks(const po::variables_map& vm, const study::CheckReport& r);

/// The order check of --expect ORDER --tolerance TOL: the slope is NaN when
/// none could be fitted (then it fails, saying so).
study::Check order_check(const std::string& what, double slope, int points, double want,
                         double tol);

/// An --expect-error expression, parsed: channel globs, tolerance, case glob.
struct ErrorExpect {
  std::string globs, case_glob = "*";
  double tol = 0.0;
};
/// Parses "GLOBS<=TOL[@CASE]"; throws InputError naming the option.
ErrorExpect parse_error_expect(const std::string& expr);

/// One --expect-error "GLOBS<=TOL[@CASE]" (GLOBS comma-separated channel
/// globs, CASE a glob over the case labels, default every case): one check per
/// case it names, passed when the case completed and the largest error of the
/// selected channels is <= TOL. `names` are the study's channels. Throws
/// InputError for a malformed expression or globs that select nothing.
std::vector<study::Check> error_checks(const std::string& expr,
                                       const std::vector<study::CaseResult>& cases,
                                       const std::vector<std::string>& names);

/// --expect-stable-to H: one check per stability point, passed when the
/// largest stable step found is >= H.
std::vector<study::Check> stable_checks(double h, const study::StabilityResult& res);

}  // namespace evas::cli
