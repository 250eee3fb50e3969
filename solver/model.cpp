#include "solver/model.h"

#include <cmath>

#include "solver/reduce_body.h"

namespace evas {

int Model::add_body(const std::string& name, std::shared_ptr<const ModalBody> data,
                    const Lof& lof) {
  for (const auto& b : bodies_)
    if (b.name == name) throw InputError("body '" + name + "' defined twice");
  data->validate();
  Body b;
  b.name = name;
  b.data = std::move(data);
  // Stored invariants and mass properties (of the full body) when the body
  // carries them, which a reduced body must; else computed from the nodes.
  b.inv = body_invariants(*b.data);
  b.mp = body_mass_properties(*b.data);
  b.lof = lof;
  b.offset = size_;
  b.q0 = Vec::Zero(b.n());
  b.v0 = Vec::Zero(b.n());
  b.rigid = find_rigid_modes(*b.data, b.inv, b.mp);
  if (lof.kind() == LofKind::Tracking)
    for (int r : b.rigid)
      if (r < 0)
        throw InputError("body '" + name +
                         "': a tracking LOF needs the six explicit rigid modes (rigid: true)");
  size_ += b.n();
  bodies_.push_back(std::move(b));
  return static_cast<int>(bodies_.size()) - 1;
}

int Model::add_marker(Marker m) {
  for (const auto& x : markers_)
    if (x.name == m.name) throw InputError("marker '" + m.name + "' defined twice");
  if (!m.on_ground()) {
    if (m.body >= static_cast<int>(bodies_.size()))
      throw InputError("marker '" + m.name + "': no such body");
    if (m.Bu.cols() != bodies_[m.body].n())
      throw InputError("marker '" + m.name + "': map size differs from body mode count");
  }
  markers_.push_back(std::move(m));
  return static_cast<int>(markers_.size()) - 1;
}

int Model::add_element(std::unique_ptr<Element> e) {
  for (const auto& x : elements_)
    if (x->name() == e->name()) throw InputError("element '" + e->name() + "' defined twice");
  const auto& ids = e->markers();
  for (std::size_t slot = 0; slot < ids.size(); ++slot) {
    const int m = ids[slot];
    if (m < 0 || m >= static_cast<int>(markers_.size()))
      throw InputError("element '" + e->name() + "': marker index out of range");
    if (e->needs_rotation(slot) && !markers_[m].has_rotation)
      throw InputError("element '" + e->name() + "': marker '" + markers_[m].name +
                       "' carries no rotation (a single node or a collinear node set), but "
                       "this element reads its rotation or loads it with a moment; attach it "
                       "to a node set that spans a plane");
  }
  elements_.push_back(std::move(e));
  return static_cast<int>(elements_.size()) - 1;
}

int Model::find_body(const std::string& name) const {
  for (std::size_t i = 0; i < bodies_.size(); ++i)
    if (bodies_[i].name == name) return static_cast<int>(i);
  throw InputError("no body named '" + name + "'");
}

int Model::find_marker(const std::string& name) const {
  for (std::size_t i = 0; i < markers_.size(); ++i)
    if (markers_[i].name == name) return static_cast<int>(i);
  throw InputError("no marker named '" + name + "'");
}

int Model::find_element(const std::string& name) const {
  for (std::size_t i = 0; i < elements_.size(); ++i)
    if (elements_[i]->name() == name) return static_cast<int>(i);
  throw InputError("no element named '" + name + "'");
}

}  // namespace evas
