// Modal invariants of a body (formulation.md section 2), computed once so that
// one evaluation of Eq. 1 costs O(n^2) per body whatever the node count.
//
//   S    (3 x n)   row a: 1^T M_s Phi_a
//   p_ab (n)       Phi_a^T M_s s_b
//   M_ab (n x n)   Phi_a^T M_s Phi_b
#pragma once

#include <array>

#include "model/modal_body.h"

namespace evas {

struct ModalInvariants {
  Mat S;                                ///< 3 x n
  std::array<std::array<Vec, 3>, 3> p;  ///< p[a][b], n each
  std::array<std::array<Mat, 3>, 3> M;  ///< M[a][b], n x n each
};

/// From the body's nodes and mass matrix (never the stored invariants); throws
/// InputError for a reduced body (see solver/reduce_body.h body_invariants()).
ModalInvariants compute_invariants(const ModalBody& body);

/// The frame-dependent terms of Eq. 1 for one body at given LOF kinematics
/// (all in L components): accel a_L (including -g), angular velocity w_L and
/// angular acceleration al_L. Writes
///   f0 = S^T a_L + sum_ab W_ab p_ab,   KW = sum_ab W_ab M_ab,   G = 2 sum_ab Omega_ab M_ab
/// with W = skew(al_L) + skew(w_L)^2 and Omega = skew(w_L). Allocation-free
/// when the outputs already have their sizes.
void frame_terms(const ModalInvariants& inv, const Vec3& a_L, const Vec3& w_L, const Vec3& al_L,
                 Vec& f0, Mat& KW, Mat& G);

/// The two parts of frame_terms: f0 (O(n), changes with gravity seen from a
/// rotating frame) and KW, G (O(n^2), change only when W or Omega change).
void frame_force(const ModalInvariants& inv, const Vec3& a_L, const Mat3& W, Vec& f0);
void frame_matrices(const ModalInvariants& inv, const Mat3& W, const Mat3& Om, Mat& KW, Mat& G);

/// Correction of the rigid-rotation block for the linearised small rotation.
/// Eq. 1 moves a node by theta x d for a rigid rotation theta about the centre
/// of mass; in a rotating frame this linearisation gives the rotation modes a
/// spurious centrifugal stiffness (-omega^2 J about the spin axis: a spinning
/// crankshaft would be torsionally unstable on a soft clutch). Linearising
/// Euler's equations in the frame instead gives the exact first-order stiffness
///   K_exact = -(J al)~ + J al~ + w~ (J w~ - (J w)~),
/// while the modal form yields K_lin = -sum m d~ W d~ (W = al~ + w~ w~); the
/// difference, in rotation-vector components (J about the centre of mass, L axes):
///   K_geo = J al~ - tr(J)/2 al~ - w~ (J w)~ + tr(J)/2 w~ w~ + |w|^2 J.
/// The gyroscopic terms of both forms agree. See docs/theory.md.
Mat3 rigid_rotation_correction(const Mat3& J, const Vec3& w_L, const Vec3& al_L);

/// Eq. 1 evaluated literally with sums over the nodes (lumped masses only), as
/// the paper writes it. Returns the left side minus the modal forces:
///   qdd + sum_i m_i Phi_i^T A^T a + ... + Lambda q + C qd - sum_i Phi_i^T A^T F_i.
/// For verification and benchmarks only: O(N n) per call.
Vec eq1_literal(const ModalBody& body, const Mat3& A, const Vec3& a_G, const Vec3& w_G,
                const Vec3& al_G, const Vec& q, const Vec& qd, const Vec& qdd,
                const Eigen::Matrix<double, Eigen::Dynamic, 3>& F_G);

}  // namespace evas
