// Sets of study targets (`--and`: one study over several scenes or problems,
// as DiffEqDevTools' WorkPrecisionSet runs one set of setups over several
// problems) and `evas study compare` (study/compare.h) for the command line.
#pragma once

#include <boost/program_options.hpp>
#include <functional>
#include <string>
#include <vector>

#include "study/checks.h"

namespace evas::cli {

namespace po = boost::program_options;

/// --and (a set of targets) and --atol-ratio (problem targets) of
/// work-precision and convergence.
void add_target_options(po::options_description& o);

/// A study's target (a SCENE argument or problem:NAME) and its output folder.
struct Target {
  std::string scene, out;
};

/// The SCENE argument and every --and; one target keeps --out, a set puts
/// each into OUT/<name> (OUT default out/study-set).
std::vector<Target> targets_of(const po::variables_map& vm, const std::string& sub);

/// Runs `one` on every target (each prints its own table) and writes the
/// checks of all to --junit/--json; for a set also OUT/set.md, one row per
/// target. The exit code: the first target's that did not complete (2, 128 +
/// N), else 3 when a check failed, else 0.
int run_targets(const po::variables_map& vm, const std::vector<Target>& targets,
                const std::function<int(const Target&, study::CheckReport&)>& one);

/// `evas study compare A B ...` (args[0] is "compare").
int study_compare(const std::vector<std::string>& args);

}  // namespace evas::cli
