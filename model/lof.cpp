#include "model/lof.h"

#include <algorithm>
#include <cmath>

namespace evas {

Lof Lof::fixed(const Vec3& p_GL, const Mat3& R_GL) {
  Lof f;
  f.kind_ = LofKind::Fixed;
  f.p0_ = p_GL;
  f.R0_ = R_GL;
  return f;
}

Lof Lof::spin(const Vec3& p_GL, const Mat3& R_GL0, const Vec3& axis_G, double theta0,
              std::vector<double> times, std::vector<double> speeds) {
  if (!(axis_G.norm() > 0.0)) throw InputError("spin LOF: axis must be non-zero");
  Lof f;
  f.kind_ = LofKind::Spin;
  f.p0_ = p_GL;
  f.R0_ = R_GL0;
  f.axis_ = axis_G.normalized();
  f.theta0_ = theta0;
  try {
    f.profile_ = SpeedProfile(std::move(times), std::move(speeds));
  } catch (const InputError& e) {
    throw InputError(std::string("spin LOF: ") + e.what());
  }
  return f;
}

Lof Lof::tracking(const Vec3& p_GL, const Mat3& R_GL, const Vec3& v_GL, const Vec3& w_GL_G,
                  double interval) {
  if (!(interval > 0.0)) throw InputError("tracking LOF: interval must be > 0");
  Lof f;
  f.kind_ = LofKind::Tracking;
  f.p0_ = p_GL;
  f.R0_ = R_GL;
  f.R_init_ = R_GL;
  f.v0_ = v_GL;
  f.w0_ = w_GL_G;
  f.interval_ = interval;
  return f;
}

void Lof::set_origin_motion(const Vec3& v0, const Vec3& a0) {
  if (kind_ == LofKind::Tracking)
    throw InputError(
        "tracking LOF: the origin motion follows the body; velocity/acceleration "
        "cannot be prescribed");
  v0_ = v0;
  a0_ = a0;
}

double Lof::spin_speed(double t) const { return kind_ == LofKind::Spin ? profile_.speed(t) : 0.0; }

double Lof::spin_acceleration(double t) const {
  return kind_ == LofKind::Spin ? profile_.acceleration(t) : 0.0;
}

double Lof::spin_angle(double t) const {
  if (kind_ != LofKind::Spin) return 0.0;
  return theta0_ + profile_.integral(t) - profile_.integral(0.0);
}

LofState Lof::at(double t) const {
  LofState s;
  switch (kind_) {
    case LofKind::Fixed:
    case LofKind::Spin: {
      s.p_GL = p0_ + v0_ * t + 0.5 * a0_ * t * t;
      s.v_GL = v0_ + a0_ * t;
      s.a_GL = a0_;
      if (kind_ == LofKind::Spin) {
        const double th = spin_angle(t);
        const double w = spin_speed(t);
        const double al = spin_acceleration(t);
        s.R_GL = Eigen::AngleAxisd(th, axis_).toRotationMatrix() * R0_;
        s.w_GL_G = w * axis_;
        s.al_GL_G = al * axis_;
        s.psi_G = th * axis_;
      } else {
        s.R_GL = R0_;
      }
      break;
    }
    case LofKind::Tracking: {
      const double dt = t - t_anchor_;
      s.p_GL = p0_ + v0_ * dt;
      s.v_GL = v0_;
      s.R_GL = rotation_from_vector(w0_ * dt) * R0_;
      s.w_GL_G = w0_;
      s.psi_G = psi_anchor_ + w0_ * dt;
      break;
    }
  }
  return s;
}

void Lof::reanchor(double t, const LofState& s) {
  if (kind_ != LofKind::Tracking) throw std::logic_error("reanchor on a non-tracking LOF");
  t_anchor_ = t;
  p0_ = s.p_GL;
  v0_ = s.v_GL;
  R0_ = s.R_GL;
  w0_ = s.w_GL_G;
  psi_anchor_ = s.psi_G;
}

}  // namespace evas
