// `evas study compare A B`: two study tables (CSV) compared cell by cell with
// tolerances, as numdiff does, for regression checks in CI. Rows are matched
// by the key column (default the first: a case's label), columns by name;
// two numbers agree when |a - b| <= atol + rtol max(|a|, |b|), two texts when
// they are equal, two empty cells always. Columns matching an --ignore glob
// (default the wall times) are skipped. A row or column that only one table
// has is a difference. Folders: every CSV file both hold.
#pragma once

#include <string>
#include <vector>

namespace evas::study {

struct CompareOptions {
  double rtol = 1e-9, atol = 0.0;
  std::vector<std::string> ignore = {"wall", "wall_seconds"};  ///< column globs
  std::string key;  ///< column that names the rows ("" = the first)
};

struct CellDiff {
  std::string file, row, column, a, b;
  double abs = 0.0, rel = 0.0;  ///< NaN for a text or a missing cell
};

struct CompareResult {
  std::vector<std::string> files;     ///< the tables compared (file names)
  std::vector<CellDiff> diffs;        ///< every cell that differs
  std::vector<std::string> problems;  ///< rows or columns only one table has
  long cells = 0;                     ///< cells compared
  bool same() const { return diffs.empty() && problems.empty(); }
};

/// Compares the tables at a and b (two CSV files, or two folders: each CSV
/// file of a that b holds too). Throws InputError naming a file that cannot be
/// read, a folder pair without a common CSV file, or a key column missing.
CompareResult compare_tables(const std::string& a, const std::string& b, const CompareOptions& o);

/// The report: the files, the counts, and a table of the differences (up to
/// `max_rows`).
std::string compare_report(const CompareResult& r, const CompareOptions& o,
                           std::size_t max_rows = 50);

}  // namespace evas::study
