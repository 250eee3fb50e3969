// CalculiX import (see calculix.h and docs/fe-pipeline.md).
#include "io/calculix.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <unordered_map>
#include <unordered_set>

namespace evas {

namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;

std::string upper(std::string s) {
  for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

std::string trim(const std::string& s) {
  std::size_t a = 0, b = s.size();
  while (a < b && std::isspace(static_cast<unsigned char>(s[a]))) ++a;
  while (b > a && std::isspace(static_cast<unsigned char>(s[b - 1]))) --b;
  return s.substr(a, b - a);
}

[[noreturn]] void fail_at(const std::string& file, long line, const std::string& what) {
  std::ostringstream os;
  os << file;
  if (line > 0) os << ":" << line;
  os << ": " << what;
  throw InputError(os.str());
}

/// Largest accepted CalculiX file (4 GiB) and GENERATE range (entries).
constexpr std::uintmax_t kMaxFileBytes = 4ull << 30;
constexpr long kMaxGenerate = 10000000;

/// Refuses, before opening, a missing path, anything but a regular file (a
/// device or pipe such as /dev/zero never ends) and a file above the limit.
void check_input_file(const std::string& path) {
  std::error_code ec;
  const auto st = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(st)) fail_at(path, 0, "cannot open the file (no such file)");
  if (!std::filesystem::is_regular_file(st))
    fail_at(path, 0, "not a regular file (a folder, device or pipe)");
  const auto bytes = std::filesystem::file_size(path, ec);
  if (!ec && bytes > kMaxFileBytes)
    fail_at(path, 0,
            "the file is " + std::to_string(bytes) + " bytes, more than the limit of " +
                std::to_string(kMaxFileBytes) + " bytes (4 GiB)");
}

std::vector<std::string> split_commas(const std::string& s) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : s) {
    if (c == ',') {
      out.push_back(trim(cur));
      cur.clear();
    } else {
      cur += c;
    }
  }
  out.push_back(trim(cur));
  return out;
}

bool parse_long(const std::string& s, long& v) {
  if (s.empty()) return false;
  char* end = nullptr;
  v = std::strtol(s.c_str(), &end, 10);
  while (end && *end && std::isspace(static_cast<unsigned char>(*end))) ++end;
  return end && *end == '\0';
}

bool parse_double(const std::string& s, double& v) {
  if (s.empty()) return false;
  char* end = nullptr;
  v = std::strtod(s.c_str(), &end);
  while (end && *end && std::isspace(static_cast<unsigned char>(*end))) ++end;
  return end && *end == '\0' && end != s.c_str();
}

std::string directory_of(const std::string& path) {
  const std::size_t p = path.find_last_of('/');
  return p == std::string::npos ? std::string() : path.substr(0, p + 1);
}

/// Keyword line "*NAME, KEY=VALUE, FLAG": name and parameters in upper case
/// (values keep their case).
struct Keyword {
  std::string name;
  std::map<std::string, std::string> params;
};

Keyword parse_keyword(const std::string& line) {
  Keyword k;
  const std::vector<std::string> parts = split_commas(line.substr(1));
  k.name = upper(parts[0]);
  for (std::size_t i = 1; i < parts.size(); ++i) {
    if (parts[i].empty()) continue;
    const std::size_t eq = parts[i].find('=');
    if (eq == std::string::npos)
      k.params[upper(parts[i])] = "";
    else
      k.params[upper(trim(parts[i].substr(0, eq)))] = trim(parts[i].substr(eq + 1));
  }
  return k;
}

/// Number of nodes of the element types we know (0 = unknown: rely on commas).
int nodes_per_element(const std::string& type) {
  static const std::map<std::string, int> n = {
      {"C3D4", 4},    {"C3D10", 10}, {"C3D8", 8},   {"C3D8R", 8}, {"C3D8I", 8}, {"C3D20", 20},
      {"C3D20R", 20}, {"C3D6", 6},   {"C3D15", 15}, {"CPS3", 3},  {"CPS6", 6},  {"CPS4", 4},
      {"CPS8", 8},    {"S3", 3},     {"S6", 6},     {"S4", 4},    {"S8", 8},    {"B31", 2},
      {"B32", 3},     {"T3D2", 2},   {"T3D3", 3}};
  const auto it = n.find(type);
  return it == n.end() ? 0 : it->second;
}

/// Reader state for one deck (and its includes).
struct InpParser {
  InpMesh mesh;
  std::unordered_map<long, std::vector<long>> element_nodes;
  std::unordered_map<long, std::pair<std::string, long>> element_where;  // file, line
  std::set<std::string> explicit_elsets;                                 // named by *ELSET

