// CalculiX import (see calculix.h): K and the scalar mass Ms from the matrix
// storage of *FREQUENCY, SOLVER=MATRIXSTORAGE (job.sti, job.mas, job.dof).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <unordered_map>

#include "io/calculix.h"
#include "io/calculix_common.h"

namespace evas {

namespace {

using calculix_detail::check_input_file;
using calculix_detail::fail_at;
using calculix_detail::parse_long;
using calculix_detail::trim;

/// Whole file as a string; InputError naming the file if it cannot be read.
std::string slurp(const std::string& path) {
  check_input_file(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) fail_at(path, 0, "cannot open the file");
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

struct MatrixEntry {
  long row, col;
  double value;
};

/// "row col value" lines (1-based equation numbers).
std::vector<MatrixEntry> read_matrix_file(const std::string& path, long neq) {
  const std::string text = slurp(path);
  std::vector<MatrixEntry> out;
  out.reserve(text.size() / 30);
  const char* p = text.c_str();
  long ln = 0;
  while (*p) {
    ++ln;
    const char* eol = std::strchr(p, '\n');
    const std::string line = eol ? std::string(p, eol) : std::string(p);
    p = eol ? eol + 1 : p + line.size();
    const char* q = line.c_str();
    while (*q && std::isspace(static_cast<unsigned char>(*q))) ++q;
    if (!*q) continue;
    char* e1 = nullptr;
    char* e2 = nullptr;
    char* e3 = nullptr;
    const long r = std::strtol(q, &e1, 10);
    const long c = std::strtol(e1, &e2, 10);
    const double v = std::strtod(e2, &e3);
    if (e1 == q || e2 == e1 || e3 == e2)
      fail_at(path, ln, "expected 'row column value', got '" + line + "'");
    if (r < 1 || c < 1 || r > neq || c > neq) {
      std::ostringstream os;
      os << "equation number out of range 1.." << neq << " (from the .dof file): '" << line << "'";
      fail_at(path, ln, os.str());
    }
    if (!std::isfinite(v)) fail_at(path, ln, "value is not finite");
    out.push_back({r - 1, c - 1, v});
  }
  return out;
}

}  // namespace

FeModel read_matrix_storage(const InpMesh& mesh, const std::string& sti, const std::string& mas,
                            const std::string& dof, const UnitSystem& units) {
  // --- equation -> (node, direction) --------------------------------------------
  std::vector<std::pair<long, int>> eqs;
  {
    check_input_file(dof);
    std::ifstream in(dof);
    if (!in) fail_at(dof, 0, "cannot open the file");
    std::string line;
    long ln = 0;
    while (std::getline(in, line)) {
      ++ln;
      const std::string t = trim(line);
      if (t.empty()) continue;
      const std::size_t dot = t.find('.');
      long node, dir;
      if (dot == std::string::npos || !parse_long(t.substr(0, dot), node) ||
          !parse_long(t.substr(dot + 1), dir))
        fail_at(dof, ln, "expected 'node.direction', got '" + t + "'");
      if (dir < 1 || dir > 3)
        fail_at(dof, ln,
                "direction " + std::to_string(dir) + " of node " + std::to_string(node) +
                    ": only translations 1-3 are supported (no beams/shells)");
      if (mesh.index_of(node) < 0)
        fail_at(dof, ln, "node " + std::to_string(node) + " is not in the .inp mesh");
      eqs.emplace_back(node, static_cast<int>(dir));
    }
  }
  if (eqs.empty()) fail_at(dof, 0, "no equations");
  // Nodes in mesh order that carry DOF.
  std::vector<int> dirs_seen(mesh.node_ids.size(), 0);
  for (const auto& [node, dir] : eqs) {
    int& bits = dirs_seen[mesh.index_of(node)];
    if (bits & (1 << dir))
      fail_at(
          dof, 0,
          "node " + std::to_string(node) + " direction " + std::to_string(dir) + " appears twice");
    bits |= 1 << dir;
  }
  FeModel fe;
  std::vector<int> row_of(mesh.node_ids.size(), -1);
  for (std::size_t i = 0; i < mesh.node_ids.size(); ++i) {
    if (!dirs_seen[i]) continue;
    if (dirs_seen[i] != 0xE)
      fail_at(
          dof, 0,
          "node " + std::to_string(mesh.node_ids[i]) + " does not carry all three translations");
    row_of[i] = static_cast<int>(fe.node_ids.size());
    fe.node_ids.push_back(mesh.node_ids[i]);
  }
  const int N = static_cast<int>(fe.node_ids.size());
  fe.s.resize(N, 3);
  for (std::size_t i = 0; i < mesh.node_ids.size(); ++i)
    if (row_of[i] >= 0) fe.s.row(row_of[i]) = units.length * mesh.s.row(static_cast<long>(i));
  std::vector<int> eq_node(eqs.size()), eq_dir(eqs.size());
  for (std::size_t k = 0; k < eqs.size(); ++k) {
    eq_node[k] = row_of[mesh.index_of(eqs[k].first)];
    eq_dir[k] = eqs[k].second - 1;
  }
  const long neq = static_cast<long>(eqs.size());

  // --- stiffness -------------------------------------------------------------------
  if (!sti.empty()) {
    const std::vector<MatrixEntry> ke = read_matrix_file(sti, neq);
    bool lower = false, upper_t = false;
    for (const MatrixEntry& e : ke) {
      lower = lower || e.row > e.col;
      upper_t = upper_t || e.row < e.col;
    }
    const bool mirror = !(lower && upper_t);
    std::vector<Triplet> t;
    t.reserve(ke.size() * 2);
    for (const MatrixEntry& e : ke) {
      const int r = 3 * eq_node[e.row] + eq_dir[e.row];
      const int c = 3 * eq_node[e.col] + eq_dir[e.col];
      const double v = units.mass * e.value;
      t.emplace_back(r, c, v);
      if (mirror && e.row != e.col) t.emplace_back(c, r, v);
    }
    fe.K.resize(3 * N, 3 * N);
    fe.K.setFromTriplets(t.begin(), t.end());
    fe.K.makeCompressed();
  }

  // --- mass: M = Ms (x) I3 -------------------------------------------------------------
  {
    const std::vector<MatrixEntry> me = read_matrix_file(mas, neq);
    bool lower = false, upper_t = false;
    double maxdiag = 0.0;
    for (const MatrixEntry& e : me) {
      lower = lower || e.row > e.col;
      upper_t = upper_t || e.row < e.col;
      if (e.row == e.col) maxdiag = std::max(maxdiag, std::abs(e.value));
    }
    if (!(maxdiag > 0.0)) fail_at(mas, 0, "the mass matrix has no positive diagonal entry");
    const double tol = 1e-9 * maxdiag;
    struct PairVals {
      double v[3] = {0.0, 0.0, 0.0};
      int seen = 0;
    };
    std::unordered_map<std::uint64_t, PairVals> pairs;
    pairs.reserve(me.size() / 3 + 16);
    long ln = 0;
    for (const MatrixEntry& e : me) {
      ++ln;
      if (lower && upper_t && e.row > e.col) continue;  // full matrix: upper half is enough
      int i = eq_node[e.row], j = eq_node[e.col];
      const int a = eq_dir[e.row], b = eq_dir[e.col];
      if (a != b) {
        if (std::abs(e.value) > tol) {
          std::ostringstream os;
          os << "mass couples direction " << a + 1 << " of node " << fe.node_ids[i]
             << " with direction " << b + 1 << " of node " << fe.node_ids[j] << " (" << e.value
             << "): M is not Ms (x) I3";
          fail_at(mas, ln, os.str());
        }
        continue;
      }
      if (i > j) std::swap(i, j);
      PairVals& pv = pairs[(static_cast<std::uint64_t>(i) << 32) | static_cast<std::uint32_t>(j)];
      pv.v[a] += e.value;
      pv.seen |= 1 << a;
    }
    std::vector<Triplet> t;
    t.reserve(pairs.size() * 2);
    for (const auto& [key, pv] : pairs) {
      const int i = static_cast<int>(key >> 32), j = static_cast<int>(key & 0xffffffffu);
      const double d = std::max(std::abs(pv.v[1] - pv.v[0]), std::abs(pv.v[2] - pv.v[0]));
      if (d > tol) {
        std::ostringstream os;
        os << "mass entry between nodes " << fe.node_ids[i] << " and " << fe.node_ids[j]
           << " differs between directions (" << pv.v[0] << ", " << pv.v[1] << ", " << pv.v[2]
           << "): M is not Ms (x) I3";
        fail_at(mas, 0, os.str());
      }
      const double v = units.mass * pv.v[0];
      if (v == 0.0) continue;
      t.emplace_back(i, j, v);
      if (i != j) t.emplace_back(j, i, v);
    }
    fe.Ms.resize(N, N);
    fe.Ms.setFromTriplets(t.begin(), t.end());
    fe.Ms.makeCompressed();
  }

  // --- node sets ---------------------------------------------------------------------------
  for (const auto& [name, ids] : mesh.node_sets) {
    std::vector<long> kept;
    for (long id : ids) {
      const int r = mesh.index_of(id);
      if (r >= 0 && row_of[r] >= 0) kept.push_back(id);
    }
    if (!kept.empty()) fe.node_sets[name] = kept;
  }
  return fe;
}

}  // namespace evas
