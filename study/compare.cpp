// Study tables compared with tolerances (compare.h).
#include "study/compare.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

#include "model/types.h"
#include "plot/report_budget.h"
#include "study/case_grid.h"
#include "study/report.h"

namespace evas::study {

namespace fs = std::filesystem;

namespace {

constexpr double kNoValue = std::numeric_limits<double>::quiet_NaN();

std::vector<std::vector<std::string>> read_table(const fs::path& p) {
  std::ifstream in(p);
  if (!in) throw InputError(p.string() + ": cannot read the table");
  std::stringstream ss;
  ss << in.rdbuf();
  auto rows = parse_csv(ss.str());
  if (rows.empty()) throw InputError(p.string() + ": the table is empty (no header line)");
  return rows;
}

std::string join_words(const std::vector<std::string>& v) {
  std::string out;
  for (const auto& w : v) out += (out.empty() ? "" : ", ") + w;
  return out;
}

bool number(const std::string& s, double& x) {
  if (s.empty()) return false;
  char* end = nullptr;
  x = std::strtod(s.c_str(), &end);
  return end != s.c_str() && *end == '\0';
}

bool ignored(const std::string& col, const CompareOptions& o) {
  for (const auto& g : o.ignore)
    if (glob_match(g, col)) return true;
  return false;
}

// Row names: the key column's values, made unique by " #k" for repeats.
std::vector<std::string> row_names(const std::vector<std::vector<std::string>>& t, int key) {
  std::vector<std::string> names;
  std::map<std::string, int> seen;
  for (std::size_t r = 1; r < t.size(); ++r) {
    std::string n = static_cast<std::size_t>(key) < t[r].size() ? t[r][key] : "";
    const int k = ++seen[n];
    if (k > 1) n += " #" + std::to_string(k);
    names.push_back(n);
  }
  return names;
}

void compare_file(const fs::path& pa, const fs::path& pb, const CompareOptions& o,
                  CompareResult& res) {
  const auto ta = read_table(pa), tb = read_table(pb);
  const std::string file = pa.filename().string();
  res.files.push_back(file);
  auto key_of = [&](const std::vector<std::string>& header, const fs::path& p) {
    if (o.key.empty()) return 0;
    const auto it = std::find(header.begin(), header.end(), o.key);
    if (it == header.end()) throw InputError(p.string() + ": no column '" + o.key + "' (--key)");
    return static_cast<int>(it - header.begin());
  };
  const int ka = key_of(ta[0], pa), kb = key_of(tb[0], pb);
  const auto na = row_names(ta, ka), nb = row_names(tb, kb);
  std::map<std::string, std::size_t> rows_b;
  for (std::size_t r = 0; r < nb.size(); ++r) rows_b[nb[r]] = r + 1;
  std::map<std::string, std::size_t> cols_b;
  for (std::size_t c = 0; c < tb[0].size(); ++c) cols_b[tb[0][c]] = c;
  for (const auto& col : ta[0])
    if (!cols_b.count(col) && !ignored(col, o))
      res.problems.push_back(file + ": column '" + col + "' only in the first table");
  for (const auto& col : tb[0])
    if (std::find(ta[0].begin(), ta[0].end(), col) == ta[0].end() && !ignored(col, o))
      res.problems.push_back(file + ": column '" + col + "' only in the second table");
  std::map<std::string, bool> matched;
  for (std::size_t r = 0; r < na.size(); ++r) {
    const auto it = rows_b.find(na[r]);
    if (it == rows_b.end()) {
      res.problems.push_back(file + ": row '" + na[r] + "' only in the first table");
      continue;
    }
    matched[na[r]] = true;
    const auto& ra = ta[r + 1];
    const auto& rb = tb[it->second];
    for (std::size_t c = 0; c < ta[0].size(); ++c) {
      const std::string& col = ta[0][c];
      const auto cb = cols_b.find(col);
      if (cb == cols_b.end() || ignored(col, o)) continue;
      const std::string a = c < ra.size() ? ra[c] : "";
      const std::string b = cb->second < rb.size() ? rb[cb->second] : "";
      ++res.cells;
      double x = 0, y = 0;
      if (number(a, x) && number(b, y)) {
        if (std::isnan(x) && std::isnan(y)) continue;
        const double d = std::abs(x - y), m = std::max(std::abs(x), std::abs(y));
        if (d <= o.atol + o.rtol * m || x == y) continue;
        res.diffs.push_back({file, na[r], col, a, b, d, m > 0 ? d / m : kNoValue});
      } else if (a != b) {
        res.diffs.push_back({file, na[r], col, a, b, kNoValue, kNoValue});
      }
    }
  }
  for (const auto& n : nb)
    if (!matched.count(n))
      res.problems.push_back(file + ": row '" + n + "' only in the second table");
}

}  // namespace

CompareResult compare_tables(const std::string& a, const std::string& b, const CompareOptions& o) {
  if (!(o.rtol >= 0) || !(o.atol >= 0)) throw InputError("--rtol and --atol must be >= 0");
  CompareResult res;
  const fs::path pa(a), pb(b);
  for (const auto& p : {pa, pb})
    if (!fs::exists(p)) throw InputError(p.string() + ": no such file or folder");
  if (fs::is_directory(pa) != fs::is_directory(pb))
    throw InputError(a + ", " + b + ": compare two tables or two folders, not one of each");
  if (!fs::is_directory(pa)) {
    compare_file(pa, pb, o, res);
    return res;
  }
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(pa))
    if (e.path().extension() == ".csv" && fs::exists(pb / e.path().filename()))
      files.push_back(e.path().filename());
  std::sort(files.begin(), files.end());
  if (files.empty()) throw InputError(a + ", " + b + ": the folders hold no CSV table in common");
  for (const auto& f : files) compare_file(pa / f, pb / f, o, res);
  return res;
}

std::string compare_report(const CompareResult& r, const CompareOptions& o, std::size_t max_rows) {
  std::ostringstream os;
  os << "evas study compare: " << join_words(r.files) << "; " << r.cells << " cells compared (rtol "
     << gnum(o.rtol, 3) << ", atol " << gnum(o.atol, 3)
     << (o.ignore.empty() ? std::string() : ", ignoring " + join_words(o.ignore))
     << "): " << (r.same() ? "the tables agree" : std::to_string(r.diffs.size()) + " differ")
     << "\n";
  for (const auto& p : r.problems) os << "  " << p << "\n";
  if (!r.diffs.empty()) {
    os << "\n| file | row | column | first | second | abs | rel "
          "|\n|---|---|---|---:|---:|---:|---:|\n";
    for (std::size_t i = 0; i < r.diffs.size() && i < max_rows; ++i) {
      const CellDiff& d = r.diffs[i];
      os << "| " << d.file << " | " << md_cell(d.row, 60) << " | " << d.column << " | "
         << md_cell(d.a, 30) << " | " << md_cell(d.b, 30) << " | " << sci(d.abs, 2) << " | "
         << sci(d.rel, 2) << " |\n";
    }
    if (r.diffs.size() > max_rows)
      os << "\n(" << r.diffs.size() - max_rows << " more differences not shown)\n";
  }
  return os.str();
}

}  // namespace evas::study
