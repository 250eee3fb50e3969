// Test-only Problem: n uncoupled damped oscillators with optional harmonic forcing,
//     qdd_i + 2 zeta_i w_i qd_i + w_i^2 q_i = F_i cos(W_i t),
// i.e. f_i(t, q, v) = 2 zeta_i w_i v_i + w_i^2 q_i - F_i cos(W_i t), with the
// closed-form solution of the damped harmonic oscillator (e.g. S. S. Rao,
// Mechanical Vibrations, free damped response + steady-state harmonic response):
//     q(t) = qp(t) + exp(-zeta w tau) (A cos(wd tau) + B sin(wd tau)),  tau = t - t0,
//     wd = w sqrt(1 - zeta^2),  A = q0 - qp(t0),  B = (v0 - vp(t0) + zeta w A)/wd,
//     qp(t) = Xc cos(W t) + Xs sin(W t),  D = (w^2 - W^2)^2 + (2 zeta w W)^2,
//     Xc = F (w^2 - W^2)/D,  Xs = 2 zeta w W F/D        (zeta < 1).
//
// body_part = true: the oscillators' own terms are the "body" part
// (body_operator returns KB = diag(w^2), CB = diag(2 zeta w)); body_part =
// false: everything is an "element" load and body_operator gives zeros, so the
// linear-acceleration method runs its pure fixed-point path.
//
// Optional stops: at each stop time the velocity may be kicked by a given vector
// (at_stop then returns true); the exact solution follows the kicks.
// Standalone on purpose: depends only on solver/problem.h.
#pragma once

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "model/problem.h"

namespace evas {
namespace test {

struct Oscillator {
  double omega = 1.0;       // natural frequency w [rad/s]
  double zeta = 0.0;        // damping ratio, < 1
  double force = 0.0;       // forcing amplitude F per unit mass [m/s^2]
  double force_freq = 0.0;  // forcing frequency W [rad/s]
  double q0 = 0.0, v0 = 0.0;
};

struct Stop {
  double t = 0.0;
  std::vector<double> kick;  // added to v at the stop (empty: state unchanged)
};

/// Closed-form state at t of one oscillator that was at (q0, v0) at t0.
inline void oscillator_solution(const Oscillator& o, double t0, double q0, double v0, double t,
                                double& q, double& v) {
  const double w = o.omega, z = o.zeta, W = o.force_freq, F = o.force;
  double Xc = 0.0, Xs = 0.0;
  if (F != 0.0) {
    const double D = (w * w - W * W) * (w * w - W * W) + (2 * z * w * W) * (2 * z * w * W);
    Xc = F * (w * w - W * W) / D;
    Xs = 2 * z * w * W * F / D;
  }
  auto qp = [&](double s) { return Xc * std::cos(W * s) + Xs * std::sin(W * s); };
  auto vp = [&](double s) { return W * (-Xc * std::sin(W * s) + Xs * std::cos(W * s)); };
  const double wd = w * std::sqrt(1.0 - z * z);
  const double A = q0 - qp(t0);
  const double B = (v0 - vp(t0) + z * w * A) / wd;
  const double tau = t - t0;
  const double e = std::exp(-z * w * tau), c = std::cos(wd * tau), s = std::sin(wd * tau);
  q = qp(t) + e * (A * c + B * s);
  v = vp(t) + e * ((-z * w * A + wd * B) * c + (-z * w * B - wd * A) * s);
}

/// The standard set: 1 Hz lightly damped free; 3 Hz damped and forced at 1.7 Hz; 0.5 Hz undamped.
inline std::vector<Oscillator> oscillators(std::size_t count = 3) {
  Oscillator a;
  a.omega = 2 * M_PI * 1.0;
  a.zeta = 0.05;
  a.q0 = 1.0;
  Oscillator b;
  b.omega = 2 * M_PI * 3.0;
  b.zeta = 0.2;
  b.force = 10.0;
  b.force_freq = 2 * M_PI * 1.7;
  b.v0 = 0.5;
  Oscillator c;
  c.omega = 2 * M_PI * 0.5;
  c.q0 = -0.3;
  c.v0 = 1.0;
  std::vector<Oscillator> all = {a, b, c};
  all.resize(count);
  return all;
}

class SdofProblem : public Problem {
 public:
  explicit SdofProblem(std::vector<Oscillator> osc, bool body_part = true,
                       std::vector<Stop> stops = {})
      : osc_(std::move(osc)), body_part_(body_part), stops_(std::move(stops)) {
    const int n = size();
    std::vector<Triplet> trip;
    for (int i = 0; i < n; ++i) trip.emplace_back(i, i, 0.0);
    pattern_.resize(n, n);
    pattern_.setFromTriplets(trip.begin(), trip.end());
    pattern_.makeCompressed();
  }

  int size() const override { return static_cast<int>(osc_.size()); }

  void initial_state(Vec& q, Vec& v) const override {
    q.resize(size());
    v.resize(size());
    for (int i = 0; i < size(); ++i) {
      q[i] = osc_[static_cast<std::size_t>(i)].q0;
      v[i] = osc_[static_cast<std::size_t>(i)].v0;
    }
  }

