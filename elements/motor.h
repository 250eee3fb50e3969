// Motor element (paper Fig. 7, Eqs. 4-5): a dynamometer drives the clutch
// through a torsional spring-damper.
//
// Disk 1 (driver) turns at the prescribed angle theta_1 = w t + theta_0 (Eq. 4),
// or, without its own `speed`, follows the crank's speed profile w(t)
// (model/speed_profile.h): theta_1 = integral_0^t w + theta_0;
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
//
// Clutch disk (optional, beyond the paper): with clutch_stiffness K_c > 0 a
// massless disk sits between the dynamometer's spring-damper (K_r, C_r) and the
// clutch marker, joined to it by a clutch spring-damper (K_c, C_c). Its angle
// theta_d (relative to the stator) and speed omega_d are element internal
// states; having no inertia, the disk's torque balance replaces Newton's law
// and omega_d is an ALGEBRAIC variable (index 1 when C_r + C_c > 0):
//   theta_d' = omega_d
//   0 = K_r (theta_1 - theta_d) + C_r (w - omega_d) - T_c
//   T_c = K_c (theta_d - theta_2) + C_c (omega_d - theta_2_dot)   (torque on the crank)
// Loads: M_0 = T_c a, M_1 = -T_c a. The start (internal_initial) has the disk
// turning with the crank and passing the dynamometer's torque on:
//   theta_d = (K_r theta_1 + C_r (w - theta_2_dot) + K_c theta_2) / (K_r + K_c),
// omega_d from the balance (= theta_2_dot); the z-free evaluate() uses that
// quasi-static disk, whose torque is Eq. 5's times K_c / (K_r + K_c).
#pragma once

#include "elements/prescribed_speed.h"
#include "elements/registry.h"
#include "model/element.h"

namespace evas {

class Motor : public Element {
 public:
  /// The twist is read from both markers' rotation about the axis.
  bool needs_rotation(std::size_t) const override { return true; }
  unsigned motion_reads(std::size_t) const override { return kReadsRotation; }
  /// A torque about the axis on both markers, no force.
  unsigned load_parts(std::size_t) const override { return kLoadsMoment; }
  /// axis: any non-zero vector (normalised); speed [rad/s]; theta0 [rad].
  Motor(std::string name, std::vector<int> markers, const Vec3& axis, double speed, double theta0,
        double K_r, double C_r, double K_c = 0.0, double C_c = 0.0);
  std::string type() const override { return "motor"; }
  void evaluate(double t, const MarkerMotion* m, MarkerLoad* loads) const override;
  void derivatives(double t, const MarkerMotion* m, Mat& D) const override;
  std::vector<Channel> channels() const override;
  void channel_values(double t, const MarkerMotion* m, double* out) const override;

  /// The driver follows the crank's speed profile (the scene reader's
  /// follow_speed); until then the element reports wants_speed().
  void leave_speed_to_crank() { drive_.leave_to_crank(); }
  const SpeedProfile* own_speed() const override { return drive_.own(); }
  bool wants_speed() const override { return drive_.waiting(); }
  void follow_speed(const SpeedProfile& crank) override { drive_.follow(crank); }

  /// Twist theta_2 - theta_1 [rad] and clutch torque T [N m] at (t, motion)
  /// (with a clutch disk: at its quasi-static state).
  void torque(double t, const MarkerMotion* m, double& twist, double& T) const;

  // Clutch disk: states (theta_d, omega_d), the second algebraic.
  int internal_count() const override { return disk_ ? 2 : 0; }
  bool internal_algebraic(int i) const override { return i == 1; }
  std::string internal_name(int i) const override { return i == 0 ? "theta_d" : "omega_d"; }
  void internal_initial(double t, const MarkerMotion* m, double* z) const override;
  void evaluate_z(double t, const MarkerMotion* m, const double* z,
                  MarkerLoad* loads) const override;
  void derivatives_z(double t, const MarkerMotion* m, const double* z, Mat& D) const override;
  void channel_values_z(double t, const MarkerMotion* m, const double* z,
                        double* out) const override;
  void internal_rate(double t, const MarkerMotion* m, const double* z, double* h) const override;
  void internal_derivatives(double t, const MarkerMotion* m, const double* z, Mat& Dz, Mat& Hm,
                            Mat& Hz) const override;

 private:
  /// The clutch torque on the crank at disk states z.
  double clutch_torque(const MarkerMotion* m, const double* z) const;
  /// Spring-damper derivative rows of D for stiffness k, damping c.
  void spring_damper_rows(double k, double c, Mat& D) const;
  Vec3 a_;
  PrescribedSpeed drive_;  // driver angle turned since t = 0 and speed
  double th0_, K_, C_, Kc_, Cc_;
  bool disk_;
};

/// Declaration for the registry ("motor").
ElementType motor_element_type();

}  // namespace evas
