// The model: bodies (modal data + invariants + LOF), markers and elements.
// Built by the scene reader (io/scene) or directly in code (tests).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "model/element.h"
#include "model/invariants.h"
#include "model/joint.h"
#include "model/lof.h"
#include "model/marker.h"

namespace evas {

struct Body {
  std::string name;
  std::shared_ptr<const ModalBody> data;
  ModalInvariants inv;
  MassProperties mp;
  Lof lof;
  int offset = 0;  ///< first coordinate of this body in the system vector q
  Vec q0, v0;      ///< initial modal coordinates and velocities
  /// Index of the explicit rigid basis modes (tx, ty, tz, r1, r2, r3) or -1 where absent.
  std::array<int, 6> rigid = {-1, -1, -1, -1, -1, -1};
  /// Modes (0 .. n-1, ascending) taken as quasi-static: no inertia, their
  /// equation f_k = 0 (Problem::quasi_static; the scene's
  /// `modes: {quasi_static_above: HZ}`).
  std::vector<int> quasi_static;

  int n() const { return data->num_modes(); }
};

class Model {
 public:
  Vec3 gravity = Vec3::Zero();  ///< [m/s^2], G components

  /// Adds a body: its invariants and mass properties (the stored ones of the
  /// full body when it carries them, as a reduced body must; else computed from
  /// its nodes) and the location of its rigid basis modes.
  /// `checked`: data->validate() has passed already (a body a study shares
  /// between its parses); otherwise it is checked here.
  int add_body(const std::string& name, std::shared_ptr<const ModalBody> data, const Lof& lof,
               bool checked = false);
  int add_marker(Marker m);
  int add_element(std::unique_ptr<Element> e);
  /// Adds a joint (solver/joint.h); checks its name, markers and length.
  int add_joint(Joint j);

  int find_body(const std::string& name) const;     ///< throws InputError
  int find_marker(const std::string& name) const;   ///< throws InputError
  int find_element(const std::string& name) const;  ///< throws InputError

  std::vector<Body>& bodies() { return bodies_; }
  const std::vector<Body>& bodies() const { return bodies_; }
  const std::vector<Marker>& markers() const { return markers_; }
  const std::vector<std::unique_ptr<Element>>& elements() const { return elements_; }
  const std::vector<Joint>& joints() const { return joints_; }
  int size() const { return size_; }  ///< total number of modal coordinates

 private:
  std::vector<Body> bodies_;
  std::vector<Marker> markers_;
  std::vector<std::unique_ptr<Element>> elements_;
  std::vector<Joint> joints_;
  int size_ = 0;
};

}  // namespace evas
