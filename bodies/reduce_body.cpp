#include "bodies/reduce_body.h"

#include <cmath>
#include <set>
#include <unordered_map>

namespace evas {

void store_full_body_data(ModalBody& body) {
  body.require_full("computing the invariants to store");
  body.validate();
  body.invariants = std::make_shared<ModalInvariants>(compute_invariants(body));
  body.mass_props = mass_properties(body.s, body.mass);
}

ModalBody reduce_body(const ModalBody& body, const ReduceOptions& opt) {
  body.validate();
  const std::string who = body.label() + ": reduce: ";
  ModalBody out;
  out.name = body.name;
  out.source = body.source;
  if (body.invariants && body.mass_props) {
    out.invariants = body.invariants;
    out.mass_props = body.mass_props;
  } else {
    out.invariants = std::make_shared<ModalInvariants>(body_invariants(body));
    out.mass_props = body_mass_properties(body);
  }
  out.full_num_nodes = body.reduced() ? body.full_num_nodes : body.num_nodes();

  // Kept sets and nodes.
  std::unordered_map<long, int> row;
  for (int i = 0; i < body.num_nodes(); ++i) row[body.node_ids[i]] = i;
  std::set<int> keep;
  auto keep_set = [&](const std::string& name, const std::vector<long>& ids) {
    out.node_sets[name] = ids;
    if (const auto sf = body.surfaces.find(name); sf != body.surfaces.end()) {
      out.surfaces[name] = sf->second;
      for (long id : sf->second.nodes) keep.insert(row.at(id));
    }
    for (long id : ids) keep.insert(row.at(id));  // validate(): set members are nodes
  };
  if (opt.all_sets) {
    if (!opt.keep_sets.empty())
      throw InputError(who + "give either all sets or a list of sets to keep, not both");
    for (const auto& [name, ids] : body.node_sets) keep_set(name, ids);
  } else {
    for (const std::string& name : opt.keep_sets) {
      const auto it = body.node_sets.find(name);
      if (it == body.node_sets.end()) {
        std::string known;
        for (const auto& s : body.node_sets) known += (known.empty() ? "" : ", ") + s.first;
        throw InputError(who + "no node set '" + name +
                         "' (known: " + (known.empty() ? "none" : known) + ")");
      }
      keep_set(name, it->second);
    }
  }
  for (long id : opt.extra_nodes) {
    const auto it = row.find(id);
    if (it == row.end())
      throw InputError(who + "extra node " + std::to_string(id) + " is not a node of the body");
    keep.insert(it->second);
  }

  const int Nr = static_cast<int>(keep.size()), n = body.num_modes();
  out.node_ids.reserve(Nr);
  out.s.resize(Nr, 3);
  out.modes.resize(3 * Nr, n);
  int r = 0;
  for (int i : keep) {
    out.node_ids.push_back(body.node_ids[i]);
    out.s.row(r) = body.s.row(i);
    out.modes.middleRows(3 * r, 3) = body.modes.middleRows(3 * i, 3);
    ++r;
  }
  out.mass.resize(0, 0);
  out.eigenvalues = body.eigenvalues;
  out.damping = body.damping;
  out.kinds = body.kinds;
  out.validate();
  return out;
}

}  // namespace evas
