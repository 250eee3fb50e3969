// Random modal bodies for tests: random nodes and masses, the explicit rigid
// basis, and random elastic shapes M-orthonormalised against it.
#pragma once

#include <random>

#include "model/modal_body.h"

namespace evas::test_bodies {

inline ModalBody random_body(int N, int n_elastic, unsigned seed, bool rigid = true,
                             bool consistent = false) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  ModalBody b;
  b.name = "random" + std::to_string(seed);
  b.s.resize(N, 3);
  for (int i = 0; i < N; ++i) {
    b.node_ids.push_back(100 + 3 * i);
    b.s.row(i) << 0.5 * U(gen) + 0.2, 0.3 * U(gen) - 0.1, 0.2 * U(gen) + 0.05;
  }
  std::vector<Triplet> t;
  for (int i = 0; i < N; ++i) t.emplace_back(i, i, 1.0 + 0.5 * U(gen));
  if (consistent)
    for (int i = 0; i + 1 < N; ++i) {
      const double c = 0.1 + 0.05 * U(gen);
      t.emplace_back(i, i + 1, c);
      t.emplace_back(i + 1, i, c);
    }
  b.mass.resize(N, N);
  b.mass.setFromTriplets(t.begin(), t.end());
  const Mat R = rigid_basis(b.s, b.mass);
  Mat E(3 * N, n_elastic);
  for (int j = 0; j < n_elastic; ++j)
    for (int r = 0; r < 3 * N; ++r) E(r, j) = U(gen);
  // Two passes of modified Gram-Schmidt in the mass inner product.
  for (int pass = 0; pass < 2; ++pass)
    for (int j = 0; j < n_elastic; ++j) {
      Vec e = E.col(j);
      const Vec Me = apply_mass(b.mass, e);
      e -= R * (R.transpose() * Me);
      for (int k = 0; k < j; ++k) e -= E.col(k) * E.col(k).dot(Vec(apply_mass(b.mass, e)));
      e /= std::sqrt(e.dot(Vec(apply_mass(b.mass, e))));
      E.col(j) = e;
    }
  const int n = (rigid ? 6 : 0) + n_elastic;
  b.modes.resize(3 * N, n);
  if (rigid) b.modes.leftCols(6) = R;
  b.modes.rightCols(n_elastic) = E;
  b.eigenvalues = Vec::Zero(n);
  b.damping = Vec::Zero(n);
  for (int k = 0; k < n; ++k) {
    const bool el = !rigid || k >= 6;
    b.kinds.push_back(el ? ModeKind::Elastic : ModeKind::Rigid);
    if (el) {
      b.eigenvalues[k] = std::pow(2 * M_PI * (50.0 + 30.0 * k), 2);
      b.damping[k] = 2 * 0.01 * std::sqrt(b.eigenvalues[k]);
    }
  }
  std::vector<long> all(b.node_ids.begin(), b.node_ids.end());
  b.node_sets["all"] = all;
  b.node_sets["first4"] = std::vector<long>(all.begin(), all.begin() + std::min(4, N));
  return b;
}

}  // namespace evas::test_bodies
