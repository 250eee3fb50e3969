// Figures by gnuplot (gnuplot.h).
#include "plot/gnuplot.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "io/fe_pipeline.h"  // find_program

namespace evas {

// Looked up on PATH (find_program), not by starting a shell for `command -v`
// (5 to 10 ms a call; a sweep asks at its start and again for its figures).
bool have_gnuplot() { return !find_program({"gnuplot"}).empty(); }

bool run_gnuplot(const std::filesystem::path& script) {
  return run_gnuplot(std::vector<std::filesystem::path>{script});
}

bool run_gnuplot(const std::vector<std::filesystem::path>& scripts) {
  if (scripts.empty()) return true;
  // from the scripts' folder: a script names its output without a folder
  const std::filesystem::path& first = scripts.front();
  const std::filesystem::path dir = first.has_parent_path() ? first.parent_path() : ".";
  std::string cmd = "cd " + shell_quote(dir.string()) + " && gnuplot";
  for (const auto& s : scripts) cmd += " " + shell_quote(s.filename().string());
  return std::system((cmd + " >/dev/null 2>&1").c_str()) == 0;
}

bool draw_figure(const std::filesystem::path& script, const std::filesystem::path& figure) {
  std::error_code ec;
  std::filesystem::remove(figure, ec);  // a stale figure must not pass for a new one
  if (run_gnuplot(script) && std::filesystem::exists(figure, ec) &&
      std::filesystem::file_size(figure, ec) > 0 && !ec)
    return true;
  std::filesystem::remove(figure, ec);
  return false;
}

std::string gp_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) {
    if (c == '\'') out += '\'';
    out += c;
  }
  return out + "'";
}

std::string gp_num(double x, int digits) {
  if (std::isnan(x)) return "";
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*g", digits, x);
  return buf;
}

std::string gp_terminal(const std::filesystem::path& out, int w, int h) {
  std::string gp;
  if (out.extension() == ".svg")
    gp = "set terminal svg noenhanced size " + std::to_string(w) + "," + std::to_string(h) +
         " dynamic font 'Helvetica,13'\n";
  else
    gp = "set terminal pngcairo noenhanced size " + std::to_string(w) + "," + std::to_string(h) +
         " font ',11'\n";
  return gp + "set output " + gp_quote(out.filename().string()) + "\n";
}

DisplayScale display_scale(const std::string& unit) {
  if (unit == "N") return {1e-3, "kN"};
  if (unit == "Pa") return {1e-6, "MPa"};
  if (unit == "rad") return {1e3, "mrad"};
  if (unit == "m") return {1e6, "\u00b5m"};
  return {1.0, unit.empty() ? "-" : unit};
}

}  // namespace evas