  void force(double t, const double* q, const double* v, double* f) override {
    ++counters.f_evals;
    for (int i = 0; i < size(); ++i) {
      const Oscillator& o = osc_[static_cast<std::size_t>(i)];
      f[i] = 2 * o.zeta * o.omega * v[i] + o.omega * o.omega * q[i] -
             o.force * std::cos(o.force_freq * t);
    }
  }

  void force_jacobian(double, const double*, const double*, SpMat& K, SpMat& C) override {
    ++counters.jac_evals;
    for (int i = 0; i < size(); ++i) {
      const Oscillator& o = osc_[static_cast<std::size_t>(i)];
      K.valuePtr()[i] = o.omega * o.omega;  // diagonal pattern: value i is (i, i)
      C.valuePtr()[i] = 2 * o.zeta * o.omega;
    }
  }

  const SpMat& jacobian_pattern() const override { return pattern_; }

  void body_operator(double t, SpMat& KB, SpMat& CB) override {
    if (!body_part_) {
      Problem::body_operator(t, KB, CB);
      return;
    }
    for (int i = 0; i < size(); ++i) {
      const Oscillator& o = osc_[static_cast<std::size_t>(i)];
      KB.valuePtr()[i] = o.omega * o.omega;
      CB.valuePtr()[i] = 2 * o.zeta * o.omega;
    }
  }

  double next_stop(double t) const override {
    for (const Stop& s : stops_)
      if (s.t > t) return s.t;
    return Problem::next_stop(t);
  }

  bool at_stop(double t, double* /*q*/, double* v) override {
    landed.push_back(t);
    for (const Stop& s : stops_) {
      if (s.t != t || s.kick.empty()) continue;
      for (int i = 0; i < size(); ++i) v[i] += s.kick[static_cast<std::size_t>(i)];
      return true;
    }
    return false;
  }

  std::string describe_state(double t, const double* q, const double* v) const override {
    std::ostringstream os;
    os << "sdof problem at t = " << t << " s:";
    for (int i = 0; i < size(); ++i)
      os << " q" << i << " = " << q[i] << ", v" << i << " = " << v[i];
    return os.str();
  }

  /// Exact state at t (stops with kicks strictly before t are applied).
  void exact(double t, Vec& q, Vec& v) const {
    q.resize(size());
    v.resize(size());
    for (int i = 0; i < size(); ++i) {
      const Oscillator& o = osc_[static_cast<std::size_t>(i)];
      double t0 = 0.0, q0 = o.q0, v0 = o.v0;
      for (const Stop& s : stops_) {
        if (!(s.t < t)) break;
        oscillator_solution(o, t0, q0, v0, s.t, q0, v0);
        if (!s.kick.empty()) v0 += s.kick[static_cast<std::size_t>(i)];
        t0 = s.t;
      }
      oscillator_solution(o, t0, q0, v0, t, q[i], v[i]);
    }
  }

  std::vector<double> landed;  // times at_stop was called with

 private:
  std::vector<Oscillator> osc_;
  bool body_part_;
  std::vector<Stop> stops_;
  SpMat pattern_;
};

// A mass matrix without constraints runs through the DAE residual
// [q' - v; M v' + f]: the oscillators with every equation multiplied by a
// mass (M = diag(m_i), f_i = m_i (2 zeta w v + w^2 q - F cos W t)) have the
// same closed-form solution (sdof_problem.h).
class MassSdof : public test::SdofProblem {
 public:
  explicit MassSdof(std::vector<test::Oscillator> osc) : SdofProblem(std::move(osc)) {
    mass_ = jacobian_pattern();
  }
  bool has_mass() const override { return true; }
  const SpMat& mass_pattern() const override { return mass_; }
  void mass(double, const double*, SpMat& M) override {
    for (int i = 0; i < size(); ++i) M.valuePtr()[i] = weight(i);  // diagonal pattern
  }
  void force(double t, const double* q, const double* v, double* f) override {
    SdofProblem::force(t, q, v, f);
    for (int i = 0; i < size(); ++i) f[i] *= weight(i);
  }
  void force_jacobian(double t, const double* q, const double* v, SpMat& K, SpMat& C) override {
    SdofProblem::force_jacobian(t, q, v, K, C);
    for (int i = 0; i < size(); ++i) {
      K.valuePtr()[i] *= weight(i);
      C.valuePtr()[i] *= weight(i);
    }
  }

 private:
  static double weight(int i) { return 0.5 + 2.0 * i; }
  SpMat mass_;
};

// An SdofProblem whose model refuses the first `times` trial states past
// t_refuse, as a film that closes on a Newton iterate: a RangeError (the
// integrator cuts the step or retries), or with `fatal` a plain RunError (the
// run ends).
class RefusingSdof : public SdofProblem {
 public:
  RefusingSdof(std::vector<Oscillator> osc, double t_refuse, int times = 1, bool fatal = false)
      : SdofProblem(std::move(osc)), t_refuse_(t_refuse), left_(times), fatal_(fatal) {}
  void force(double t, const double* q, const double* v, double* f) override {
    if (left_ > 0 && t > t_refuse_) {
      refused = true;
      --left_;
      if (fatal_) throw RunError("element 'film': broken");
      throw RangeError("element 'film': film closed on a trial state");
    }
    SdofProblem::force(t, q, v, f);
  }
  bool refused = false;

 private:
  double t_refuse_;
  int left_;
  bool fatal_;
};

}  // namespace test
}  // namespace evas
