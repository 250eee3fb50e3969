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
  const std::size_t K = f.times_.size();
  // Fritsch-Carlson slopes: zero at the ends and at local extrema, harmonic mean elsewhere.
  f.slopes_.assign(K, 0.0);
  for (std::size_t i = 1; i + 1 < K; ++i) {
    const double d0 = (f.speeds_[i] - f.speeds_[i - 1]) / (f.times_[i] - f.times_[i - 1]);
    const double d1 = (f.speeds_[i + 1] - f.speeds_[i]) / (f.times_[i + 1] - f.times_[i]);
    if (d0 * d1 > 0.0) f.slopes_[i] = 2.0 / (1.0 / d0 + 1.0 / d1);
  }
  f.angles_.assign(K, 0.0);
  for (std::size_t i = 1; i < K; ++i) {
    const double h = f.times_[i] - f.times_[i - 1];
    // integral of the cubic Hermite segment over its whole length
    f.angles_[i] = f.angles_[i - 1] + h * (0.5 * (f.speeds_[i - 1] + f.speeds_[i]) +
                                           h * (f.slopes_[i - 1] - f.slopes_[i]) / 12.0);
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

namespace {
// Segment k of a profile containing t (times[k] <= t < times[k+1]) and s in [0, 1].
std::size_t segment(const std::vector<double>& T, double t, double& s) {
  const std::size_t k = std::upper_bound(T.begin(), T.end(), t) - T.begin() - 1;
  s = (t - T[k]) / (T[k + 1] - T[k]);
  return k;
}
}  // namespace

double Lof::speed_integral(double t) const {
  const auto& T = times_;
  if (t <= T.front()) return speeds_.front() * (t - T.front());
  if (t >= T.back()) return angles_.back() + speeds_.back() * (t - T.back());
  double x;
  const std::size_t k = segment(T, t, x);
  const double h = T[k + 1] - T[k], x2 = x * x, x3 = x2 * x, x4 = x3 * x;
  // integrals of the Hermite basis h00, h10, h01, h11 over [0, x]
  const double i00 = 0.5 * x4 - x3 + x, i10 = 0.25 * x4 - 2.0 * x3 / 3.0 + 0.5 * x2;
  const double i01 = -0.5 * x4 + x3, i11 = 0.25 * x4 - x3 / 3.0;
  return angles_[k] + h * (i00 * speeds_[k] + i10 * h * slopes_[k] + i01 * speeds_[k + 1] +
                           i11 * h * slopes_[k + 1]);
}

double Lof::spin_speed(double t) const {
  if (kind_ != LofKind::Spin) return 0.0;
  if (t <= times_.front()) return speeds_.front();
  if (t >= times_.back()) return speeds_.back();
  double x;
  const std::size_t k = segment(times_, t, x);
  const double h = times_[k + 1] - times_[k], x2 = x * x, x3 = x2 * x;
  return (2 * x3 - 3 * x2 + 1) * speeds_[k] + (x3 - 2 * x2 + x) * h * slopes_[k] +
         (-2 * x3 + 3 * x2) * speeds_[k + 1] + (x3 - x2) * h * slopes_[k + 1];
}

double Lof::spin_acceleration(double t) const {
  if (kind_ != LofKind::Spin || t <= times_.front() || t >= times_.back()) return 0.0;
  double x;
  const std::size_t k = segment(times_, t, x);
  const double h = times_[k + 1] - times_[k], x2 = x * x;
  return ((6 * x2 - 6 * x) * speeds_[k] + (3 * x2 - 4 * x + 1) * h * slopes_[k] +
          (-6 * x2 + 6 * x) * speeds_[k + 1] + (3 * x2 - 2 * x) * h * slopes_[k + 1]) /
         h;
}

double Lof::spin_angle(double t) const {
  if (kind_ != LofKind::Spin) return 0.0;
  return theta0_ + speed_integral(t) - speed_integral(0.0);
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
