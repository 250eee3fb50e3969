// Figures by gnuplot (a Debian package; docs/dependencies.md): finding it,
// running scripts, quoting. Used by `evas plot` (plot/figures.h) and by the
// studies' diagrams (study/).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "io/text_escape.h"  // shell_quote

namespace evas {

/// True when `gnuplot` is on the PATH.
bool have_gnuplot();
/// Runs gnuplot on `script` in the script's folder (the script names its output
/// file without a folder); false on failure.
bool run_gnuplot(const std::filesystem::path& script);
/// Draws `script` into `figure` (the file the script's `set output` names):
/// removes a stale figure first, and a partial one when gnuplot fails (gnuplot
/// creates the file at `set output`, before an error in a plot), so that a
/// figure on disk is always one that was drawn. True when it was.
bool draw_figure(const std::filesystem::path& script, const std::filesystem::path& figure);
/// Several scripts of one folder in one gnuplot process, in order (gnuplot's
/// start is most of the time of a small figure). False when gnuplot failed.
bool run_gnuplot(const std::vector<std::filesystem::path>& scripts);
/// A gnuplot string literal: '...' with ' doubled.
std::string gp_quote(const std::string& s);
/// "%.*g" of x, "" for NaN (numbers in scripts and data blocks).
std::string gp_num(double x, int digits);
/// The terminal lines of a figure `out` (w x h pixels): pngcairo for .png,
/// svg otherwise; the output is named without its folder (run_gnuplot runs
/// in the script's folder).
std::string gp_terminal(const std::filesystem::path& out, int w, int h);

/// The unit a figure shows a channel of SI unit `unit` in, and the factor from
/// it: kN for N, MPa for Pa, mrad for rad, micrometres for m (else the unit).
struct DisplayScale {
  double factor = 1.0;
  std::string unit;
};
DisplayScale display_scale(const std::string& unit);

}  // namespace evas
