// CalculiX import (see calculix.h): results, the mode shapes of a .frd file
// and the modal tables (eigenvalues, participation factors, effective masses)
// of a .dat file.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>
#include <unordered_map>

#include "io/calculix.h"
#include "io/calculix_common.h"

namespace evas {

namespace {

using calculix_detail::check_input_file;
using calculix_detail::fail_at;
using calculix_detail::parse_double;
using calculix_detail::parse_long;
using calculix_detail::trim;
using calculix_detail::upper;

}  // namespace

bool parse_frd_node_line(const std::string& line, long& node, std::vector<double>& values) {
  if (line.size() < 13 || line.compare(0, 3, " -1") != 0) return false;
  if (!parse_long(trim(line.substr(3, 10)), node)) return false;
  values.clear();
  std::size_t end = line.size();
  while (end > 13 && std::isspace(static_cast<unsigned char>(line[end - 1]))) --end;
  for (std::size_t pos = 13; pos < end; pos += 12) {
    double v;
    if (!parse_double(trim(line.substr(pos, std::min<std::size_t>(12, end - pos))), v))
      return false;
    values.push_back(v);
  }
  return true;
}

FrdModes read_frd_modes(const std::string& path) {
  check_input_file(path);
  std::ifstream in(path);
  if (!in) fail_at(path, 0, "cannot open the file");
  FrdModes fm;
  std::vector<std::vector<double>> cols;  // one 3N column per DISP block
  std::unordered_map<long, int> row;
  std::string line;
  long ln = 0;
  double pending_freq = 0.0;
  int pending_mode = 0;
  enum class State { Outside, Disp, Skip } st = State::Outside;
  std::vector<double> vals;
  std::vector<char> filled;
  while (std::getline(in, line)) {
    ++ln;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (st == State::Outside) {
      if (line.compare(0, 6, "  100C") == 0) {
        if (line.size() < 24 || !parse_double(trim(line.substr(12, 12)), pending_freq))
          fail_at(path, ln, "100C record: cannot read the step value in columns 13-24");
        long mn = 0;
        pending_mode = (line.size() >= 63 && parse_long(trim(line.substr(58, 5)), mn))
                           ? static_cast<int>(mn)
                           : static_cast<int>(cols.size()) + 1;
      } else if (line.compare(0, 3, " -4") == 0) {
        std::istringstream is(line.substr(3));
        std::string name;
        is >> name;
        if (upper(name) == "DISP") {
          st = State::Disp;
          cols.emplace_back(fm.node_ids.empty() ? 0 : 3 * fm.node_ids.size(), 0.0);
          filled.assign(fm.node_ids.size(), 0);
          fm.frequencies.push_back(pending_freq);
          fm.mode_numbers.push_back(pending_mode);
        } else {
          st = State::Skip;
        }
      }
      continue;
    }
    if (line.compare(0, 3, " -3") == 0) {
      if (st == State::Disp && cols.size() > 1)
        for (std::size_t i = 0; i < filled.size(); ++i)
          if (!filled[i])
            fail_at(path, ln,
                    "DISP block " + std::to_string(cols.size()) + " lacks node " +
                        std::to_string(fm.node_ids[i]));
      st = State::Outside;
      continue;
    }
    if (st != State::Disp || line.compare(0, 3, " -1") != 0) continue;
    long node;
    if (!parse_frd_node_line(line, node, vals) || vals.size() < 3)
      fail_at(path, ln, "DISP record: expected ' -1', node (I10) and 3 values (E12.5)");
    for (int a = 0; a < 3; ++a)
      if (!std::isfinite(vals[a]))
        fail_at(path, ln, "DISP record of node " + std::to_string(node) + ": value not finite");
    std::vector<double>& col = cols.back();
    if (cols.size() == 1) {
      if (row.count(node)) fail_at(path, ln, "node " + std::to_string(node) + " listed twice");
      row[node] = static_cast<int>(fm.node_ids.size());
      fm.node_ids.push_back(node);
      col.insert(col.end(), vals.begin(), vals.begin() + 3);
    } else {
      const auto it = row.find(node);
      if (it == row.end())
        fail_at(path, ln, "node " + std::to_string(node) + " is not in the first DISP block");
      for (int a = 0; a < 3; ++a) col[3 * it->second + a] = vals[a];
      filled[it->second] = 1;
    }
  }
  if (cols.empty()) fail_at(path, 0, "no DISP blocks (was *NODE FILE with U requested?)");
  fm.shapes.resize(static_cast<long>(3 * fm.node_ids.size()), static_cast<long>(cols.size()));
  for (std::size_t k = 0; k < cols.size(); ++k)
    fm.shapes.col(static_cast<long>(k)) = Eigen::Map<const Vec>(cols[k].data(), cols[k].size());
  return fm;
}

DatModal read_dat_modal(const std::string& path) {
  check_input_file(path);
  std::ifstream in(path);
  if (!in) fail_at(path, 0, "cannot open the file");
  std::vector<std::string> lines;
  std::string line;
  while (std::getline(in, line)) lines.push_back(line);
  auto squeeze = [](const std::string& s) {
    std::string o;
    for (char c : s)
      if (!std::isspace(static_cast<unsigned char>(c))) o += c;
    return o;
  };
  auto numbers = [](const std::string& s, std::vector<double>& v) {
    std::istringstream is(s);
    v.clear();
    std::string tok;
    while (is >> tok) {
      double x;
      if (!parse_double(tok, x)) return false;
      v.push_back(x);
    }
    return !v.empty();
  };
  // Rows "mode v1 .. vk" after the title at line t; returns rows (mode, values).
  auto table = [&](std::size_t t, std::size_t k) {
    std::vector<std::vector<double>> rows;
    std::vector<double> v;
    std::size_t i = t + 1;
    while (i < lines.size() && !(numbers(lines[i], v) && v.size() == k + 1)) {
      if (squeeze(lines[i]).find("TOTAL") == 0 || squeeze(lines[i]).find("EIGEN") == 0) break;
      ++i;
    }
    for (; i < lines.size() && numbers(lines[i], v) && v.size() == k + 1; ++i) rows.push_back(v);
    return rows;
  };
  DatModal d;
  d.total.setZero();
  bool got_eig = false, got_part = false, got_eff = false;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string s = squeeze(lines[i]);
    if (!got_eig && s == "EIGENVALUEOUTPUT") {
      const auto rows = table(i, 4);
      if (rows.empty()) fail_at(path, static_cast<long>(i + 1), "eigenvalue table is empty");
      d.eigenvalues.resize(static_cast<long>(rows.size()));
      for (std::size_t r = 0; r < rows.size(); ++r) {
        if (rows[r][0] != static_cast<double>(r + 1))
          fail_at(path, static_cast<long>(i + 1),
                  "eigenvalue table: modes are not numbered 1, 2, ...");
        if (!std::isfinite(rows[r][1]))
          fail_at(path, static_cast<long>(i + 1),
                  "eigenvalue table: the eigenvalue of mode " + std::to_string(r + 1) +
                      " is not finite");
        d.eigenvalues[static_cast<long>(r)] = rows[r][1];
      }
      got_eig = true;
    } else if ((!got_part && s == "PARTICIPATIONFACTORS") ||
               (!got_eff && s == "EFFECTIVEMODALMASS")) {
      const auto rows = table(i, 6);
      Mat m(static_cast<long>(rows.size()), 6);
      for (std::size_t r = 0; r < rows.size(); ++r)
        for (int c = 0; c < 6; ++c) m(static_cast<long>(r), c) = rows[r][c + 1];
      if (s == "PARTICIPATIONFACTORS") {
        d.participation = m;
        got_part = true;
      } else {
        d.effective_mass = m;
        got_eff = true;
      }
    } else if (!d.has_total && s == "TOTALEFFECTIVEMASS") {
      std::vector<double> v;
      for (std::size_t j = i + 1; j < lines.size() && j < i + 8; ++j)
        if (numbers(lines[j], v) && v.size() == 6) {
          for (int c = 0; c < 6; ++c) d.total[c] = v[c];
          d.has_total = true;
          break;
        }
      if (!d.has_total)
        fail_at(path, static_cast<long>(i + 1), "total effective mass: no row of 6 numbers");
    }
  }
  if (!got_eig)
    fail_at(path, 0, "no 'E I G E N V A L U E   O U T P U T' table (not a *FREQUENCY run?)");
  return d;
}

}  // namespace evas
