// Output helpers of the studies: CSV/Markdown cells, atomic file writes,
// number formats and gnuplot.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "model/types.h"
#include "plot/gnuplot.h"

namespace evas::study {

/// A CSV field (quoted when it holds a comma, quote or line break).
std::string csv_field(const std::string& s);
/// A Markdown table cell ('|' escaped, line breaks as spaces), cut to `max_len` characters.
std::string md_cell(const std::string& s, std::size_t max_len = 0);
/// "%.*e" of x, "" for NaN.
std::string sci(double x, int digits = 3);
/// "%.*g" of x, "" for NaN.
std::string gnum(double x, int digits = 6);
/// Integer text of x, "" for NaN.
std::string inum(double x);

/// Writes `text` to path.tmp and renames it onto `path` (a reader never sees
/// half a file). Throws RunError naming the file.
void write_file_atomic(const std::filesystem::path& path, const std::string& text);

// gnuplot (plot/gnuplot.h), by its study names
using evas::gp_quote;
using evas::have_gnuplot;
using evas::run_gnuplot;

}  // namespace evas::study
