// The error-budget section of `evas report`: when `evas study budget` wrote
// budget_sources.csv into the folder of the results file (its --out the run's
// output folder), the page shows one row per source of error (integration,
// start-up, basis, element): the largest error, its channel, the cost of
// removing it against the base run, and what it was measured against.
#pragma once

#include <string>
#include <vector>

#include "plot/report_html.h"

namespace evas {

/// The fields of each line of an RFC 4180 CSV text (quoted fields, doubled quotes).
std::vector<std::vector<std::string>> parse_csv(const std::string& text);

/// Adds the section when DIR_OF(results)/budget_sources.csv exists; else a
/// note saying how to compute one. A file that cannot be read is said so.
void budget_section(const std::string& results, report::Page& page);

}  // namespace evas
