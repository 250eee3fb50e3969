// Private helpers of dae/: positions of entries in a fixed sparsity pattern
// (compressed column-major, as solver/first_order.cpp builds its matrices).
#pragma once

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "model/types.h"

namespace evas::dae {

/// Position of (row, col) in the value array of a compressed column-major matrix.
inline int value_position(const SpMat& A, int row, int col) {
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();
  const int* begin = inner + outer[col];
  const int* end = inner + outer[col + 1];
  const int* it = std::lower_bound(begin, end, row);
  if (it == end || *it != row) throw std::logic_error("dae: entry missing from pattern");
  return static_cast<int>(it - inner);
}

/// Positions in J of the entries of S placed with its (0, 0) at (row0, col0).
inline std::vector<int> block_positions(const SpMat& J, const SpMat& S, int row0, int col0) {
  std::vector<int> pos(static_cast<std::size_t>(S.nonZeros()));
  for (int c = 0; c < S.cols(); ++c)
    for (int k = S.outerIndexPtr()[c]; k < S.outerIndexPtr()[c + 1]; ++k)
      pos[static_cast<std::size_t>(k)] = value_position(J, row0 + S.innerIndexPtr()[k], col0 + c);
  return pos;
}

/// val[pos[e]] += sign * S.valuePtr()[e] for every entry e of S.
inline void add_at(double* val, const std::vector<int>& pos, const SpMat& S, double sign) {
  const double* s = S.valuePtr();
  for (std::size_t e = 0; e < pos.size(); ++e) val[pos[e]] += sign * s[e];
}

/// Appends the entries of S placed at (row0, col0) to trip (values zero).
inline void place_pattern(std::vector<Triplet>& trip, const SpMat& S, int row0, int col0) {
  for (int c = 0; c < S.cols(); ++c)
    for (SpMat::InnerIterator it(S, c); it; ++it) trip.emplace_back(row0 + it.row(), col0 + c, 0.0);
}

/// A compressed pattern (values zero) with the given entries (duplicates allowed).
inline SpMat pattern_from(int rows, int cols, const std::vector<Triplet>& trip) {
  SpMat A(rows, cols);
  A.setFromTriplets(trip.begin(), trip.end());
  A.makeCompressed();
  A.coeffs().setZero();
  return A;
}

/// Structural pattern of G^T G (n x n) for G m x n: entry (i, j) whenever some
/// row of G holds both columns i and j (the Hessian of that constraint may
/// couple them).
inline std::vector<Triplet> gtg_entries(const SpMat& G) {
  std::vector<std::vector<int>> rows(static_cast<std::size_t>(G.rows()));
  for (int c = 0; c < G.outerSize(); ++c)
    for (SpMat::InnerIterator it(G, c); it; ++it)
      rows[static_cast<std::size_t>(it.row())].push_back(c);
  std::vector<Triplet> trip;
  for (const auto& r : rows)
    for (int a : r)
      for (int b : r) trip.emplace_back(a, b, 0.0);
  return trip;
}

}  // namespace evas::dae
