#include "integrators/sundials_ode.h"

#include <algorithm>
#include <cmath>

#include "dae/constraint_stats.h"

namespace evas {

void SundialsOdeIntegrator::prepare(const std::string& who, Problem& p, double t0, const Vec& q0,
                                    const Vec& v0, const IntegratorSettings& s) {
  p_ = &p;
  s_ = s;
  n_ = p.size();
  total_ = IntegratorStats{};
  form_.reset();
  penalty_.reset();
  model_ = &p;
  if (const int m = p.constraint_count(); m > 0) {
    if (s.formulation != "penalty")
      throw InputError(who + ": the problem has " + std::to_string(m) +
                       " constraint equation(s) (first: '" + p.constraint_name(0) + "') and " +
                       who + " integrates ODEs only; use ida, or set formulation=penalty");
    penalty_ = std::make_unique<dae::PenaltyProblem>(p, s.penalty_stiffness, s.penalty_damping);
    model_ = penalty_.get();
  }
  if (model_->has_mass())
    throw InputError(who + ": the problem has a mass matrix (M != I), which " + who +
                     "'s explicit form v' = -f cannot take; use ida");
  require_quasi_static_support(*this, *model_);       // (its explicit form has no place for them)
  form_ = std::make_unique<FirstOrderForm>(*model_);  // refuses algebraic internal states
  J_ = form_->rhs_pattern();
  y_.create(form_->size(), ctx_);
  ytmp_.create(form_->size(), ctx_);
  set_state(q0, v0);
  if (form_->internal_count() > 0) {
    Vec z;
    model_->internal_initial(t0, q0, v0, z);
    std::copy(z.data(), z.data() + z.size(), y_.data() + 2 * n_);
    model_->set_internal(z.data());
  }
}

void SundialsOdeIntegrator::make_linear_solver(const std::string& who) {
  if (s_.linear_solver != "second-order") {
    ls_.create(s_.linear_solver, J_, y_.get(), ctx_);
  } else if (form_->internal_count() > 0) {
    throw InputError(who +
                     ": linear_solver second-order needs a problem without internal states (this "
                     "one has " +
                     std::to_string(form_->internal_count()) + "); use klu");
  } else {
    ls_.create_second_order(model_->jacobian_pattern(), ctx_);
  }
}

void SundialsOdeIntegrator::set_state(const Vec& q, const Vec& v) {
  double* y = y_.data();
  for (int i = 0; i < n_; ++i) {
    y[i] = q[i];
    y[n_ + i] = v[i];
  }
}

void SundialsOdeIntegrator::get_state(const double* y, Vec& q, Vec& v) const {
  q.resize(n_);
  v.resize(n_);
  for (int i = 0; i < n_; ++i) {
    q[i] = y[i];
    v[i] = y[n_ + i];
  }
  if (form_->internal_count() > 0) form_->problem().set_internal(y + 2 * n_);
}

int SundialsOdeIntegrator::jacobian(double t, N_Vector y, SUNMatrix J) {
  return guard_.run([&] {
    if (SecondOrderSolver* so = ls_.second_order()) {
      const double* yv = N_VGetArrayPointer(y);
      form_->problem().force_jacobian(t, yv, yv + n_, so->K(), so->C());
      return;
    }
    form_->rhs_jacobian(t, N_VGetArrayPointer(y), J_);
    ls_.copy(J_, J);
  });
}

void SundialsOdeIntegrator::advance(double tout, bool land, Vec& q, Vec& v) {
  WallTimer timer(total_.wall_seconds);
  if (!has_solver()) throw RunError(name() + ": advance() before init()");
  last_error_.clear();
  if (!(tout > t_)) {
    throw RunError(name() + ": output time " + format_number(tout) + " s is not after " +
                   format_number(t_) + " s");
  }
  const double tstop = land ? tout : p_->next_stop(t_);
  if (std::isfinite(tstop) && tstop > solver_time())
    check(solver_set_stop(tstop), "setting the stop time");

  const bool exact = sundials::step_to(
      tout, s_.max_steps, tstop_return(), total_,
      [&](double& tret) { return solver_step(tout, tret); }, [&] { return solver_last_step(); },
      [&] { return solver_time(); },
      [&](int flag, const std::string& why) { fail(flag < 0 ? solver_flag_name(flag) : why); },
      [&](double t, double h) { step_done(t, h); });
  if (!exact) {
    const int flag = solver_dky(tout, ytmp_.get());
    if (flag < 0) fail(solver_flag_name(flag));
    get_state(ytmp_.data(), q, v);
  } else {
    get_state(y_.data(), q, v);
  }
  t_ = tout;
  if (p_->constraint_count() > 0) dae::note_constraints(*p_, tout, q, v, total_);
}

void SundialsOdeIntegrator::restart(double t, const Vec& q, const Vec& v) {
  WallTimer timer(total_.wall_seconds);
  if (!has_solver()) throw RunError(name() + ": restart() before init()");
  sundials::add_segment(total_, segment());  // (re-initialization resets the counters)
  ++total_.restarts;
  set_state(q, v);
  check(solver_reinit(t), "re-initialization");
  t_ = t;
}

IntegratorStats SundialsOdeIntegrator::stats() const {
  IntegratorStats out = total_;
  out.refused_states = guard_.recoverable;
  if (!has_solver()) return out;
  sundials::add_segment(out, segment());
  out.last_step = solver_last_step();
  out.last_order = solver_last_order();
  return out;
}

void SundialsOdeIntegrator::check(int flag, const char* what) const {
  if (flag < 0) {
    throw RunError(name() + ": " + what + " failed with " + solver_flag_name(flag) +
                   (last_error_.empty() ? "" : " (" + last_error_ + ")"));
  }
}

void SundialsOdeIntegrator::fail(const std::string& why) const {
  const double tn = solver_time();
  const double* y = y_.data();
  if (solver_dky(tn, ytmp_.get()) >= 0) y = ytmp_.data();
  throw RunError(sundials::failure_message(failure_head(), why, tn, last_error_, guard_) +
                 "; state: " + p_->describe_state(tn, y, y + n_));
}

void SundialsOdeIntegrator::error_cb(int /*code*/, const char* module, const char* function,
                                     char* msg, void* user) {
  auto* self = static_cast<SundialsOdeIntegrator*>(user);
  self->last_error_ = std::string(module) + "/" + function + ": " + msg;
}

}  // namespace evas