  enum class Mode { None, Node, Element, Nset, Elset };
  Mode mode = Mode::None;
  std::string set_name;
  bool generate = false;
  std::string node_nset;
  InpElementBlock* block = nullptr;
  std::vector<std::string> pending;  // element tokens across continuation lines
  long pending_line = 0;

  void add_to_set(std::map<std::string, std::vector<long>>& sets, const std::string& name,
                  long id) {
    sets[name].push_back(id);
  }

  const std::vector<long>* find_set(const std::map<std::string, std::vector<long>>& sets,
                                    const std::string& name) const {
    const auto it = sets.find(name);
    if (it != sets.end()) return &it->second;
    for (const auto& [k, v] : sets)
      if (upper(k) == upper(name)) return &v;
    return nullptr;
  }

  void finish_element(const std::string& file) {
    if (pending.empty()) return;
    std::vector<long> vals;
    for (const std::string& t : pending) {
      if (t.empty()) continue;
      long v;
      if (!parse_long(t, v))
        fail_at(file, pending_line, "element data: '" + t + "' is not an integer");
      vals.push_back(v);
    }
    pending.clear();
    if (vals.size() < 2) fail_at(file, pending_line, "element line with no nodes");
    const int expect = nodes_per_element(block->type);
    if (expect > 0 && static_cast<int>(vals.size()) != expect + 1) {
      std::ostringstream os;
      os << "element " << vals[0] << " of type " << block->type << " has " << vals.size() - 1
         << " nodes, expected " << expect;
      fail_at(file, pending_line, os.str());
    }
    block->ids.push_back(vals[0]);
    block->nodes.emplace_back(vals.begin() + 1, vals.end());
    element_nodes[vals[0]] = block->nodes.back();
    element_where[vals[0]] = {file, pending_line};
    if (!block->elset.empty()) mesh.element_sets[block->elset].push_back(vals[0]);
  }

  void data_line(const std::string& file, long ln, const std::string& line,
                 std::vector<std::array<double, 3>>& coords) {
    const std::vector<std::string> tok = split_commas(line);
    switch (mode) {
      case Mode::None:
        return;
      case Mode::Node: {
        long id;
        if (!parse_long(tok[0], id))
          fail_at(file, ln, "node id '" + tok[0] + "' is not an integer");
        std::array<double, 3> x = {0.0, 0.0, 0.0};
        for (std::size_t a = 0; a < 3 && a + 1 < tok.size(); ++a) {
          if (tok[a + 1].empty()) continue;
          if (!parse_double(tok[a + 1], x[a]))
            fail_at(
                file, ln,
                "node " + std::to_string(id) + ": coordinate '" + tok[a + 1] + "' is not a number");
          if (!std::isfinite(x[a]))
            fail_at(
                file, ln,
                "node " + std::to_string(id) + ": coordinate '" + tok[a + 1] + "' is not finite");
        }
        if (mesh.index.count(id))
          fail_at(file, ln, "node " + std::to_string(id) + " defined twice");
        mesh.index[id] = static_cast<int>(mesh.node_ids.size());
        mesh.node_ids.push_back(id);
        coords.push_back(x);
        if (!node_nset.empty()) add_to_set(mesh.node_sets, node_nset, id);
        return;
      }
      case Mode::Element: {
        if (pending.empty()) pending_line = ln;
        const bool continues = !trim(line).empty() && trim(line).back() == ',';
        for (const std::string& t : tok)
          if (!t.empty()) pending.push_back(t);
        const int expect = nodes_per_element(block->type);
        const bool short_of_known = expect > 0 && static_cast<int>(pending.size()) < expect + 1;
        if (!continues && !short_of_known) finish_element(file);
        if (continues && expect > 0 && static_cast<int>(pending.size()) >= expect + 1)
          finish_element(file);
        return;
      }
      case Mode::Nset:
      case Mode::Elset: {
        auto& sets = mode == Mode::Nset ? mesh.node_sets : mesh.element_sets;
        std::vector<long>& dst = sets[set_name];
        if (generate) {
          long v[3] = {0, 0, 1};
          int n = 0;
          for (const std::string& t : tok) {
            if (t.empty()) continue;
            if (n >= 3 || !parse_long(t, v[n]))
              fail_at(file, ln, "GENERATE needs 'first, last[, step]' integers");
            ++n;
          }
          if (n < 2 || v[2] <= 0 || v[1] < v[0])
            fail_at(file, ln, "GENERATE needs 'first, last[, step]' with first <= last, step > 0");
          // v[1] >= v[0], v[2] > 0; in long double, so that no range overflows
          const long double span = static_cast<long double>(v[1]) - v[0];
          const long double want = span / v[2] + 1.0L + static_cast<long double>(dst.size());
          if (want > kMaxGenerate) {
            char buf[40];
            std::snprintf(buf, sizeof buf, "%.4Lg", span / v[2] + 1.0L);
            fail_at(file, ln,
                    "GENERATE " + std::to_string(v[0]) + ", " + std::to_string(v[1]) + ", " +
                        std::to_string(v[2]) + " gives " + buf +
                        " entries, more than the limit of " + std::to_string(kMaxGenerate) +
                        " per set");
          }
          const long count = static_cast<long>(span / v[2]) + 1;
          for (long k = 0; k < count; ++k) dst.push_back(v[0] + k * v[2]);
          return;
        }
        for (const std::string& t : tok) {
          if (t.empty()) continue;
          long id;
          if (parse_long(t, id)) {
            dst.push_back(id);
          } else {
            const std::vector<long>* other = find_set(sets, t);
            if (!other || other == &dst)
              fail_at(file, ln,
                      "set '" + set_name + "' refers to unknown set or value '" + t + "'");
            const std::vector<long> copy = *other;
            dst.insert(dst.end(), copy.begin(), copy.end());
          }
        }
        return;
      }
    }
  }

