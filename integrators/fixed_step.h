// Base of the fixed-step integrators (generalized-alpha, linear-acceleration,
// radau) and public for plug-ins: stepping to outputs and stops, step
// control, dense output and restarts. A derived class implements one step
// (step()) and its local error estimate (local_error()); its steps are not
// capped at the output interval (outputs between steps are interpolated).
// The Newmark family on it: newmark.h, newmark_dae.h.
//
// advance(tout, land):
//   steps are never taken across the problem's next stop, and when landing the
//   last step is shortened to end exactly on tout. A step that would end within
//   1e-6 h of tout is stretched/shortened to end on tout, so outputs on the step
//   grid are step states, not interpolations.
//   Outputs between steps are cubic Hermite interpolants on the bracketing step
//   states: q from (q, v) at both ends, v from (v, a) at both ends. Both are
//   O(h^4) locally, so the second-order accuracy of the states is kept.
//
// Step control (settings.step_control):
//   fixed     steps of settings.step; a step whose iteration fails ends the run.
//   substep   steps of settings.step; a failed step is retried over the same
//             interval with sub-steps (halved after each failure, doubled again
//             after a success, never beyond the interval), counted in
//             stats.substeps; the run fails when a sub-step would fall below
//             settings.min_step. The step grid is the same as with `fixed`;
//             an output inside an interval in sub-steps is interpolated on the
//             sub-step that reaches it (the next call goes on from there).
//   adaptive  from settings.step, each step's local error estimate e (from the
//             derived class) is measured in the weighted RMS norm of SUNDIALS,
//             w_i = 1 / (rtol |y_i| + atol) over q and v; the step is accepted
//             when ||e_n|| <= 1. The next step is the PI controller's
//             h * clamp(0.9 ||e_n||^(-0.7/k) ||e_{n-1}||^(0.4/k), 0.2, 2), k =
//             error_order() (3 for the Newmark family: local error O(h^3); Gustafsson, Lundh &
//             Soederlind, BIT 28 (1988) 270-287; Hairer, Noersett & Wanner, Solving ODEs I, 2nd
//             ed., section II.4), ||e_{n-1}|| floored at 1e-4; on the first step after a start, and
//             for a rejected step (stats.error_test_failures, retried), the I controller's 0.9
//             ||e||^(-1/k); the step after a rejection does not grow. A step whose iteration fails
//             (stats.convergence_failures) is retried with h / 4. Bounded by
//             settings.min_step (failure) and settings.max_step. On the paper's
//             engine the I controller alone rejected 12 % of the steps (the
//             estimate follows the top modes' oscillation), the PI controller
//             0.3 % (docs/engine-speed.md).
// restart(t, q, v): a = -f(t, q, v) and continue.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include "dae/constraint_stats.h"
#include "dae/penalty.h"
#include "integrators/common.h"
#include "solver/quasi_static.h"

