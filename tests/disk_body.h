// Rigid disk test body: N equal masses on a ring of radius r in the y-z plane
// (axis x), inertia J about x. Its single mode is the rigid basis' rotation about
// x (solver/modal_body.h rigid_basis), so a Model finds it as a rigid mode and a
// spinning LOF gets the rigid-rotation correction. All nodes form the set "all".
#pragma once

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "model/modal_body.h"

namespace evas::test_bodies {

inline std::shared_ptr<ModalBody> disk(const std::string& name, double J, double r = 0.1,
                                       int N = 12) {
  auto b = std::make_shared<ModalBody>();
  b->name = name;
  const double mi = J / (N * r * r);
  b->s.resize(N, 3);
  std::vector<Triplet> t;
  for (int i = 0; i < N; ++i) {
    const double a = 2 * M_PI * i / N;
    b->node_ids.push_back(i + 1);
    b->s.row(i) << 0.0, r * std::cos(a), r * std::sin(a);
    t.emplace_back(i, i, mi);
  }
  b->mass.resize(N, N);
  b->mass.setFromTriplets(t.begin(), t.end());
  const MassProperties mp = mass_properties(b->s, b->mass);
  int k = 0;  // the principal axis along x
  for (int i = 0; i < 3; ++i)
    if (std::abs(mp.principal_axes(0, i)) > 0.99) k = i;
  b->modes = rigid_basis(b->s, b->mass).col(3 + k);
  b->eigenvalues = Vec::Zero(1);
  b->damping = Vec::Zero(1);
  b->kinds = {ModeKind::Rigid};
  b->node_sets["all"] = std::vector<long>(b->node_ids.begin(), b->node_ids.end());
  return b;
}

/// Rotation of the disk about +x per unit modal coordinate [rad] (+-1/sqrt(J)).
inline double rotation_per_q(const ModalBody& b) {
  const Vec3 s = b.s.row(1).transpose();
  const Vec3 u = b.modes.block<3, 1>(3, 0);
  return Vec3::UnitX().dot(s.cross(u)) / s.squaredNorm();
}

}  // namespace evas::test_bodies
