#include "elements/motor.h"

#include <cmath>

namespace evas {

Motor::Motor(std::string name, std::vector<int> markers, const Vec3& axis, double speed,
             double theta0, double K_r, double C_r, double K_c, double C_c)
    : Element(std::move(name), std::move(markers)),
      drive_(speed),
      th0_(theta0),
      K_(K_r),
      C_(C_r),
      Kc_(K_c),
      Cc_(C_c),
      disk_(K_c > 0.0) {
  const std::string where = "motor '" + this->name() + "'";
  if (this->markers().size() != 2) throw InputError(where + ": needs 2 markers (clutch, stator)");
  if (!(axis.norm() > 0) || !axis.allFinite())
    throw InputError(where + ": axis must be a non-zero vector");
  if (!(K_r >= 0 && C_r >= 0))
    throw InputError(where + ": stiffness and damping must not be negative");
  if (!(K_c >= 0 && C_c >= 0))
    throw InputError(where + ": clutch_stiffness and clutch_damping must not be negative");
  if (C_c > 0 && K_c == 0)
    throw InputError(where + ": clutch_damping is given without clutch_stiffness");
  if (disk_ && !(C_r + C_c > 0))
    throw InputError(where +
                     ": a massless clutch disk needs damping on one side (damping or "
                     "clutch_damping > 0), else its speed is not determined");
  a_ = axis.normalized();
}

void Motor::internal_initial(double t, const MarkerMotion* m, double* z) const {
  const double th1 = drive_.profile().angle_plus(t, th0_);
  const double th2 = a_.dot(m[0].psi - m[1].psi);
  const double th2d = a_.dot(m[0].w - m[1].w);
  // the disk turning with the crank (omega_d = theta_2_dot) and passing the
  // dynamometer's torque on: K_c (th_d - th2) = K_r (th1 - th_d) + C_r (w - th2d)
  z[0] = (K_ * th1 + C_ * (drive_.profile().speed(t) - th2d) + Kc_ * th2) / (K_ + Kc_);
  // 0 = K_r (th1 - th_d) + C_r (w - om_d) - K_c (th_d - th2) - C_c (om_d - th2d)
  z[1] = (K_ * (th1 - z[0]) + C_ * drive_.profile().speed(t) - Kc_ * (z[0] - th2) + Cc_ * th2d) /
         (C_ + Cc_);
}

double Motor::clutch_torque(const MarkerMotion* m, const double* z) const {
  const double th2 = a_.dot(m[0].psi - m[1].psi);
  const double th2d = a_.dot(m[0].w - m[1].w);
  return Kc_ * (z[0] - th2) + Cc_ * (z[1] - th2d);
}

void Motor::evaluate_z(double t, const MarkerMotion* m, const double* z, MarkerLoad* loads) const {
  if (!disk_) {
    evaluate(t, m, loads);
    return;
  }
  const double T = clutch_torque(m, z);
  loads[0].F.setZero();
  loads[0].M = T * a_;
  loads[1].F.setZero();
  loads[1].M = -T * a_;
}

void Motor::internal_rate(double t, const MarkerMotion* m, const double* z, double* h) const {
  h[0] = z[1];
  h[1] = K_ * (drive_.profile().angle_plus(t, th0_) - z[0]) +
         C_ * (drive_.profile().speed(t) - z[1]) - clutch_torque(m, z);
}

void Motor::internal_derivatives(double, const MarkerMotion*, const double*, Mat& Dz, Mat& Hm,
                                 Mat& Hz) const {
  Dz.setZero();
  Hm.setZero();
  Dz.block<3, 1>(3, 0) = Kc_ * a_;  // M_0 = T_c a
  Dz.block<3, 1>(3, 1) = Cc_ * a_;
  Dz.block<3, 2>(9, 0) = -Dz.block<3, 2>(3, 0);
  // h_1 = ... - K_c (th_d - a.(psi_0 - psi_1)) - C_c (om_d - a.(w_0 - w_1))
  Hm.block<1, 3>(1, 6) = Kc_ * a_.transpose();
  Hm.block<1, 3>(1, 9) = Cc_ * a_.transpose();
  Hm.block<1, 3>(1, 18) = -Kc_ * a_.transpose();
  Hm.block<1, 3>(1, 21) = -Cc_ * a_.transpose();
  Hz << 0.0, 1.0, -(K_ + Kc_), -(C_ + Cc_);
}

void Motor::torque(double t, const MarkerMotion* m, double& twist, double& T) const {
  const double th1 = drive_.profile().angle_plus(t, th0_);
  const double th2 = a_.dot(m[0].psi - m[1].psi);
  const double th2d = a_.dot(m[0].w - m[1].w);
  twist = th2 - th1;
  if (disk_) {
    double z[2];
    internal_initial(t, m, z);
    T = clutch_torque(m, z);
    return;
  }
  T = -K_ * twist - C_ * (th2d - drive_.profile().speed(t));
}

void Motor::spring_damper_rows(double k, double c, Mat& D) const {
  // Rows (F0, M0, F1, M1); columns per marker (p, v, psi, w).
  D.setZero();
  const Mat3 aa = a_ * a_.transpose();
  for (int j = 0; j < 2; ++j) {
    const double s = j == 0 ? 1.0 : -1.0;  // d(theta_2)/d(psi_j) = s a^T
    D.block<3, 3>(3, 12 * j + 6) = -s * k * aa;
    D.block<3, 3>(3, 12 * j + 9) = -s * c * aa;
    D.block<3, 3>(9, 12 * j + 6) = s * k * aa;
    D.block<3, 3>(9, 12 * j + 9) = s * c * aa;
  }
}

void Motor::derivatives_z(double t, const MarkerMotion* m, const double* z, Mat& D) const {
  if (!disk_) {
    derivatives(t, m, D);
    return;
  }
  (void)z;
  spring_damper_rows(Kc_, Cc_, D);
}

void Motor::channel_values_z(double t, const MarkerMotion* m, const double* z, double* out) const {
  double twist, T;
  torque(t, m, twist, T);
  out[0] = disk_ ? clutch_torque(m, z) : T;
  out[1] = twist;
  if (!disk_) return;
  out[2] = z[0] - (drive_.profile().angle_plus(t, th0_));
  out[3] = z[1];
}

void Motor::evaluate(double t, const MarkerMotion* m, MarkerLoad* loads) const {
  double twist, T;
  torque(t, m, twist, T);
  loads[0].F.setZero();
  loads[0].M = T * a_;
  loads[1].F.setZero();
  loads[1].M = -T * a_;
}

void Motor::derivatives(double t, const MarkerMotion* m, Mat& D) const {
  if (disk_) {  // the quasi-static disk (torque()): differences of evaluate()
    derivatives_fd(t, m, D);
    return;
  }
  spring_damper_rows(K_, C_, D);
}

std::vector<Channel> Motor::channels() const {
  if (disk_)
    return {{"torque", "N m"}, {"twist", "rad"}, {"disk_angle", "rad"}, {"disk_speed", "rad/s"}};
  return {{"torque", "N m"}, {"twist", "rad"}};
}

void Motor::channel_values(double t, const MarkerMotion* m, double* out) const {
  double z[2] = {0.0, 0.0};
  if (disk_) internal_initial(t, m, z);
  channel_values_z(t, m, z, out);
}

ElementType motor_element_type() {
  ElementType t;
  t.type = "motor";
  t.doc =
      "Dynamometer drive (paper Fig. 7, Eqs. 4-5). Driver angle theta_1 = speed t + "
      "initial_angle (without its own speed: the integral of the crank's speed w(t)); torque T = "
      "-K_r (theta_2 - theta_1) - C_r (theta_2_dot - speed) on the "
      "clutch marker (marker 1) about axis, with theta_2 = axis . (psi_clutch - psi_stator); "
      "the reaction -T acts on the stator marker (marker 2, usually ground).";
  t.num_markers = 2;
  ParamSpec axis;
  axis.key = "axis";
  axis.kind = ParamSpec::Kind::Vector3;
  axis.unit = "-";
  axis.doc = "rotation axis in G components (normalised; positive rotation right-handed)";
  axis.default_value = {1.0, 0.0, 0.0};
  t.params = {
      axis,
      scalar_param("speed", "rad/s",
                   "driver speed w (3000 rpm = 314.159 rad/s); omitted: the crank's (the body "
                   "with a spin LOF), constant or a profile",
                   false, 0, -1e300),
      scalar_param("initial_angle", "deg", "driver angle theta_0 at t = 0", false, 0, -1e300),
      scalar_param("stiffness", "N m/rad", "torsional clutch spring K_r", true, 0, 0.0),
      scalar_param("damping", "N m s/rad", "torsional damping C_r", false, 0, 0.0),
      scalar_param("clutch_stiffness", "N m/rad",
                   "clutch spring K_c between a massless clutch disk and the clutch marker (0: "
                   "no disk, the paper's Eq. 5); the disk's angle is a differential, its speed an "
                   "algebraic internal state",
                   false, 0, 0.0),
      scalar_param("clutch_damping", "N m s/rad", "clutch damping C_c (with clutch_stiffness)",
                   false, 0, 0.0)};
  t.make = [](const std::string& name, const std::vector<int>& markers, const ParamValues& v) {
    auto e = std::make_unique<Motor>(name, markers, v.vec3("axis"), v.scalar("speed"),
                                     v.scalar("initial_angle") * M_PI / 180.0,
                                     v.scalar("stiffness"), v.scalar("damping"),
                                     v.scalar("clutch_stiffness"), v.scalar("clutch_damping"));
    if (!v.given("speed")) e->leave_speed_to_crank();
    return e;
  };
  return t;
}

}  // namespace evas