  void read_file(const std::string& path, std::vector<std::array<double, 3>>& coords, int depth) {
    if (depth > 20) fail_at(path, 0, "*INCLUDE nested too deeply");
    check_input_file(path);
    std::ifstream in(path);
    if (!in) fail_at(path, 0, "cannot open the file");
    std::string line;
    long ln = 0;
    while (std::getline(in, line)) {
      ++ln;
      if (!line.empty() && line.back() == '\r') line.pop_back();
      const std::string t = trim(line);
      if (t.empty() || t.rfind("**", 0) == 0) continue;
      if (t[0] == '*') {
        if (mode == Mode::Element && !pending.empty()) finish_element(path);
        const Keyword k = parse_keyword(t);
        mode = Mode::None;
        generate = k.params.count("GENERATE") > 0;
        if (k.name == "INCLUDE") {
          const auto it = k.params.find("INPUT");
          if (it == k.params.end() || it->second.empty())
            fail_at(path, ln, "*INCLUDE needs INPUT=");
          std::string inc = it->second;
          if (!inc.empty() && inc.front() == '"') inc = inc.substr(1, inc.size() - 2);
          if (inc[0] != '/') inc = directory_of(path) + inc;
          read_file(inc, coords, depth + 1);
          mode = Mode::None;
        } else if (k.name == "NODE") {
          mode = Mode::Node;
          const auto it = k.params.find("NSET");
          node_nset = it == k.params.end() ? "" : it->second;
        } else if (k.name == "ELEMENT") {
          const auto it = k.params.find("TYPE");
          if (it == k.params.end() || it->second.empty()) fail_at(path, ln, "*ELEMENT needs TYPE=");
          mesh.elements.push_back(InpElementBlock{});
          block = &mesh.elements.back();
          block->type = upper(it->second);
          const auto es = k.params.find("ELSET");
          block->elset = es == k.params.end() ? "" : es->second;
          mode = Mode::Element;
        } else if (k.name == "NSET" || k.name == "ELSET") {
          const auto it = k.params.find(k.name);
          if (it == k.params.end() || it->second.empty())
            fail_at(path, ln, "*" + k.name + " needs " + k.name + "=");
          set_name = it->second;
          mode = k.name == "NSET" ? Mode::Nset : Mode::Elset;
          if (mode == Mode::Elset) explicit_elsets.insert(set_name);
          (mode == Mode::Nset ? mesh.node_sets : mesh.element_sets)[set_name];
        }
        continue;
      }
      data_line(path, ln, t, coords);
    }
    if (mode == Mode::Element && !pending.empty()) finish_element(path);
  }
};

