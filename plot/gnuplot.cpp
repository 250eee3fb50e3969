// Figures by gnuplot (gnuplot.h).
#include "plot/gnuplot.h"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace evas {

// An executable `gnuplot` in a folder of PATH (what the shell's `command -v`
// finds), looked up here rather than by starting a shell for it (5 to 10 ms
// a call; a sweep asks at its start and again for its figures).
bool have_gnuplot() {
  const char* path = std::getenv("PATH");
  const std::string dirs = path ? path : "/usr/bin:/bin";
  std::size_t start = 0;
  while (start <= dirs.size()) {
    const std::size_t end = std::min(dirs.find(':', start), dirs.size());
    const std::string dir = end > start ? dirs.substr(start, end - start) : ".";
    const std::string file = dir + "/gnuplot";
    struct stat st;
    if (::stat(file.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(file.c_str(), X_OK) == 0)
      return true;
    start = end + 1;
  }
  return false;
}

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

}  // namespace evas