namespace evas {

class FixedStepIntegrator : public Integrator {
 public:
  void init(Problem& p, double t0, const Vec& q0, const Vec& v0,
            const IntegratorSettings& s) override {
    if (!(s.step > 0.0) || !std::isfinite(s.step))
      throw InputError(name() + ": step must be > 0 (got " + format_number(s.step) + ")");
    if (s.max_iterations < 1) throw InputError(name() + ": max_iterations must be >= 1");
    // the first step, min(step, max_step), must be one the step control may take
    if (s.step_control != StepControl::fixed) {
      if (s.max_step > 0.0 && s.max_step < s.min_step)
        throw InputError(name() + ": max_step = " + format_number(s.max_step) +
                         " s is below min_step = " + format_number(s.min_step) + " s");
      if (s.step < s.min_step)
        throw InputError(
            name() + ": step = " + format_number(s.step) +
            " s is below min_step = " + format_number(s.min_step) + " s (" +
            (s.step_control == StepControl::adaptive ? "the first step" : "the fixed step") +
            " must be one the step control may take)");
    }
    // Constraints: in the integrator's own form where it has one
    // (takes_constraints), else only as the penalty ODE (dae/penalty.h).
    base_ = &p;
    penalty_.reset();
    Problem* model = &p;
    const bool own = takes_constraints(s);
    if (const int m = p.constraint_count(); m > 0 && !own) {
      if (s.formulation != "penalty")
        throw InputError(name() + ": the problem has " + std::to_string(m) +
                         " constraint equation(s) (first: '" + p.constraint_name(0) + "'); " +
                         name() + " solves constrained problems as " + constraint_forms() +
                         ", not as formulation=" + s.formulation +
                         " (use ida for the index-2, ggl and index-1 formulations)");
      penalty_ = std::make_unique<dae::PenaltyProblem>(p, s.penalty_stiffness, s.penalty_damping);
      model = penalty_.get();
    }
    if (model->has_mass() && !own)
      throw InputError(name() + ": the problem has a mass matrix (M != I), which " + name() +
                       " takes only as " + constraint_forms() + "; use ida");
    p_ = model;
    s_ = s;
    n_ = p.size();
    stats_ = IntegratorStats{};
    q_ = q0;
    v_ = v0;
    require_quasi_static_support(*this, *p_);
    settle_quasi_static(*p_, t0, q_, v_);  // (nothing without quasi-static modes)
    a_.resize(n_);
    f_.resize(n_);
    q1_.resize(n_);
    v1_.resize(n_);
    a1_.resize(n_);
    f1_.resize(n_);
    a_prev_.resize(n_);
    h_ = s.step;
    if (s.max_step > 0.0) h_ = std::min(h_, s.max_step);
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
    const bool adaptive = s_.step_control == StepControl::adaptive;
    while (true) {
      // h stays bit-identical to settings.step unless the step is cut (so the
      // derived classes can keep their factorizations)
      const double h_plan = adaptive ? h_ : s_.step;
      const double snap = 1e-6 * h_plan;
      if (!(t_ < tout - snap)) break;
      double h = h_plan;
      double t_end = t_ + h;
      const double stop = p_->next_stop(t_);  // never step across a stop
      if (stop < t_end + snap) t_end = stop;
      if (t_end > tout - snap && (land || t_end < tout + snap)) t_end = tout;
      h = t_end - t_;
      // shortened for a stop or an output (not by the round-off of t_end - t_,
      // which left an adaptive step stuck at a small size: it never grew)
      const bool cut = h < h_plan - snap;
      if (!adaptive) {
        take_interval(h, tout);
        continue;
      }
      if (h < s_.min_step && cut) {  // a sliver before a stop or output: take it as it is
        if (!try_step(h)) fail_below_min_step(h);
        accept(h);
        continue;
      }
      if (!try_step(h)) {
        ++stats_.convergence_failures;
        rejected_ = true;
        h_ = 0.25 * h;
        if (h_ < s_.min_step) fail_below_min_step(h_);
        continue;
      }
      const double err = weighted_norm(h);
      const double k = error_order();
      double fac = std::isfinite(err) && err > 0.0
                       ? std::clamp(0.9 * std::pow(err, -1.0 / k), 0.2, 2.0)
                       : (err == 0.0 ? 2.0 : 0.2);
      if (!(err <= 1.0)) {
        ++stats_.error_test_failures;
        undo_step();  // the trial leaves no trace (the retry starts from the same state)
        rejected_ = true;
        h_ = h * fac;
        if (h_ < s_.min_step) fail_below_min_step(h_);
        continue;
      }
      if (err > 0.0 && err_prev_ > 0.0)  // PI: the last accepted error damps the change
        fac = std::clamp(0.9 * std::pow(err, -0.7 / k) * std::pow(err_prev_, 0.4 / k), 0.2, 2.0);
      if (rejected_) fac = std::min(fac, 1.0);
      rejected_ = false;
      err_prev_ = std::max(err, 1e-4);
      accept(h);
      // a step cut short for a stop or an output says little about the next one:
      // keep the planned step unless the error asks for a smaller one
      const double h_next = keep_step(h, cut ? std::min(h_, h * fac) : h * fac);
      h_ = s_.max_step > 0.0 ? std::min(h_next, s_.max_step) : h_next;
      h_ = std::max(h_, s_.min_step);
    }
    if (std::abs(t_ - tout) <= 1e-6 * std::max(t_ - t_prev_, 1e-300)) {  // on a step
      q = q_;
      v = v_;
    } else {
      // t_prev_ < tout < t_: Hermite on the last step (q1_.. hold the previous state)
      interpolate(tout, q, v);
    }
    tout_last_ = tout;
    if (base_->constraint_count() > 0) dae::note_constraints(*base_, tout, q, v, stats_);
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
  /// One step from (t, q_, v_, a_, f_) to t + h, writing q1_, v1_, a1_ and f1_
  /// (the force the method associates with the new state). Returns false, with
  /// the reason in failure_, when the iteration does not converge; may throw
  /// RangeError for the same reason (an element refusing a trial state).
  virtual bool step(double t, double h) = 0;
  /// Local error estimate of the step just taken (q1_ - q(t + h), v1_ - v(t + h)),
  /// written into eq, ev; `hist` is false when no earlier step exists since the
  /// last start (a_prev_, h_prev_ undefined).
  virtual void local_error(double h, bool hist, Vec& eq, Vec& ev) const = 0;

  /// True when the integrator solves constrained problems (and a mass matrix)
  /// itself under the settings `s`, so init() hands it the problem as it is.
  virtual bool takes_constraints(const IntegratorSettings& s) const {
    (void)s;
    return false;
  }
  /// The constrained forms it solves, for messages.
  virtual std::string constraint_forms() const { return "penalty forces (formulation=penalty)"; }
  /// Called when a step that converged is not taken after all (its error
  /// estimate failed the test): whatever step() changed of the state at t_
  /// (the Newmark family: the acceleration moved for the change of step) is put back.
  virtual void undo_step() {}
  /// Called after a step is accepted (the swap of q1_.. into q_.. done).
  virtual void accepted() {}
  /// Sets a_ (and whatever else the method carries) at the start state
  /// (t_, q_, v_, f_); default a_ = -f, and for quasi-static coordinates the
  /// accelerations that keep their rows f_i = 0 along the motion.
  virtual void start_acceleration() {
    a_ = -f_;
    quasi_static_accelerations(*p_, t_, q_, v_, a_);
  }

  /// Current state (t_, q_, v_) with f_ = f(t, q, v) and start_acceleration().
  void start(double t) {
    t_ = t;
    sub_end_ = -std::numeric_limits<double>::infinity();  // no interval in sub-steps
    t_prev_ = t;
    tout_last_ = t;
    have_prev_ = false;
    err_prev_ = 0.0;  // the PI controller starts over
    rejected_ = false;
    p_->force(t, q_.data(), v_.data(), f_.data());
    ++stats_.residual_evals;
    start_acceleration();
  }
  /// True when a_prev_, h_prev_ hold the step before the current one.
  bool has_history() const { return have_prev_; }
  /// Time of the last output handed back by advance().
  double last_output_time() const { return tout_last_; }
  /// Order k of the local error estimate, e = O(h^k): the step controller's
  /// exponents are 1/k (I) and 0.7/k, 0.4/k (PI).
  virtual int error_order() const { return 3; }
  /// The next step the adaptive control takes after an accepted step of h, given
  /// the controller's proposal (default: the proposal).
  virtual double keep_step(double h, double proposal) const {
    (void)h;
    return proposal;
  }
  /// The state at t_prev_ < t < t_: the cubic Hermite interpolant of the last step.
  virtual void interpolate(double t, Vec& q, Vec& v) const {
    const double h = t_ - t_prev_;
    const double s = (t - t_prev_) / h;
    const double s2 = s * s, s3 = s2 * s;
    const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s;
    const double h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
    // previous state lives in the *1_ vectors after the swap in accept()
    q = h00 * q1_ + h10 * h * v1_ + h01 * q_ + h11 * h * v_;
    v = h00 * v1_ + h10 * h * a1_ + h01 * v_ + h11 * h * a_;
  }

  double previous_time() const { return t_prev_; }

  /// "time, step, state" tail of a failure message.
  std::string where(double t, double h, const Vec& q, const Vec& v) const {
    return " at t = " + format_number(t) + " s, step h = " + format_number(h) +
           " s; state: " + p_->describe_state(t, q.data(), v.data());
  }

  Problem* p_ = nullptr;     // the problem stepped: base_ or its penalty form
  Problem* base_ = nullptr;  // the problem given to init()
  std::unique_ptr<dae::PenaltyProblem> penalty_;
  IntegratorSettings s_;
  int n_ = 0;
  IntegratorStats stats_;
  double t_ = 0.0;
  Vec q_, v_, a_, f_;      // state at t_
  Vec q1_, v1_, a1_, f1_;  // written by step(); after the swap: the state at t_prev_
  Vec a_prev_;             // acceleration of the step before the current one
  double h_prev_ = 0.0;    // its length
  std::string failure_;    // why the last step() returned false

 private:
  // step() with a trial state outside an element's range turned into a failed
  // step (any other error ends the run)
  bool try_step(double h) {
    failure_.clear();
    bool ok = false;
    try {
      ok = step(t_, h);
    } catch (const RangeError& e) {
      ++stats_.refused_states;
      failure_ = e.what();
      ok = false;
    }
    if (!ok && failure_.empty()) failure_ = "the iteration failed";
    return ok;
  }

  void accept(double h) {
    a_prev_ = a_;
    h_prev_ = h;
    have_prev_ = true;
    t_prev_ = t_;
    t_ += h;
    q_.swap(q1_);
    v_.swap(v1_);
    a_.swap(a1_);
    f_.swap(f1_);
    ++stats_.steps;
    stats_.last_step = h;
    note_step(stats_, h);
    accepted();
    step_done(t_, h);  // interrupts, wall-time limit, timed flushes (may throw)
  }

  // The interval [t_, t_ + h] with steps of h, cut into sub-steps where needed.
  // advance() interpolates an output between steps on the last step taken, so
  // the sub-steps stop at the first that reaches the output time tout when it
  // lies inside the interval; the next call goes on with the same interval
  // (sub_end_, sub_h_), so the step grid stays that of `fixed`. (Before, the
  // sub-steps ran to the interval's end and an output before the last one was
  // extrapolated from it.)
  void take_interval(double h, double tout) {
    if (!(sub_end_ > t_)) {  // a new interval
      if (try_step(h)) {
        accept(h);
        return;
      }
      ++stats_.convergence_failures;
      if (s_.step_control == StepControl::fixed) throw RunError(failure_);
      sub_end_ = t_ + h;
      sub_len_ = h;
      sub_h_ = 0.5 * h;
    }
    while (sub_end_ - t_ > 1e-9 * sub_len_) {
      const double rest = sub_end_ - t_;
      const double hh = sub_h_ >= rest * (1.0 - 1e-9) ? rest : sub_h_;
      if (hh < s_.min_step) fail_below_min_step(hh);
      if (try_step(hh)) {
        accept(hh);
        ++stats_.substeps;
        sub_h_ = std::min(2.0 * hh, sub_end_ - t_);
        if (t_ >= tout && sub_end_ - t_ > 1e-9 * sub_len_) return;  // the output is passed
      } else {
        ++stats_.convergence_failures;
        sub_h_ = 0.5 * hh;
      }
    }
    t_ = sub_end_;  // remove round-off of the sum of sub-steps
    sub_end_ = -std::numeric_limits<double>::infinity();
  }

  [[noreturn]] void fail_below_min_step(double h) const {
    throw RunError(name() + ": the step would fall to " + format_number(h) +
                   " s, below min_step = " + format_number(s_.min_step) +
                   " s; last failure: " + failure_);
  }

  double weighted_norm(double h) {
    eq_.resize(n_);
    ev_.resize(n_);
    local_error(h, have_prev_, eq_, ev_);
    double sum = 0.0;
    for (int i = 0; i < n_; ++i) {
      const double wq = 1.0 / (s_.rtol * std::max(std::abs(q1_[i]), std::abs(q_[i])) + s_.atol);
      const double wv = 1.0 / (s_.rtol * std::max(std::abs(v1_[i]), std::abs(v_[i])) + s_.atol);
      sum += eq_[i] * eq_[i] * wq * wq + ev_[i] * ev_[i] * wv * wv;
    }
    return std::sqrt(sum / (2.0 * n_));
  }

  double t_prev_ = 0.0;
  double tout_last_ = 0.0;
  // substep: the end and length of an interval being crossed in sub-steps (none
  // when sub_end_ <= t_), and its next sub-step
  double sub_end_ = -std::numeric_limits<double>::infinity(), sub_len_ = 0.0, sub_h_ = 0.0;
  double h_ = 0.0;  // adaptive: the planned step
  bool have_prev_ = false;
  double err_prev_ = 0.0;  // error norm of the last accepted step (0: none since a start)
  bool rejected_ = false;  // the last trial step failed the error test
  Vec eq_, ev_;
};

}  // namespace evas