void sort_unique(std::vector<long>& v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

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

UnitSystem unit_system(const std::string& name) {
  const std::string n = upper(trim(name));
  if (n == "SI" || n == "M-KG-S" || n == "M-KG-S-N") return {1.0, 1.0};
  if (n == "MM-T-S" || n == "MM-T-S-N" || n == "MM-T-S-N-MPA") return {1e-3, 1e3};
  if (n == "MM-KG-S") return {1e-3, 1.0};
  throw InputError("unknown unit system '" + name + "' (known: SI, m-kg-s, mm-t-s, mm-kg-s)");
}

int InpMesh::index_of(long id) const {
  const auto it = index.find(id);
  return it == index.end() ? -1 : it->second;
}

bool is_solid_element(const std::string& type) { return upper(type).rfind("C3D", 0) == 0; }

InpMesh read_inp(const std::string& path) {
  InpParser p;
  std::vector<std::array<double, 3>> coords;
  p.read_file(path, coords, 0);
  InpMesh& m = p.mesh;
  m.s.resize(static_cast<long>(coords.size()), 3);
  for (std::size_t i = 0; i < coords.size(); ++i)
    for (int a = 0; a < 3; ++a) m.s(static_cast<long>(i), a) = coords[i][a];
  if (m.node_ids.empty()) fail_at(path, 0, "no *NODE data");
  for (auto& [name, ids] : m.element_sets) sort_unique(ids);
  for (const std::string& es : p.explicit_elsets) {
    if (p.find_set(m.node_sets, es)) continue;
    std::vector<long> nodes;
    for (long e : m.element_sets[es]) {
      const auto it = p.element_nodes.find(e);
      if (it == p.element_nodes.end())
        fail_at(path, 0,
                "*ELSET " + es + " names element " + std::to_string(e) + " that is not defined");
      nodes.insert(nodes.end(), it->second.begin(), it->second.end());
    }
    m.node_sets[es] = nodes;
  }
  for (auto& [name, ids] : m.node_sets) {
    sort_unique(ids);
    for (long id : ids)
      if (!m.index.count(id))
        fail_at(path, 0,
                "node set " + name + " names node " + std::to_string(id) + " that is not defined");
  }
  for (const InpElementBlock& b : m.elements)
    for (std::size_t e = 0; e < b.ids.size(); ++e)
      for (long n : b.nodes[e])
        if (!m.index.count(n)) {
          const auto w = p.element_where.find(b.ids[e]);
          fail_at(w != p.element_where.end() ? w->second.first : path,
                  w != p.element_where.end() ? w->second.second : 0,
                  "element " + std::to_string(b.ids[e]) + " uses node " + std::to_string(n) +
                      " that is not defined");
        }
  return p.mesh;
}

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

ModalBody body_from_ccx_modes(const std::string& name, const FeModel& fe, const FrdModes& modes,
                              const DatModal& dat, const BuildOptions& opt) {
  auto fail = [&](const std::string& what) { throw InputError("body '" + name + "': " + what); };
  const int N = static_cast<int>(fe.node_ids.size());
  if (fe.s.rows() != N || fe.Ms.rows() != N || fe.Ms.cols() != N)
    fail("FE model sizes disagree (node ids, coordinates, Ms)");
  const int m = static_cast<int>(modes.shapes.cols());
  // Rows of the FE nodes in the .frd.
  std::unordered_map<long, int> frd_row;
  for (std::size_t i = 0; i < modes.node_ids.size(); ++i)
    frd_row[modes.node_ids[i]] = static_cast<int>(i);
  Mat X(3 * N, m);
  for (int i = 0; i < N; ++i) {
    const auto it = frd_row.find(fe.node_ids[i]);
    if (it == frd_row.end()) fail("node " + std::to_string(fe.node_ids[i]) + " has no .frd result");
    X.middleRows(3 * i, 3) = modes.shapes.middleRows(3 * it->second, 3);
  }
  Vec lam(m);
  for (int k = 0; k < m; ++k) {
    const int mn = modes.mode_numbers[k];
    if (mn < 1 || mn > dat.eigenvalues.size())
      fail("mode " + std::to_string(mn) + " of the .frd has no eigenvalue in the .dat");
    lam[k] = dat.eigenvalues[mn - 1];
  }
  const double lmax = lam.cwiseAbs().maxCoeff();
  std::vector<int> order(m);
  for (int k = 0; k < m; ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](int a, int b) { return lam[a] < lam[b]; });
  int n_rigid = 0;
  while (n_rigid < m && n_rigid < 6 && std::abs(lam[order[n_rigid]]) < 1e-6 * lmax) ++n_rigid;
  const Mat R = rigid_basis(fe.s, fe.Ms);
  const double lambda_cut = opt.max_frequency > 0.0 ? std::pow(kTwoPi * opt.max_frequency, 2) : 0.0;
  std::vector<int> keep;
  for (int j = n_rigid; j < m; ++j) {
    const int k = order[j];
    if (lam[k] <= 0.0) fail("elastic mode " + std::to_string(k + 1) + " has eigenvalue <= 0");
    if (lambda_cut > 0.0 && lam[k] > lambda_cut) continue;
    if (opt.num_elastic > 0 && static_cast<int>(keep.size()) >= opt.num_elastic) break;
    keep.push_back(k);
  }
  if (keep.empty()) fail("no elastic modes in the .frd within the requested count / cut-off");
  if (opt.num_elastic > static_cast<int>(keep.size()) && lambda_cut == 0.0)
    fail(std::to_string(opt.num_elastic) + " elastic modes asked for, but the .frd holds only " +
         std::to_string(keep.size()) + " (run ccx with more *FREQUENCY modes, or ask for fewer)");
  Mat elastic(3 * N, static_cast<Eigen::Index>(keep.size()));
  Vec lam_keep(static_cast<Eigen::Index>(keep.size()));
  for (std::size_t j = 0; j < keep.size(); ++j) {
    Vec phi = X.col(keep[j]);
    for (int pass = 0; pass < 2; ++pass) phi -= R * (R.transpose() * apply_mass(fe.Ms, phi));
    const double nrm2 = phi.dot(apply_mass(fe.Ms, phi).col(0));
    if (!(nrm2 > 0.0)) fail("mode " + std::to_string(keep[j] + 1) + " is a rigid-body motion");
    elastic.col(j) = phi / std::sqrt(nrm2);
    lam_keep[j] = lam[keep[j]];
  }
  // The .frd holds about 6 digits, so the elastic shapes are mass-orthogonal to
  // only ~1e-7: orthogonalise them (Gram-Schmidt in frequency order, twice) so
  // that the body meets the modal contract (solver/modal_contract.h) to round-off.
  for (int pass = 0; pass < 2; ++pass)
    for (Eigen::Index j = 0; j < elastic.cols(); ++j) {
      Vec phi = elastic.col(j);
      if (j > 0) {
        const Vec Mphi = apply_mass(fe.Ms, phi);
        phi -= elastic.leftCols(j) * (elastic.leftCols(j).transpose() * Mphi);
      }
      const double nrm2 = phi.dot(apply_mass(fe.Ms, phi).col(0));
      if (!(nrm2 > 0.0)) fail("mode " + std::to_string(keep[j] + 1) + " repeats another mode");
      elastic.col(j) = phi / std::sqrt(nrm2);
    }
  return assemble_modal_body(name, fe, elastic, lam_keep, opt);
}

