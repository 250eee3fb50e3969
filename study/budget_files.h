// The files of `evas study budget` (budget.h): DIR/budget.csv (one row per
// channel: its error from each source), DIR/budget_sources.csv (one row per
// source: largest error, its channel, the variation's wall time and steps and
// their ratios to the base run, what was run, why not measured) and
// DIR/budget.md (both tables and which source dominates). `evas report`
// shows budget_sources.csv when it lies beside the results file.
#pragma once

#include <filesystem>
#include <string>

#include "study/budget.h"

namespace evas::study {

/// Writes the three files (atomically) and adds them to info.files.
void write_budget_files(const std::filesystem::path& dir, const BudgetResult& res, StudyInfo& info);

/// The Markdown page (budget.md).
std::string budget_markdown(const BudgetResult& res);

}  // namespace evas::study
