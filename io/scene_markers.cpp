// Scene files (see scene.h): markers (ground markers, node markers, markers
// on a node set or list) and the joints between them.
#include <set>

#include "io/body_cache.h"
#include "io/scene_reader.h"

namespace evas::scene_detail {

void SceneReader::read_marker(const Node& m, std::size_t i, Model& model) {
  std::string item = "markers[" + std::to_string(i) + "]";
  expect_map(m, item);
  const std::string name = text(require(m, "name", item), item, "name");
  item = "marker '" + name + "'";
  for (const auto& other : model.markers())
    if (other.name == name) fail(m["name"], item, "a marker with this name is already defined");
  Marker marker;
  if (const Node g = m["ground"]) {
    check_keys(m, item, {"name", "ground", "rotation"});
    const Mat3 R = rotation_from_vector(vec3_or(m, "rotation", item, Vec3::Zero()));
    marker = make_ground_marker(name, vec3(g, item, "ground"), R);
  } else {
    check_keys(m, item, {"name", "body", "node", "set", "nodes", "weights", "centre", "rotation"});
    const Node body_node = require(m, "body", item);
    const std::string body_name = text(body_node, item, "body");
    int body = -1;
    std::vector<std::string> known;
    for (std::size_t k = 0; k < model.bodies().size(); ++k) {
      known.push_back(model.bodies()[k].name);
      if (model.bodies()[k].name == body_name) body = static_cast<int>(k);
    }
    if (body < 0)
      fail(body_node, item, "no body named '" + body_name + "' (known: " + join(known) + ")");
    const ModalBody& data = *model.bodies()[body].data;
    const Node node = m["node"], set = m["set"], nodes = m["nodes"];
    if (int(bool(node)) + int(bool(set)) + int(bool(nodes)) != 1)
      fail(m, item,
           "give exactly one of 'node', 'set' and 'nodes' (or 'ground' for a ground marker)");
    try {
      if (node) {
        if (m["weights"] || m["centre"])
          fail(m, item, "'weights' and 'centre' apply to 'set' or 'nodes' markers only");
        marker = make_node_marker(name, body, data, integer(node, item, "node", -(1L << 62)));
      } else {
        std::vector<long> ids;
        if (set) {
          const std::string set_name = text(set, item, "set");
          const auto it = data.node_sets.find(set_name);
          if (it == data.node_sets.end()) {
            std::vector<std::string> sets;
            for (const auto& s : data.node_sets) sets.push_back(s.first);
            fail(set, item,
                 "body '" + body_name + "' has no node set '" + set_name +
                     "' (known: " + join(sets) + ")");
          }
          ids = it->second;
        } else {
          if (!nodes.IsSequence()) fail(nodes, item, "'nodes' must be a list of node ids");
          check_size(nodes, item, "nodes");
          std::set<long> seen;
          for (const Node& x : nodes) {
            ids.push_back(integer(x, item, "nodes", -(1L << 62)));
            if (!seen.insert(ids.back()).second)
              fail(x, item,
                   "node id " + std::to_string(ids.back()) +
                       " is listed twice in 'nodes' (each node once; use 'weights' to weight "
                       "it)");
          }
        }
        std::vector<double> weights;
        if (m["weights"]) weights = numbers(m["weights"], item, "weights", ids.size());
        Vec3 centre;
        const bool has_centre = bool(m["centre"]);
        if (has_centre) centre = marker_centre(m["centre"], item, data, ids);
        marker = set_marker_cached(name, body, model.bodies()[body].data, ids, weights,
                                   has_centre ? &centre : nullptr);
      }
    } catch (const InputError& e) {
      const std::string msg = e.what();
      if (msg.rfind(file_ + ":", 0) == 0) throw;
      rethrow(node ? node : set ? set : nodes, item, e);
    }
    if (m["rotation"]) marker.R_LM = rotation_from_vector(vec3(m["rotation"], item, "rotation"));
  }
  try {
    model.add_marker(std::move(marker));
  } catch (const InputError& e) {
    rethrow(m, item, e);
  }
}

void SceneReader::read_joint(const Node& e, std::size_t i, Model& model) {
  std::string item = "joints[" + std::to_string(i) + "]";
  expect_map(e, item);
  const std::string name = text(require(e, "name", item), item, "name");
  item = "joint '" + name + "'";
  check_keys(e, item, {"name", "type", "markers", "length"});
  Joint j;
  j.name = name;
  const Node type = require(e, "type", item);
  try {
    j.type = joint_type(text(type, item, "type"));
  } catch (const InputError& err) {
    fail(type, item, err.what());
  }
  const Node markers = require(e, "markers", item);
  if (!markers.IsSequence() || markers.size() != 2)
    fail(markers, item, "'markers' must be a list of two marker names" + got(markers));
  std::vector<std::string> names;
  for (const auto& m : model.markers()) names.push_back(m.name);
  int idx[2] = {-1, -1};
  for (int k = 0; k < 2; ++k) {
    const std::string mname = text(markers[k], item, "markers");
    for (std::size_t m = 0; m < names.size(); ++m)
      if (names[m] == mname) idx[k] = static_cast<int>(m);
    if (idx[k] < 0)
      fail(markers[k], item, "no marker named '" + mname + "' (known: " + join(names) + ")");
  }
  j.marker1 = idx[0];
  j.marker2 = idx[1];
  if (const Node len = e["length"]) {
    if (j.type != JointType::distance) fail(len, item, "'length' applies to distance joints only");
    j.length = number_in(len, item, "length", 0.0, 1e300, true);
  }
  try {
    model.add_joint(std::move(j));
  } catch (const InputError& err) {
    rethrow(e, item, err);
  }
}

}  // namespace evas::scene_detail
