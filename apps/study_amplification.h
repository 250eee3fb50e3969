// `evas study amplification` (study/amplification.h) for the command line.
#pragma once

#include <string>
#include <vector>

namespace evas::cli {

/// `evas study amplification --case SPEC ...`: the one-step amplification of
/// integrator settings; prints amplification.md. Exit 0, or 1 when every case
/// was refused.
int study_amplification(const std::vector<std::string>& args);

}  // namespace evas::cli
