// A moving elastic body described by eigenmodes (paper Eq. 1).
//
// Nodes carry undeformed positions s_i in the body's local observer frame
// (LOF) and a scalar mass matrix M_s (N x N): the consistent mass of a solid
// FE model is M = M_s (x) I3; a lumped-mass model has a diagonal M_s.
// Modes are mass-normalised (Phi^T M Phi = I), stored as a 3N x n matrix whose
// row 3*i + a is the a-component (a = x, y, z) of node i.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "solver/types.h"

namespace evas {

enum class ModeKind { Rigid = 0, Elastic = 1 };

struct ModalBody {
  std::string name;
  std::vector<long> node_ids;                  ///< FE node id of each node (unique)
  Eigen::Matrix<double, Eigen::Dynamic, 3> s;  ///< N x 3 undeformed positions in L [m]
  SpMat mass;                                  ///< N x N scalar mass matrix M_s [kg]
  Vec eigenvalues;                             ///< n, lambda_k = omega_k^2 [rad^2/s^2]
  Mat modes;                                   ///< 3N x n mass-normalised shapes
  Vec damping;                  ///< n, modal damping c_k [1/s] (c_k = 2 zeta_k omega_k)
  std::vector<ModeKind> kinds;  ///< n, rigid or elastic
  std::map<std::string, std::vector<long>> node_sets;  ///< named sets of node ids

  int num_nodes() const { return static_cast<int>(s.rows()); }
  int num_modes() const { return static_cast<int>(modes.cols()); }
  /// Row index of a node id; throws InputError naming the body if absent.
  int node_index(long id) const;
  /// Throws InputError if sizes disagree or values are not finite.
  void validate() const;
  /// Keep only the listed modes (in the given order).
  ModalBody select_modes(const std::vector<int>& keep) const;
};

/// Mass, centre of mass and inertia (about the centre of mass, L axes).
struct MassProperties {
  double mass = 0.0;
  Vec3 com = Vec3::Zero();
  Mat3 inertia = Mat3::Zero();
  Vec3 principal_moments = Vec3::Zero();   ///< ascending
  Mat3 principal_axes = Mat3::Identity();  ///< columns, right-handed
};

MassProperties mass_properties(const Eigen::Matrix<double, Eigen::Dynamic, 3>& s, const SpMat& Ms);

/// Explicit mass-orthonormal rigid basis (3N x 6): three translations and three
/// small rotations about the principal axes through the centre of mass.
Mat rigid_basis(const Eigen::Matrix<double, Eigen::Dynamic, 3>& s, const SpMat& Ms);

/// y = (M_s (x) I3) x for 3N-vectors / 3N x k matrices in the row layout above.
Mat apply_mass(const SpMat& Ms, const Mat& x);

}  // namespace evas
