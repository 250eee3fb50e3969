#include "integrators/sundials_ode.h"

#include <algorithm>

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

std::string SundialsOdeIntegrator::failure(const std::string& head, const std::string& why,
                                           double tn, const double* y) const {
  return sundials::failure_message(head, why, tn, last_error_, guard_) +
         "; state: " + p_->describe_state(tn, y, y + n_);
}

void SundialsOdeIntegrator::error_cb(int /*code*/, const char* module, const char* function,
                                     char* msg, void* user) {
  auto* self = static_cast<SundialsOdeIntegrator*>(user);
  self->last_error_ = std::string(module) + "/" + function + ": " + msg;
}

}  // namespace evas
