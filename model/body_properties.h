// The invariants and mass properties a Model takes from a modal body (the
// stored ones of a reduced body, else computed from the nodes), and where the
// explicit rigid-body modes stand among its modes. The reduction itself, which
// stores them with a body, is in bodies/reduce_body.h.
#pragma once

#include <array>

#include "model/invariants.h"

namespace evas {

/// The invariants of a body: the stored ones when present, otherwise computed
/// from its nodes (which throws for a reduced body).
ModalInvariants body_invariants(const ModalBody& body);
/// The mass properties of a body: stored when present, otherwise computed.
MassProperties body_mass_properties(const ModalBody& body);

/// Rigid-body participation of the modes, P = R^T M Phi (6 x n, R the
/// mass-orthonormal rigid basis of rigid_basis(): tx, ty, tz, then rotations
/// about the principal axes), from the invariants and mass properties alone:
///   P_a = S_a / sqrt(m),  P_{3+k} = e_k . (h - com x S) / sqrt(J_k),
///   h = (p_zy - p_yz, p_xz - p_zx, p_yx - p_xy).
/// A mode equals rigid basis vector r exactly when P(:, j) = e_r and its mass
/// norm sum_a M_aa(j, j) is 1.
Mat rigid_participation(const ModalInvariants& inv, const MassProperties& mp);

/// Index of the explicit rigid basis modes (tx, ty, tz, r1, r2, r3) among the
/// body's rigid-kind modes, or -1 where absent. Uses the stored invariants and
/// mass properties (plus the mode rows at the kept nodes) when the body carries
/// them, the full node set and mass matrix otherwise.
std::array<int, 6> find_rigid_modes(const ModalBody& body, const ModalInvariants& inv,
                                    const MassProperties& mp);

}  // namespace evas
