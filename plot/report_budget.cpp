// The error-budget section of `evas report`, see report_budget.h.
#include "plot/report_budget.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace evas {

std::vector<std::vector<std::string>> parse_csv(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> row;
  std::string field;
  bool quoted = false, any = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
        field += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        field += c;
      }
      continue;
    }
    if (c == '"') {
      quoted = any = true;
    } else if (c == ',') {
      row.push_back(field);
      field.clear();
      any = true;
    } else if (c == '\n' || c == '\r') {
      if (c == '\r' && i + 1 < text.size() && text[i + 1] == '\n') ++i;
      if (any || !field.empty()) {
        row.push_back(field);
        rows.push_back(row);
      }
      row.clear();
      field.clear();
      any = false;
    } else {
      field += c;
      any = true;
    }
  }
  if (any || !field.empty()) {
    row.push_back(field);
    rows.push_back(row);
  }
  return rows;
}

void budget_section(const std::string& results, report::Page& page) {
  namespace fs = std::filesystem;
  const fs::path file = fs::path(results).parent_path() / "budget_sources.csv";
  page.heading(2, "Error budget", "budget");
  if (!fs::exists(file)) {
    page.paragraph(
        "No error budget beside the results file. <code>evas study budget SCENE --out "
        "DIR</code>, DIR the run's output folder, measures the integration, start-up, basis "
        "and element-model errors of this answer and what removing each costs.",
        "note");
    return;
  }
  std::ifstream in(file);
  std::stringstream ss;
  ss << in.rdbuf();
  const auto rows = parse_csv(ss.str());
  const std::vector<std::string> want = {"source",    "measured",   "error", "channel",
                                         "wall",      "wall_ratio", "steps", "steps_ratio",
                                         "variation", "note"};
  if (!in || rows.empty() || rows[0] != want) {
    page.paragraph(
        report::escape(file.string()) + " is not a budget_sources.csv of evas study budget.",
        "note");
    return;
  }
  std::vector<std::vector<std::string>> body;
  std::string dominant;
  double largest = -1.0;
  for (std::size_t r = 1; r < rows.size(); ++r) {
    const auto& f = rows[r];
    if (f.size() != want.size()) continue;
    const std::string against = f[8].empty() ? f[9] : f[8] + (f[9].empty() ? "" : ": " + f[9]);
    body.push_back({f[0], f[1] == "yes" ? (f[2].empty() ? "-" : f[2]) : "not measured", f[3], f[4],
                    f[5], f[6], against});
    if (f[0] != "base" && f[1] == "yes" && !f[2].empty()) {
      const double e = std::strtod(f[2].c_str(), nullptr);
      if (e > largest) largest = e, dominant = f[0] + " (" + f[2] + " in " + f[3] + ")";
    }
  }
  page.table({"source", "error (largest channel)", "channel", "wall [s]", "wall / base", "steps",
              "measured against"},
             body, "Error budget of this answer (" + file.filename().string() + ")");
  if (!dominant.empty())
    page.paragraph("Dominant source of error: " + report::escape(dominant) +
                   ". Each error is relative to the "
                   "channel's amplitude over the base run's last cycle (budget.md beside it "
                   "has every channel).");
}

}  // namespace evas
