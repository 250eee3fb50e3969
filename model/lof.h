// Local observer frames (paper Fig. 3, formulation.md section 3).
//
// The motion of a LOF is prescribed, not solved for. Kinds:
//  - fixed:     constant pose.
//  - spin:      rotation by angle theta(t) about a fixed axis (G components) through
//               a fixed point, speed constant or a profile omega(t) through given
//               knots: monotone cubic Hermite (Fritsch-Carlson), flat at the first
//               and last knot, so that the angular acceleration is continuous
//               (a jump in alpha would cost the integrators their order);
//               optionally the origin moves with constant acceleration.
//  - tracking:  moves with constant velocity and angular velocity between
//               anchors; at each anchor the body's rigid-mode motion is moved
//               into the frame and the rigid coordinates are reset (paper:
//               "the LOF is updated so that q stays infinitesimal").
// Names carry frames: p_GL is the origin of L in G, R_GL rotates L components
// into G components, w_GL_G is the angular velocity of L in G (G components).
#pragma once

#include <vector>

#include "model/speed_profile.h"
#include "model/types.h"

namespace evas {

struct LofState {
  Vec3 p_GL = Vec3::Zero();  ///< origin position [m]
  Vec3 v_GL = Vec3::Zero();  ///< origin velocity [m/s]
  Vec3 a_GL = Vec3::Zero();  ///< origin acceleration [m/s^2]
  Mat3 R_GL = Mat3::Identity();
  Vec3 w_GL_G = Vec3::Zero();   ///< angular velocity [rad/s]
  Vec3 al_GL_G = Vec3::Zero();  ///< angular acceleration [rad/s^2]
  Vec3 psi_G = Vec3::Zero();    ///< rotation vector: spin theta(t)*axis (theta0 included), fixed 0,
                                ///< tracking: accumulated since t0 [rad]
};

enum class LofKind { Fixed, Spin, Tracking };

class Lof {
 public:
  /// Fixed frame at pose (p, R).
  static Lof fixed(const Vec3& p_GL, const Mat3& R_GL);
  /// Spin about unit axis (G) through p_GL at speed profile omega(t) through
  /// (times, speeds); a single point means constant speed. theta(0) = theta0.
  static Lof spin(const Vec3& p_GL, const Mat3& R_GL0, const Vec3& axis_G, double theta0,
                  std::vector<double> times, std::vector<double> speeds);
  /// Tracking frame starting at (p, R) with velocity v and angular velocity w (G),
  /// re-anchored every `interval` seconds.
  static Lof tracking(const Vec3& p_GL, const Mat3& R_GL, const Vec3& v_GL, const Vec3& w_GL_G,
                      double interval);

  /// Uniform linear acceleration of the origin (fixed and spin kinds only).
  void set_origin_motion(const Vec3& v0, const Vec3& a0);

  LofKind kind() const { return kind_; }
  LofState at(double t) const;
  double interval() const { return interval_; }
  /// Knot times of the speed profile (integrators should stop there).
  const std::vector<double>& knots() const { return profile_.times(); }
  /// The spin's speed over time (spin kind; constant 0 otherwise).
  const SpeedProfile& speed_profile() const { return profile_; }
  /// Spin angle theta(t) about the axis [rad] (0 for other kinds).
  double spin_angle(double t) const;
  double spin_speed(double t) const;
  double spin_acceleration(double t) const;
  const Vec3& axis() const { return axis_; }

  /// Tracking only: move the frame to a new anchor state at time t.
  void reanchor(double t, const LofState& s);

 private:
  LofKind kind_ = LofKind::Fixed;
  Vec3 p0_ = Vec3::Zero(), v0_ = Vec3::Zero(), a0_ = Vec3::Zero();
  Mat3 R0_ = Mat3::Identity();
  Vec3 axis_ = Vec3::UnitZ();
  double theta0_ = 0.0;
  SpeedProfile profile_;
  // tracking
  double t_anchor_ = 0.0, interval_ = 0.0;
  Vec3 w0_ = Vec3::Zero(), psi_anchor_ = Vec3::Zero();
  Mat3 R_init_ = Mat3::Identity();
};

}  // namespace evas
