// The Jacobian blocks of element internal states (Problem::internal_count())
// inside a first-order iteration matrix, shared by FirstOrderForm and DaeForm:
// Fz = df/dz in the rows of v' + f, and Hq, Hv, Hz in the rows of z' - h, with
// v at column v0 and z at row/column z0 (solver/problem.h).
#pragma once

#include <vector>

#include "dae/sparse_util.h"
#include "model/problem.h"

namespace evas::dae {

struct InternalBlocks {
  SpMat Fz, Hq, Hv, Hz;
  std::vector<int> pFz, pHq, pHv, pHz;

  /// Appends the blocks' entries (and the (z, z) diagonal) to trip.
  void place(const Problem& p, std::vector<Triplet>& trip, int v0, int z0) {
    p.internal_patterns(Fz, Hq, Hv, Hz);
    place_pattern(trip, Fz, v0, z0);
    place_pattern(trip, Hq, z0, 0);
    place_pattern(trip, Hv, z0, v0);
    place_pattern(trip, Hz, z0, z0);
    for (int i = 0; i < Hz.rows(); ++i) trip.emplace_back(z0 + i, z0 + i, 0.0);
  }
  /// Finds the value positions in J (built with place()).
  void locate(const SpMat& J, int v0, int z0) {
    pFz = block_positions(J, Fz, v0, z0);
    pHq = block_positions(J, Hq, z0, 0);
    pHv = block_positions(J, Hv, z0, v0);
    pHz = block_positions(J, Hz, z0, z0);
  }
  /// Evaluates the blocks at the problem's current z and adds sign * Fz and
  /// -sign * (Hq, Hv, Hz): sign +1 for the residual z' - h, -1 for the rhs h.
  void add(Problem& p, double t, const double* q, const double* v, double* val, double sign) {
    p.internal_jacobian(t, q, v, Fz, Hq, Hv, Hz);
    add_at(val, pFz, Fz, sign);
    add_at(val, pHq, Hq, -sign);
    add_at(val, pHv, Hv, -sign);
    add_at(val, pHz, Hz, -sign);
  }
};

}  // namespace evas::dae
