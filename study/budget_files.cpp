// The files of `evas study budget`, see budget_files.h.
#include "study/budget_files.h"

#include <cmath>
#include <sstream>

#include "study/report.h"

namespace evas::study {

namespace {

std::string ratio(double a, double b) {
  return (std::isfinite(a) && std::isfinite(b) && b > 0.0) ? gnum(a / b, 3) : "";
}

std::string ratio_steps(long a, long b) {
  return (a > 0 && b > 0) ? gnum(static_cast<double>(a) / static_cast<double>(b), 3) : "";
}

std::string channel_name(const BudgetResult& r, int c) {
  return c >= 0 && c < static_cast<int>(r.info.channels.size())
             ? r.info.channels[static_cast<std::size_t>(c)]
             : "";
}

}  // namespace

std::string budget_markdown(const BudgetResult& r) {
  std::ostringstream md;
  md << "# Error budget: " << r.info.scene_name << "\n\n"
     << "- scene: `" << r.info.scene_path << "`\n"
     << "- base run: " << r.base_label << ", " << gnum(r.base_wall, 3) << " s wall, "
     << r.base_steps << " steps\n"
     << "- error of a channel: " << r.info.error_definition << " (the base's output)"
     << (r.orders > 0.0 ? "; of the last cycle's engine orders up to " + gnum(r.orders, 4) +
                              " only (its Fourier series)"
                        : std::string())
     << "\n\n"
     << "| source | error (largest channel) | channel | wall [s] | wall / base | steps | "
        "steps / base | measured against |\n"
     << "|---|---:|---|---:|---:|---:|---:|---|\n";
  for (const auto& s : r.sources) {
    md << "| " << s.name << " | " << (s.measured ? sci(s.error, 2) : "not measured") << " | "
       << md_cell(channel_name(r, s.channel)) << " | " << gnum(s.wall, 3) << " | "
       << ratio(s.wall, r.base_wall) << " | " << (s.steps > 0 ? std::to_string(s.steps) : "")
       << " | " << ratio_steps(s.steps, r.base_steps) << " | "
       << md_cell(s.measured ? s.variation + ": " + s.note : s.note) << " |\n";
  }
  md << "\n";
  if (r.dominant >= 0) {
    const BudgetSource& d = r.sources[static_cast<std::size_t>(r.dominant)];
    md << "**Dominant source: " << d.name << "** (" << sci(d.error, 2) << " in "
       << channel_name(r, d.channel) << "). Removing it costs " << ratio(d.wall, r.base_wall)
       << "x the base's wall time (" << d.variation << ").\n\n";
  } else {
    md << "No source could be measured.\n\n";
  }
  md << "Per channel (empty: not measured, or the channel is constant):\n\n| channel | unit |";
  for (const auto& s : r.sources) md << " " << s.name << " |";
  md << "\n|---|---|";
  for (std::size_t k = 0; k < r.sources.size(); ++k) md << "---:|";
  md << "\n";
  for (std::size_t c = 0; c < r.info.channels.size(); ++c) {
    md << "| " << md_cell(r.info.channels[c]) << " | " << md_cell(r.units[c]) << " |";
    for (const auto& s : r.sources) md << " " << sci(s.channel_error[c], 2) << " |";
    md << "\n";
  }
  return md.str();
}

void write_budget_files(const std::filesystem::path& dir, const BudgetResult& r, StudyInfo& info) {
  std::ostringstream per;
  per << "channel,unit";
  for (const auto& s : r.sources) per << "," << csv_field(s.name);
  per << "\n";
  for (std::size_t c = 0; c < r.info.channels.size(); ++c) {
    per << csv_field(r.info.channels[c]) << "," << csv_field(r.units[c]);
    for (const auto& s : r.sources) per << "," << sci(s.channel_error[c], 6);
    per << "\n";
  }
  std::ostringstream src;
  src << "source,measured,error,channel,wall,wall_ratio,steps,steps_ratio,variation,note\n";
  for (const auto& s : r.sources)
    src << csv_field(s.name) << "," << (s.measured ? "yes" : "no") << "," << sci(s.error, 6) << ","
        << csv_field(channel_name(r, s.channel)) << "," << gnum(s.wall, 6) << ","
        << ratio(s.wall, r.base_wall) << "," << (s.steps > 0 ? std::to_string(s.steps) : "") << ","
        << ratio_steps(s.steps, r.base_steps) << "," << csv_field(s.variation) << ","
        << csv_field(s.note) << "\n";
  src << "base,yes,,," << gnum(r.base_wall, 6) << ",1," << r.base_steps << ",1,"
      << csv_field(r.base_label) << ",\n";
  const std::vector<std::pair<std::string, std::string>> files = {
      {"budget.csv", per.str()},
      {"budget_sources.csv", src.str()},
      {"budget.md", budget_markdown(r)}};
  for (const auto& [name, text] : files) {
    write_file_atomic(dir / name, text);
    info.files.push_back((dir / name).string());
  }
}

}  // namespace evas::study