void write_ccx_mesh(const std::string& path, const InpMesh& mesh) {
  std::ofstream out(path);
  if (!out) fail_at(path, 0, "cannot write the file");
  std::vector<char> used(mesh.node_ids.size(), 0);
  std::size_t n_solid = 0;
  for (const InpElementBlock& b : mesh.elements) {
    if (!is_solid_element(b.type)) continue;
    n_solid += b.ids.size();
    for (const auto& el : b.nodes)
      for (long n : el) used[mesh.index_of(n)] = 1;
  }
  if (n_solid == 0) fail_at(path, 0, "the mesh has no solid (C3D*) elements");
  out << "** evas: solid mesh for ccx (surface elements dropped)\n*NODE\n";
  char buf[160];
  for (std::size_t i = 0; i < mesh.node_ids.size(); ++i) {
    if (!used[i]) continue;
    const long r = static_cast<long>(i);
    std::snprintf(buf, sizeof buf, "%ld, %.13g, %.13g, %.13g\n", mesh.node_ids[i], mesh.s(r, 0),
                  mesh.s(r, 1), mesh.s(r, 2));
    out << buf;
  }
  for (const InpElementBlock& b : mesh.elements) {
    if (!is_solid_element(b.type)) continue;
    out << "*ELEMENT, TYPE=" << b.type << ", ELSET=EALL\n";
    for (std::size_t e = 0; e < b.ids.size(); ++e) {
      out << b.ids[e];
      int on_line = 1;
      for (long n : b.nodes[e]) {
        if (on_line == 16) {
          out << ",\n";
          on_line = 0;
        } else {
          out << ", ";
        }
        out << n;
        ++on_line;
      }
      out << "\n";
    }
  }
  for (const auto& [name, ids] : mesh.node_sets) {
    std::vector<long> kept;
    for (long id : ids)
      if (used[mesh.index_of(id)]) kept.push_back(id);
    if (kept.empty()) continue;
    out << "*NSET, NSET=" << name << "\n";
    for (std::size_t k = 0; k < kept.size(); ++k)
      out << kept[k] << (k + 1 == kept.size() || k % 10 == 9 ? "\n" : ", ");
  }
  if (!out) fail_at(path, 0, "write failed");
}

}  // namespace evas
