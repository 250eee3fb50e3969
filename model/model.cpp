#include "model/model.h"

#include <cmath>
#include <sstream>

#include "model/body_properties.h"

namespace evas {

int Model::add_body(const std::string& name, std::shared_ptr<const ModalBody> data, const Lof& lof,
                    bool checked) {
  for (const auto& b : bodies_)
    if (b.name == name) throw InputError("body '" + name + "' defined twice");
  if (!checked) data->validate();
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

int Model::add_joint(Joint j) {
  const std::string item = "joint '" + j.name + "': ";
  for (const auto& x : joints_)
    if (x.name == j.name) throw InputError(item + "a joint with this name is already defined");
  for (const auto& x : elements_)
    if (x->name() == j.name)
      throw InputError(item +
                       "an element has this name (joint and element names share the "
                       "output channels, so they must differ)");
  const int nm = static_cast<int>(markers_.size());
  if (j.marker1 < 0 || j.marker1 >= nm || j.marker2 < 0 || j.marker2 >= nm)
    throw InputError(item + "marker index out of range");
  const Marker &m1 = markers_[j.marker1], &m2 = markers_[j.marker2];
  if (j.marker1 == j.marker2) throw InputError(item + "joins marker '" + m1.name + "' to itself");
  if (m1.on_ground())
    throw InputError(item + "marker 1 ('" + m1.name + "') is on the ground; the first marker " +
                     "must be on a body (its axes are the joint's axes)");
  if (m1.body == m2.body)
    throw InputError(item + "both markers are on body '" + bodies_[m1.body].name +
                     "'; a joint joins two bodies or a body and the ground");
  const auto& rows = joint_rows(j.type);
  bool rot = false;
  for (const auto& r : rows) rot = rot || r[0] == 'r' || r[0] == 'd';
  for (const Marker* m : {&m1, &m2})
    if (rot && !m->on_ground() && !m->has_rotation)
      throw InputError(item + "a " + joint_type_name(j.type) + " joint needs the rotation of " +
                       "marker '" + m->name + "', which has none (a single node or a collinear " +
                       "node set); use a marker on a node set that spans an area");
  if (j.type == JointType::distance && j.length == 0.0) {
    // default: the distance in the reference configuration (t = 0, q = 0)
    auto ref = [&](const Marker& m) -> Vec3 {
      if (m.on_ground()) return m.c;
      const LofState L = bodies_[m.body].lof.at(0.0);
      return L.p_GL + L.R_GL * m.c;
    };
    j.length = (ref(m1) - ref(m2)).norm();
  }
  if (j.type == JointType::distance && !(j.length > 0.0 && std::isfinite(j.length)))
    throw InputError(item + "the length of a distance joint must be > 0 (two coincident " +
                     "points are a spherical joint); got " +
                     [&] {
                       std::ostringstream os;
                       os << j.length;
                       return os.str();
                     }() +
                     " m");
  joints_.push_back(std::move(j));
  return static_cast<int>(joints_.size()) - 1;
}

int Model::find_element(const std::string& name) const {
  for (std::size_t i = 0; i < elements_.size(); ++i)
    if (elements_[i]->name() == name) return static_cast<int>(i);
  throw InputError("no element named '" + name + "'");
}

}  // namespace evas
