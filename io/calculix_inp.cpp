// CalculiX import (see calculix.h): the .inp deck (nodes, elements and sets,
// following *INCLUDE) and the solid mesh written back for ccx.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>
#include <unordered_map>

#include "io/calculix.h"
#include "io/calculix_common.h"

namespace evas {

namespace {

using calculix_detail::check_input_file;
using calculix_detail::fail_at;
using calculix_detail::kMaxGenerate;
using calculix_detail::parse_double;
using calculix_detail::parse_long;
using calculix_detail::trim;
using calculix_detail::upper;

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

}  // namespace

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
