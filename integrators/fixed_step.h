// Private base of the fixed-step integrators (generalized-alpha,
// linear-acceleration): stepping to outputs and stops, dense output and
// restarts. A derived class implements only one step.
//
// advance(tout, land):
//   steps of settings.step; a step is never taken across the problem's next
//   stop, and when landing the last step is shortened to end exactly on tout
//   (the following step is of full length again). A step that would end within
//   1e-9 h of tout is stretched/shortened to end on tout, so outputs on the step
//   grid are step states, not interpolations.
//   Outputs between steps are cubic Hermite interpolants on the bracketing step
//   states: q from (q, v) at both ends, v from (v, a) at both ends. Both are
//   O(h^4) locally, so the second-order accuracy of the states is kept, and the
//   stepping itself is not disturbed.
// restart(t, q, v): a = -f(t, q, v) and continue.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "integrators/common.h"

namespace evas {

class FixedStepIntegrator : public Integrator {
 public:
  void init(Problem& p, double t0, const Vec& q0, const Vec& v0,
            const IntegratorSettings& s) override {
    if (!(s.step > 0.0) || !std::isfinite(s.step))
      throw InputError(name() + ": step must be > 0 (got " + format_number(s.step) + ")");
    if (s.max_iterations < 1) throw InputError(name() + ": max_iterations must be >= 1");
    p_ = &p;
    s_ = s;
    n_ = p.size();
    stats_ = IntegratorStats{};
    q_ = q0;
    v_ = v0;
    a_.resize(n_);
    f_.resize(n_);
    q1_.resize(n_);
    v1_.resize(n_);
    a1_.resize(n_);
    f1_.resize(n_);
    setup();
    start(t0);
  }

  void advance(double tout, bool land, Vec& q, Vec& v) override {
    WallTimer timer(stats_.wall_seconds);
    if (!p_) throw RunError(name() + ": advance() before init()");
    if (!(tout > tout_last_)) {
      throw RunError(name() + ": output time " + format_number(tout) + " s is not after " +
                     format_number(tout_last_) + " s");
    }
    const double h_nominal = s_.step;
    const double snap = 1e-9 * h_nominal;
    while (t_ < tout - snap) {
      // h stays bit-identical to settings.step unless the step is cut (so the
      // derived classes can keep their factorizations)
      double h = h_nominal;
      double t_end = t_ + h;
      const double stop = p_->next_stop(t_);  // never step across a stop
      if (stop < t_end + snap) {
        t_end = stop;
        h = t_end - t_;
      }
      if (t_end > tout - snap && (land || t_end < tout + snap)) {
        t_end = tout;
        h = t_end - t_;
      }
      step(t_, h);
      // the new state becomes current; the old one is kept for interpolation
      t_prev_ = t_;
      t_ = t_end;
      q_.swap(q1_);
      v_.swap(v1_);
      a_.swap(a1_);
      f_.swap(f1_);
      ++stats_.steps;
      stats_.last_step = h;
      note_step(stats_, h);
    }
    if (std::abs(t_ - tout) <= snap) {  // on a step (exactly, except for sub-1e-9 h slivers)
      q = q_;
      v = v_;
    } else {
      // t_prev_ < tout < t_: Hermite on the last step (q1_.. hold the previous state)
      interpolate(tout, q, v);
    }
    tout_last_ = tout;
  }

  void restart(double t, const Vec& q, const Vec& v) override {
    WallTimer timer(stats_.wall_seconds);
    ++stats_.restarts;
    q_ = q;
    v_ = v;
    start(t);
  }

  IntegratorStats stats() const override { return stats_; }

 protected:
  /// Called once per init() after the state vectors are sized.
  virtual void setup() = 0;
  /// One step from (t, q_, v_, a_, f_) to t + h, writing q1_, v1_, a1_ and
  /// f1_ (the force the method associates with the new state). Throws RunError.
  virtual void step(double t, double h) = 0;

  /// Current state (t_, q_, v_) with a_ = -f and f_ = f(t, q, v).
  void start(double t) {
    t_ = t;
    t_prev_ = t;
    tout_last_ = t;
    p_->force(t, q_.data(), v_.data(), f_.data());
    ++stats_.residual_evals;
    a_ = -f_;
  }

  /// "time, step, state" tail of a failure message.
  std::string where(double t, double h, const Vec& q, const Vec& v) const {
    return " at t = " + format_number(t) + " s, step h = " + format_number(h) +
           " s; state: " + p_->describe_state(t, q.data(), v.data());
  }

  Problem* p_ = nullptr;
  IntegratorSettings s_;
  int n_ = 0;
  IntegratorStats stats_;
  double t_ = 0.0;
  Vec q_, v_, a_, f_;      // state at t_
  Vec q1_, v1_, a1_, f1_;  // written by step(); after the swap: the state at t_prev_

 private:
  void interpolate(double t, Vec& q, Vec& v) const {
    const double h = t_ - t_prev_;
    const double s = (t - t_prev_) / h;
    const double s2 = s * s, s3 = s2 * s;
    const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s;
    const double h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
    // previous state lives in the *1_ vectors after the swap in advance()
    q = h00 * q1_ + h10 * h * v1_ + h01 * q_ + h11 * h * v_;
    v = h00 * v1_ + h10 * h * a1_ + h01 * v_ + h11 * h * a_;
  }

  double t_prev_ = 0.0;
  double tout_last_ = 0.0;
};

}  // namespace evas
