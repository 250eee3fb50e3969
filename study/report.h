// Output helpers of the studies: CSV/Markdown cells, atomic file writes,
// number formats and gnuplot.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "model/types.h"

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

/// True when `gnuplot` is on the PATH.
bool have_gnuplot();
/// Runs gnuplot on `script` in the script's folder (the script names its output
/// file without a folder); false on failure.
bool run_gnuplot(const std::filesystem::path& script);
/// Several scripts of one folder in one gnuplot process, in order (gnuplot's
/// start is most of the time of a small figure). False when gnuplot failed.
bool run_gnuplot(const std::vector<std::filesystem::path>& scripts);
/// Text as a gnuplot single-quoted string literal.
std::string gp_quote(const std::string& s);

}  // namespace evas::study
