// Motor element (paper Fig. 7, Eqs. 4-5): a dynamometer drives the clutch
// through a torsional spring-damper.
//
// Disk 1 (driver) turns at the prescribed angle theta_1 = w t + theta_0 (Eq. 4);
// disk 2 (the clutch) is marker 0, whose rotation about the unit axis a (G
// components) is read relative to marker 1, the dynamometer's stator (usually a
// ground marker):
//   theta_2 = a . (psi_0 - psi_1),   theta_2_dot = a . (w_0 - w_1)
//   T = -K_r (theta_2 - theta_1) - C_r (theta_2_dot - w)            (Eq. 5)
// Loads: M_0 = T a on the clutch marker, M_1 = -T a on the stator marker
// (ignored when it is on the ground); no forces. psi is the marker's rotation
// vector (LOF spin angle plus small modal rotation), so theta_2 includes the
// crankshaft's spin; theta_0 should match the crank LOF's initial angle.
// With w = 0 and theta_0 = 0 and a free body on marker 1, the element is a plain
// torsional spring-damper between two markers.
// Derivatives (analytic, constant):
//   dM_0/dpsi_0 = -K_r a a^T, dM_0/dw_0 = -C_r a a^T, opposite signs for marker 1.
#pragma once

#include "elements/element.h"
#include "elements/registry.h"

namespace evas {

class Motor : public Element {
 public:
  /// The twist is read from both markers' rotation about the axis.
  bool needs_rotation(std::size_t) const override { return true; }
  /// axis: any non-zero vector (normalised); speed [rad/s]; theta0 [rad].
  Motor(std::string name, std::vector<int> markers, const Vec3& axis, double speed, double theta0,
        double K_r, double C_r);
  std::string type() const override { return "motor"; }
  void evaluate(double t, const MarkerMotion* m, MarkerLoad* loads) const override;
  void derivatives(double t, const MarkerMotion* m, Mat& D) const override;
  std::vector<Channel> channels() const override;
  void channel_values(double t, const MarkerMotion* m, double* out) const override;

  /// Twist theta_2 - theta_1 [rad] and clutch torque T [N m] at (t, motion).
  void torque(double t, const MarkerMotion* m, double& twist, double& T) const;

 private:
  Vec3 a_;
  double w_, th0_, K_, C_;
};

/// Declaration for the registry ("motor").
ElementType motor_element_type();

}  // namespace evas
