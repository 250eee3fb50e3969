// Sub-commands of the `evas` executable. Each takes the arguments after its
// name (args[0] is the sub-command) and returns the process exit code:
// 0 success, 1 bad input (InputError), 2 the run or the command failed;
// `evas run` 128 + N when stopped by signal N (docs/errors.md).
#pragma once

#include <boost/program_options.hpp>
#include <string>
#include <vector>

namespace evas {
struct IntegratorSettings;
}

namespace evas::cli {

namespace po = boost::program_options;

/// Parses args[1..] against `opts` plus the positional arguments named in
/// `positional` (one value each, in order). Returns true when --help was given
/// (the help is printed); the command then exits 0.
bool parse_args(const std::vector<std::string>& args, const po::options_description& opts,
                const std::vector<std::string>& positional, po::variables_map& vm);

/// The elastic modes kept, from `--elastic all|N` of `evas body` and `evas
/// modal import`: "all" gives 0 (BuildOptions::num_elastic: every mode), N >= 1
/// gives N. "0" is refused: the scene's `modes: {elastic: 0}` keeps none, and
/// the command line must not read the same words the opposite way.
int parse_elastic_option(const std::string& value);

/// Warns on stderr ("evas COMMAND: warning: ...") of each integrator setting
/// given on the command line (--rtol, --atol, --step, and each --set
/// KEY=VALUE) that the run's method `s` does not read
/// (setting_unread_reason): `--step 1e-5` on an ida run would otherwise be
/// ignored without a word. The options absent from `vm` are skipped.
void warn_unread_settings(const std::string& command, const po::variables_map& vm,
                          const IntegratorSettings& s);

int cmd_run(const std::vector<std::string>& args);
/// `evas periodic SCENE`: the periodic cycle of a scene (run/periodic_folder.h).
int cmd_periodic(const std::vector<std::string>& args);
int cmd_info(const std::vector<std::string>& args);
int cmd_export(const std::vector<std::string>& args);
int cmd_body(const std::vector<std::string>& args);
int cmd_elements(const std::vector<std::string>& args);
int cmd_modal(const std::vector<std::string>& args);
int cmd_spectrum(const std::vector<std::string>& args);
int cmd_plot(const std::vector<std::string>& args);
/// `evas report RESULTS.h5 --out DIR`: the HTML page of an engine run (plot/report_page.h).
int cmd_report(const std::vector<std::string>& args);
/// `evas study work-precision|convergence|stability` (apps/cmd_study.cpp, logic in study/).
/// Exit codes also: 3 convergence --expect not met, 128 + N stopped by signal N.
int cmd_study(const std::vector<std::string>& args);
/// `evas problem NAME`: the DAE test problems (apps/cmd_problem.cpp, problems/library.h).
int cmd_problem(const std::vector<std::string>& args);
/// `evas bearing`: the static answer of one journal bearing (apps/cmd_bearing.cpp).
int cmd_bearing(const std::vector<std::string>& args);

}  // namespace evas::cli
