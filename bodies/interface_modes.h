// Interface (static correction) modes for free-free modal bodies.
//
// A truncated set of normal modes represents the local deflection under a
// concentrated load (a bearing journal, a mount) poorly: the static response
// needs many high modes. Craig & Bampton (1968) add static shapes of the
// interface; for a free-free body the same idea uses inertia relief (the
// "static correction modes" of Dickens & Pool, used by Yoo & Haug 1986):
//
//   1. For each interface node set, unit loads through the set's centroid,
//      spread RBE3-like over the set nodes exactly as the transpose of the
//      set marker's map (solver/marker.h): 3 forces and, if the set is not a
//      single node, up to 3 moments.
//   2. Inertia relief: f_eq = f - M R R^T f (R: mass-orthonormal rigid basis),
//      a self-equilibrated load; solve K u = f_eq with R^T M u = 0.
//   3. Remove the components along all modes the body already keeps
//      (M-orthogonalisation), drop shapes that are (numerically) in their span.
//   4. Rayleigh-Ritz on the new shapes: (Psi^T K Psi) x = mu (Psi^T M Psi) x, so
//      the added modes are M-orthonormal and K-orthogonal to each other and to
//      the kept modes (which are exact eigenvectors); mu are their eigenvalues.
//
// With them a static load in the span of the interface loads is represented
// exactly (up to round-off) by the modal basis, whatever the number of normal
// modes kept (tests/test_interface_modes.cpp, docs/fe-pipeline.md).
#pragma once

#include <string>
#include <vector>

#include "bodies/truss.h"
#include "model/modal_body.h"

namespace evas {

/// Which unit loads of one set generate its static shapes: forces along the
/// body axes x, y, z and the set's moments. A journal loaded radially needs two
/// forces, not six loads.
struct InterfaceLoadMask {
  bool force[3] = {true, true, true};
  bool moments = true;
};

struct InterfaceOptions {
  bool moments = true;  ///< also the unit moments of each set (else forces only)
  /// Per set (same order as the sets) the loads to use; empty: the three forces
  /// and, with `moments`, the moments of every set.
  std::vector<InterfaceLoadMask> loads;
  /// > 0: rank the static shapes by the residual flexibility they carry at the
  /// loaded points (MacNeal 1971, Rubin 1975): the eigen-decomposition of
  /// F^T (U - P P^T M U), the loads' compliance that the kept modes P miss, and
  /// keep the principal load combinations whose residual compliance is at least
  /// this fraction of the largest. Moments are scaled by the set's radius so
  /// that they compare with forces. 0: keep every independent shape (the
  /// unranked static correction).
  double rank_tolerance = 0.0;
  /// > 0: keep at most this many ranked shapes (the largest residual compliance).
  int max_count = 0;
  /// Load-dependent Ritz vectors (Wilson, Yuan & Dickens 1982): after the static
  /// shapes X0, this many further blocks X_{b+1} = K^+ M X_b (inertia relief),
  /// each M-orthogonalised against the kept modes and the blocks before.
  int krylov_blocks = 0;
  double damping_ratio = 0.0;  ///< modal damping ratio of the added modes
  /// A correction shape whose M-norm, after removing the kept modes, is below
  /// this fraction of its norm before is dropped (already in their span).
  double independence_tol = 1e-6;
};

/// Nodal load vectors (3N x k, DOF 3i+a) of unit forces along x, y, z through
/// the centroid of the node set (equal weights) and, with `moments`, unit
/// moments about the principal axes of the set's polar tensor that are
/// observable (none for a single node, two for a collinear set). Node ids are
/// those of fe.node_ids; unknown ids are an InputError.
Mat interface_loads(const FeModel& fe, const std::vector<long>& set, bool moments);

/// Inertia-relief static solver of a free-free FE model: for loads F (3N x k)
/// returns U with K U = F - M R R^T F and R^T M U = 0. K is factorised once
/// (SimplicialLDLT) with six well-chosen DOF fixed (a statically determinate
/// support picked by pivoted QR of R^T); since the relieved load is
/// self-equilibrated the support reactions vanish and the solution is exact.
class InertiaReliefSolver {
 public:
  explicit InertiaReliefSolver(const FeModel& fe);
  Mat solve(const Mat& F) const;
  /// The relieved (self-equilibrated) loads F - M R R^T F.
  Mat relieve(const Mat& F) const;
  const Mat& rigid() const { return R_; }

 private:
  SpMat K_;
  SpMat Ms_;
  Mat R_;
  std::vector<int> fixed_;
  std::vector<bool> is_fixed_;
  Eigen::SimplicialLDLT<SpMat> ldlt_;
};

/// Body with the interface modes of the given node sets appended (after the
/// existing modes, ascending eigenvalue among themselves, ModeKind::Elastic).
/// `body` must have been built from `fe` (same nodes, same mass).
ModalBody add_interface_modes(const FeModel& fe, const ModalBody& body,
                              const std::vector<std::vector<long>>& interface_sets,
                              const InterfaceOptions& opt);

/// Same, with the sets named (keys of fe.node_sets).
ModalBody add_interface_modes_by_name(const FeModel& fe, const ModalBody& body,
                                      const std::vector<std::string>& set_names,
                                      const InterfaceOptions& opt);

}  // namespace evas
