// A moving elastic body described by eigenmodes (paper Eq. 1).
//
// Nodes carry undeformed positions s_i in the body's local observer frame
// (LOF) and a scalar mass matrix M_s (N x N): the consistent mass of a solid
// FE model is M = M_s (x) I3; a lumped-mass model has a diagonal M_s.
// Modes are mass-normalised (Phi^T M Phi = I), stored as a 3N x n matrix whose
// row 3*i + a is the a-component (a = x, y, z) of node i.
//
// A body may also carry data computed once from the full FE body (body file
// format version 2): its modal invariants and mass properties. A *reduced*
// body (solver/reduce_body.h) keeps only the nodes that markers and outputs
// need, with their mode-shape rows, and no mass matrix: everything that needs
// the full node set then comes from the stored data, and whatever cannot is
// refused (require_full) rather than computed from the partial nodes.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "model/surface.h"
#include "model/types.h"

namespace evas {

enum class ModeKind { Rigid = 0, Elastic = 1 };

/// Mass, centre of mass and inertia (about the centre of mass, L axes).
struct MassProperties {
  double mass = 0.0;
  Vec3 com = Vec3::Zero();
  Mat3 inertia = Mat3::Zero();
  Vec3 principal_moments = Vec3::Zero();   ///< ascending
  Mat3 principal_axes = Mat3::Identity();  ///< columns, right-handed
};

struct ModalInvariants;  // solver/invariants.h

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
  /// Per-node areas and outward normals of the sets that lie on the FE mesh's
  /// surface (model/surface.h), keyed like node_sets; optional.
  std::map<std::string, SurfaceSet> surfaces;

  // Data of the full body (format version 2, optional). When present they were
  // computed from the full node set and mass matrix, and Model::add_body uses
  // them instead of recomputing from the nodes.
  std::shared_ptr<const ModalInvariants> invariants;  ///< one entry per mode (as `modes`)
  std::optional<MassProperties> mass_props;
  /// > 0 for a reduced body: the node count of the full body it was cut from.
  /// A reduced body has no mass matrix (`mass` is 0 x 0) and must carry both
  /// `invariants` and `mass_props`.
  long full_num_nodes = 0;
  std::string source;  ///< file the body was read from ("" if built in memory), for messages

  int num_nodes() const { return static_cast<int>(s.rows()); }
  int num_modes() const { return static_cast<int>(modes.cols()); }
  bool reduced() const { return full_num_nodes > 0; }
  /// Row index of a node id; throws InputError naming the body if absent.
  int node_index(long id) const;
  /// Row indices of many node ids (one hash table for the lot: a linear
  /// search per node cost 11 % of the engine's set-up); the same errors.
  std::vector<int> node_indices(const std::vector<long>& ids) const;
  /// Throws InputError if sizes disagree or values are not finite.
  void validate() const;
  /// Keep only the listed modes (in the given order); stored invariants follow.
  ModalBody select_modes(const std::vector<int>& keep) const;
  /// Throws InputError naming the body and its file when the body is reduced:
  /// `what` (e.g. "the rigid basis") needs the full node set and mass matrix.
  void require_full(const std::string& what) const;
  /// Throws the InputError of node_index for an absent id.
  [[noreturn]] void missing_node(long id) const;
  /// "body 'NAME'" or "body 'NAME' (FILE)", for messages.
  std::string label() const;
};

MassProperties mass_properties(const Eigen::Matrix<double, Eigen::Dynamic, 3>& s, const SpMat& Ms);

/// Explicit mass-orthonormal rigid basis (3N x 6): three translations and three
/// small rotations about the principal axes through the centre of mass.
Mat rigid_basis(const Eigen::Matrix<double, Eigen::Dynamic, 3>& s, const SpMat& Ms);
/// The same basis evaluated at the nodes s from given mass properties (of the
/// full body): the rows of the full basis at these nodes.
Mat rigid_basis(const Eigen::Matrix<double, Eigen::Dynamic, 3>& s, const MassProperties& mp);

/// y = (M_s (x) I3) x for 3N-vectors / 3N x k matrices in the row layout above.
Mat apply_mass(const SpMat& Ms, const Mat& x);

}  // namespace evas
