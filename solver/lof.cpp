#include "solver/lof.h"

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
  if (times.empty() || times.size() != speeds.size())
    throw InputError("spin LOF: speed profile needs matching, non-empty time and speed lists");
  for (std::size_t i = 1; i < times.size(); ++i)
    if (!(times[i] > times[i - 1]))
      throw InputError("spin LOF: speed profile times must increase strictly");
  if (!(axis_G.norm() > 0.0)) throw InputError("spin LOF: axis must be non-zero");
  Lof f;
  f.kind_ = LofKind::Spin;
  f.p0_ = p_GL;
  f.R0_ = R_GL0;
  f.axis_ = axis_G.normalized();
  f.theta0_ = theta0;
  f.times_ = std::move(times);
  f.speeds_ = std::move(speeds);
  // angles_[i] = integral of omega from times_[0] to times_[i] (trapezoids: omega is linear)
  f.angles_.assign(f.times_.size(), 0.0);
  for (std::size_t i = 1; i < f.times_.size(); ++i)
    f.angles_[i] = f.angles_[i - 1] +
                   0.5 * (f.speeds_[i] + f.speeds_[i - 1]) * (f.times_[i] - f.times_[i - 1]);
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

namespace {
// Integral of the piecewise-linear speed from times[0] to t (constant outside).
double profile_integral(const std::vector<double>& T, const std::vector<double>& W,
                        const std::vector<double>& I, double t) {
  if (t <= T.front()) return W.front() * (t - T.front());
  if (t >= T.back()) return I.back() + W.back() * (t - T.back());
  const std::size_t k = std::upper_bound(T.begin(), T.end(), t) - T.begin() - 1;
  const double dt = t - T[k], h = T[k + 1] - T[k];
  const double slope = (W[k + 1] - W[k]) / h;
  return I[k] + W[k] * dt + 0.5 * slope * dt * dt;
}
}  // namespace

double Lof::spin_speed(double t) const {
  if (kind_ != LofKind::Spin) return 0.0;
  if (t <= times_.front()) return speeds_.front();
  if (t >= times_.back()) return speeds_.back();
  const std::size_t k = std::upper_bound(times_.begin(), times_.end(), t) - times_.begin() - 1;
  const double x = (t - times_[k]) / (times_[k + 1] - times_[k]);
  return speeds_[k] + x * (speeds_[k + 1] - speeds_[k]);
}

double Lof::spin_angle(double t) const {
  if (kind_ != LofKind::Spin) return 0.0;
  return theta0_ + profile_integral(times_, speeds_, angles_, t) -
         profile_integral(times_, speeds_, angles_, 0.0);
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
        double al = 0.0;
        if (t > times_.front() && t < times_.back()) {
          const std::size_t k =
              std::upper_bound(times_.begin(), times_.end(), t) - times_.begin() - 1;
          al = (speeds_[k + 1] - speeds_[k]) / (times_[k + 1] - times_[k]);
        }
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
