// Areas and outward normals of the mesh's surface sets (io/calculix.h,
// mesh_surfaces; docs/theory.md section 8.3).
//
// A surface set is an element set of 2-D elements (gmsh writes a physical
// surface as CPS3/CPS6 triangles or CPS4/CPS8 quadrilaterals). Each face's
// area vector is 1/2 (b - a) x (c - a) for a triangle with corners a, b, c and
// 1/2 (c - a) x (d - b) for a quadrilateral (exact for flat faces); it is
// turned outward, away from the centroid of the one solid element that has the
// face. The area goes to the face's nodes as a tributary share: a 3- or
// 4-node face splits it equally among its corners; a 6-node triangle, cut into
// its four sub-triangles, gives each corner 1/12 and each mid-side node 1/4; an
// 8-node quadrilateral 1/12 per corner and 1/6 per mid-side node. A node's
// normal is the area-weighted mean of its faces' normals (nodes on an edge
// between two faces get the mean direction).
#include <algorithm>
#include <array>
#include <map>
#include <unordered_map>

#include "io/calculix.h"

namespace evas {

namespace {

using Key = std::array<long, 4>;  // sorted corner ids, -1 padded

Key key_of(const long* corners, int n) {
  Key k = {-1, -1, -1, -1};
  std::copy(corners, corners + n, k.begin());
  std::sort(k.begin(), k.begin() + n);
  return k;
}

bool is_surface_element(const std::string& type, std::size_t nodes) {
  const bool shape = nodes == 3 || nodes == 6 || nodes == 4 || nodes == 8;
  for (const char* p : {"CPS", "CPE", "M3D", "STRI", "S"})
    if (type.rfind(p, 0) == 0) return shape;
  return false;
}

// Faces (corner indices) of the solid elements evas meshes with.
const std::vector<std::vector<int>>& solid_faces(std::size_t nodes) {
  static const std::vector<std::vector<int>> tet = {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};
  static const std::vector<std::vector<int>> hex = {{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                                    {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  static const std::vector<std::vector<int>> wedge = {
      {0, 1, 2}, {3, 4, 5}, {0, 1, 4, 3}, {1, 2, 5, 4}, {2, 0, 3, 5}};
  static const std::vector<std::vector<int>> none;
  if (nodes == 4 || nodes == 10) return tet;
  if (nodes == 8 || nodes == 20) return hex;
  if (nodes == 6 || nodes == 15) return wedge;
  return none;
}

int corner_count(std::size_t nodes) { return nodes == 3 || nodes == 6 ? 3 : 4; }

struct Face {
  const std::vector<long>* nodes;
  long element;
  Key key;
};

}  // namespace

std::map<std::string, SurfaceSet> mesh_surfaces(const InpMesh& mesh, const UnitSystem& units,
                                                const std::string& path) {
  // the 2-D elements by id
  std::unordered_map<long, const std::vector<long>*> faces_by_id;
  for (const InpElementBlock& b : mesh.elements)
    for (std::size_t e = 0; e < b.ids.size(); ++e)
      if (is_surface_element(b.type, b.nodes[e].size())) faces_by_id[b.ids[e]] = &b.nodes[e];
  // the sets made of 2-D elements only
  std::map<std::string, std::vector<Face>> sets;
  std::map<Key, std::pair<Vec3, int>> behind;  // solid centroid, count
  for (const auto& [name, ids] : mesh.element_sets) {
    if (ids.empty()) continue;
    std::vector<Face> faces;
    for (long id : ids) {
      const auto it = faces_by_id.find(id);
      if (it == faces_by_id.end()) break;
      faces.push_back(
          {it->second, id, key_of(it->second->data(), corner_count(it->second->size()))});
    }
    if (faces.size() != ids.size()) continue;  // not a surface set
    for (const Face& f : faces) behind.emplace(f.key, std::make_pair(Vec3::Zero(), 0));
    sets.emplace(name, std::move(faces));
  }
  if (sets.empty()) return {};
  auto pos = [&](long id) -> Vec3 {
    const int r = mesh.index_of(id);
    if (r < 0)
      throw InputError(path + ": element node " + std::to_string(id) +
                       " is not a node of the mesh");
    return mesh.s.row(r).transpose();
  };
  // the solid elements behind the faces
  for (const InpElementBlock& b : mesh.elements) {
    if (!is_solid_element(b.type)) continue;
    for (const auto& el : b.nodes) {
      const auto& fs = solid_faces(el.size());
      if (fs.empty()) continue;
      for (const auto& f : fs) {
        long corners[4];
        for (std::size_t k = 0; k < f.size(); ++k) corners[k] = el[static_cast<std::size_t>(f[k])];
        const auto it = behind.find(key_of(corners, static_cast<int>(f.size())));
        if (it == behind.end()) continue;
        Vec3 c = Vec3::Zero();
        const int nc = el.size() == 4 || el.size() == 10   ? 4
                       : el.size() == 6 || el.size() == 15 ? 6
                                                           : 8;
        for (int k = 0; k < nc; ++k) c += pos(el[static_cast<std::size_t>(k)]);
        it->second.first = c / nc;
        ++it->second.second;
      }
    }
  }
  const double L = units.length;
  std::map<std::string, SurfaceSet> out;
  for (const auto& [name, faces] : sets) {
    std::map<long, std::pair<double, Vec3>> acc;  // node -> area, sum of area * normal
    for (const Face& f : faces) {
      const std::vector<long>& n = *f.nodes;
      const int nc = corner_count(n.size());
      const auto& [centroid, count] = behind.at(f.key);
      if (count != 1)
        throw InputError(path + ": element " + std::to_string(f.element) + " of surface set '" +
                         name + "' " +
                         (count == 0 ? "is a face of no solid element"
                                     : "lies between two solid elements (inside the body)") +
                         ": a surface set must lie on the solid's outer surface");
      const Vec3 a = pos(n[0]), b = pos(n[1]), c = pos(n[2]);
      Vec3 av =
          nc == 3 ? Vec3(0.5 * (b - a).cross(c - a)) : Vec3(0.5 * (c - a).cross(pos(n[3]) - b));
      Vec3 mid = nc == 3 ? Vec3((a + b + c) / 3.0) : Vec3((a + b + c + pos(n[3])) / 4.0);
      if (av.dot(centroid - mid) > 0.0) av = -av;
      const double area = av.norm() * L * L;
      if (!(area > 0.0))
        throw InputError(path + ": element " + std::to_string(f.element) + " of surface set '" +
                         name + "' has no area (its corners are collinear)");
      const Vec3 unit = av.normalized();
      for (std::size_t k = 0; k < n.size(); ++k) {
        double share;
        if (n.size() == 3 || n.size() == 4)
          share = 1.0 / static_cast<double>(n.size());
        else if (n.size() == 6)
          share = k < 3 ? 1.0 / 12.0 : 0.25;
        else
          share = k < 4 ? 1.0 / 12.0 : 1.0 / 6.0;
        auto& [sum, dir] = acc.try_emplace(n[k], 0.0, Vec3::Zero()).first->second;
        sum += share * area;
        dir += share * area * unit;
      }
    }
    SurfaceSet s;
    const auto N = static_cast<Eigen::Index>(acc.size());
    s.area.resize(N);
    s.normal.resize(N, 3);
    Eigen::Index i = 0;
    for (const auto& [id, v] : acc) {
      s.nodes.push_back(id);
      s.area[i] = v.first;
      const double len = v.second.norm();
      if (!(len > 0.0))
        throw InputError(path + ": node " + std::to_string(id) + " of surface set '" + name +
                         "' sits on faces whose normals cancel (a sheet folded back)");
      s.normal.row(i) = (v.second / len).transpose();
      ++i;
    }
    out.emplace(name, std::move(s));
  }
  return out;
}

}  // namespace evas
