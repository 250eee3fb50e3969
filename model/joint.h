// Joints between two markers: holonomic constraints g(t, q) = 0 of a System
// (docs/theory.md section 10.4). Each joint joins marker 1 (on a body) and
// marker 2 (on a body or the ground); its equations, in the rows they take:
//
//   fixed        p.x p.y p.z  r.x r.y r.z        (weld: no relative motion)
//   spherical    p.x p.y p.z                     (ball joint)
//   revolute     p.x p.y p.z  r.x r.y            (hinge about marker 1's z axis)
//   cylindrical  r.x r.y  d.x d.y                (slides along and turns about z)
//   prismatic    r.x r.y r.z  d.x d.y            (slides along z)
//   distance     l                               (massless rod of length L)
//
// with, in G components, p1, p2 the marker positions, theta_i = R_GL_i Bt_i q_i
// the small (modal) rotation of marker i, e_k = R_GL_1 R_LM_1 the k-th reference
// axis of marker 1 and n_k = e_k + theta_1 x e_k the same axis turned by the
// small rotation:
//   p.k:  (p1 - p2)_k                         coincident points
//   r.k:  e_k . (theta_1 - theta_2)           no small relative rotation about e_k
//   d.k:  n_k . (p1 - p2)                     no offset across marker 1's z axis
//   l:    (|p1 - p2|^2 - L^2) / (2 L)         distance L (units of length)
// (joint equations of this kind: Haug, Computer-Aided Kinematics and Dynamics of
// Mechanical Systems, 1989, ch. 3; Shabana, Dynamics of Multibody Systems, 4th
// ed. 2020, ch. 3; here with the small-rotation marker maps of a modal body).
// Rotations enter through the linear marker maps, so r.k is exact within the
// modal model when the two frames do not rotate relative to each other about
// e_k; the System refuses joints where they do (a spinning frame is allowed
// about a revolute or cylindrical joint's axis only).
#pragma once

#include <string>
#include <vector>

#include "model/types.h"

namespace evas {

enum class JointType { fixed, spherical, revolute, cylindrical, prismatic, distance };

struct Joint {
  std::string name;
  JointType type = JointType::fixed;
  int marker1 = -1, marker2 = -1;  ///< marker indices; marker 1 must be on a body
  double length = 0.0;             ///< distance joints: L [m] (> 0)
};

/// The joint type named `name` ("fixed", "spherical", ...); throws InputError
/// naming the known types.
JointType joint_type(const std::string& name);
std::string joint_type_name(JointType t);
std::vector<std::string> joint_type_names();
/// The row names of a joint type ("p.x", "r.y", ...), one per equation.
const std::vector<std::string>& joint_rows(JointType t);

/// What one marker of a joint contributes at (t, q, v), in G components.
struct JointSide {
  bool ground = true;
  Vec3 p = Vec3::Zero(), v = Vec3::Zero(), a0 = Vec3::Zero();  ///< a0: at qdd = 0
  /// small rotation theta = R_GL Bt q, its rate and its second derivative at qdd = 0
  Vec3 th = Vec3::Zero(), thd = Vec3::Zero(), thdd0 = Vec3::Zero();
  Mat3 E = Mat3::Identity();                 ///< reference marker axes (columns)
  Vec3 w = Vec3::Zero(), al = Vec3::Zero();  ///< frame angular velocity, acceleration
  Mat3X Du, Dt;                              ///< dp/dq_b, dtheta/dq_b (3 x n_b)
};

/// Equations of joint `j` (rows as joint_rows(j.type)) from its two sides. Any
/// of g, gv (= dg/dt), ga (= d(gv)/dt at qdd = 0) may be null. With G1, G2 non-null
/// they receive dg/dq on the two bodies' coordinates (rows x n_b; G2 untouched for
/// a ground marker); they must be sized.
void joint_equations(const Joint& j, const JointSide& s1, const JointSide& s2, double* g,
                     double* gv, double* ga, Mat* G1, Mat* G2);

}  // namespace evas
