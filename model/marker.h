// Markers: where force elements attach (formulation.md section 4).
//
// A marker is a point with a frame on a body (or on the ground). On a modal
// body it is a single node or a weighted node set whose translation u and small
// rotation theta are the weighted least-squares (RBE3-like) fit of the nodal
// displacements, both linear in the modal coordinates:
//     u_L = Bu q,  theta_L = Bt q      (L components)
// A load (F, M) on the marker is spread back by the transpose of the same map:
//     Q = Bu^T R_LG F + Bt^T R_LG M,
// so virtual work is preserved.
#pragma once

#include <string>
#include <vector>

#include "model/lof.h"
#include "model/modal_body.h"

namespace evas {

/// Motion of a marker in G components.
struct MarkerMotion {
  Vec3 p = Vec3::Zero();      ///< position [m]
  Vec3 v = Vec3::Zero();      ///< velocity [m/s]
  Vec3 psi = Vec3::Zero();    ///< rotation vector: LOF rotation since t0 + small elastic/rigid
                              ///< rotation [rad]
  Vec3 w = Vec3::Zero();      ///< angular velocity [rad/s]
  Mat3 R = Mat3::Identity();  ///< marker axes in G (columns), reference axes carried by the LOF
  /// Acceleration and angular acceleration [m/s^2, rad/s^2]. marker_motion() gives
  /// their part at zero modal acceleration (LOF and velocity terms); System::observe()
  /// and the inertial-element path of System::force() add the modal part.
  Vec3 a = Vec3::Zero();
  Vec3 al = Vec3::Zero();
};

/// Load on a marker in G components.
struct MarkerLoad {
  Vec3 F = Vec3::Zero();  ///< force [N]
  Vec3 M = Vec3::Zero();  ///< moment [N m]
};

struct Marker {
  std::string name;
  int body = -1;                 ///< body index, -1 for ground
  Vec3 c = Vec3::Zero();         ///< reference position (L components; G for ground)
  Mat3 R_LM = Mat3::Identity();  ///< reference axes (in L; in G for ground)
  Mat3X Bu;                      ///< 3 x n translation map (empty for ground)
  Mat3X Bt;                      ///< 3 x n rotation map (zero rows where unobservable)
  bool has_rotation = false;     ///< false for a single node or a collinear set

  bool on_ground() const { return body < 0; }
};

/// Marker at a single node.
Marker make_node_marker(const std::string& name, int body, const ModalBody& b, long node_id);
/// Marker on a weighted node set (weights empty = equal weights). The centre is
/// the weighted centroid unless `centre` is given (then the fit is about it).
Marker make_set_marker(const std::string& name, int body, const ModalBody& b,
                       const std::vector<long>& node_ids, const std::vector<double>& weights,
                       const Vec3* centre = nullptr);
/// Marker fixed to the ground at p with axes R.
Marker make_ground_marker(const std::string& name, const Vec3& p_G, const Mat3& R_GM);

/// Marker motion from the body's LOF state and modal coordinates (q, v); the
/// accelerations a, al are those at qdd = 0:
///   a  = a_GL + al_GL x r + w x (w x r) + 2 w x (R Bu v),   al = al_GL + w x (R Bt v)
/// (r = R (c + Bu q)); the modal part R Bu qdd, R Bt qdd is added by the caller.
void marker_motion(const Marker& m, const LofState& L, const double* q, const double* v,
                   MarkerMotion& out);
/// The same from the modal products uq = Bu q, tq = Bt q, uv = Bu v, tv = Bt v
/// (L components; System computes them for all markers of a body at once).
void marker_motion(const Marker& m, const LofState& L, const Vec3& uq, const Vec3& tq,
                   const Vec3& uv, const Vec3& tv, MarkerMotion& out);
/// The same for a marker on a body with its axes R_GM = R_GL R_LM given (System
/// keeps them per time).
void marker_motion(const Marker& m, const LofState& L, const Mat3& R_GM, const Vec3& uq,
                   const Vec3& tq, const Vec3& uv, const Vec3& tv, MarkerMotion& out);

}  // namespace evas
