#include "elements/motor.h"

#include <cmath>

namespace evas {

Motor::Motor(std::string name, std::vector<int> markers, const Vec3& axis, double speed,
             double theta0, double K_r, double C_r)
    : Element(std::move(name), std::move(markers)), w_(speed), th0_(theta0), K_(K_r), C_(C_r) {
  const std::string where = "motor '" + this->name() + "'";
  if (this->markers().size() != 2) throw InputError(where + ": needs 2 markers (clutch, stator)");
  if (!(axis.norm() > 0) || !axis.allFinite())
    throw InputError(where + ": axis must be a non-zero vector");
  if (!(K_r >= 0 && C_r >= 0))
    throw InputError(where + ": stiffness and damping must not be negative");
  a_ = axis.normalized();
}

void Motor::torque(double t, const MarkerMotion* m, double& twist, double& T) const {
  const double th1 = w_ * t + th0_;
  const double th2 = a_.dot(m[0].psi - m[1].psi);
  const double th2d = a_.dot(m[0].w - m[1].w);
  twist = th2 - th1;
  T = -K_ * twist - C_ * (th2d - w_);
}

void Motor::evaluate(double t, const MarkerMotion* m, MarkerLoad* loads) const {
  double twist, T;
  torque(t, m, twist, T);
  loads[0].F.setZero();
  loads[0].M = T * a_;
  loads[1].F.setZero();
  loads[1].M = -T * a_;
}

void Motor::derivatives(double, const MarkerMotion*, Mat& D) const {
  // Rows (F0, M0, F1, M1); columns per marker (p, v, psi, w).
  D.setZero();
  const Mat3 aa = a_ * a_.transpose();
  for (int j = 0; j < 2; ++j) {
    const double s = j == 0 ? 1.0 : -1.0;  // d(theta_2)/d(psi_j) = s a^T
    D.block<3, 3>(3, 12 * j + 6) = -s * K_ * aa;
    D.block<3, 3>(3, 12 * j + 9) = -s * C_ * aa;
    D.block<3, 3>(9, 12 * j + 6) = s * K_ * aa;
    D.block<3, 3>(9, 12 * j + 9) = s * C_ * aa;
  }
}

std::vector<Channel> Motor::channels() const { return {{"torque", "N m"}, {"twist", "rad"}}; }

void Motor::channel_values(double t, const MarkerMotion* m, double* out) const {
  double twist, T;
  torque(t, m, twist, T);
  out[0] = T;
  out[1] = twist;
}

ElementType motor_element_type() {
  ElementType t;
  t.type = "motor";
  t.doc =
      "Dynamometer drive (paper Fig. 7, Eqs. 4-5). Driver angle theta_1 = speed t + "
      "initial_angle; torque T = -K_r (theta_2 - theta_1) - C_r (theta_2_dot - speed) on the "
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
      scalar_param("speed", "rad/s", "driver speed w (3000 rpm = 314.159 rad/s)", true, 0, -1e300),
      scalar_param("initial_angle", "deg", "driver angle theta_0 at t = 0", false, 0, -1e300),
      scalar_param("stiffness", "N m/rad", "torsional clutch spring K_r", true, 0, 0.0),
      scalar_param("damping", "N m s/rad", "torsional damping C_r", false, 0, 0.0)};
  t.make = [](const std::string& name, const std::vector<int>& markers, const ParamValues& v) {
    return std::make_unique<Motor>(name, markers, v.vec3("axis"), v.scalar("speed"),
                                   v.scalar("initial_angle") * M_PI / 180.0, v.scalar("stiffness"),
                                   v.scalar("damping"));
  };
  return t;
}

}  // namespace evas
