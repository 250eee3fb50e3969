// What the two SUNDIALS adapters on the explicit first-order form yd = g(t, y),
// y = [q; v; z] (solver/first_order.h), share: cvode (CVODE) and arkode
// (ARKODE's ARKStep). The problem they integrate (constraints only as penalty
// forces, no mass matrix), the state vector and its packing, the Jacobian
// callback's body (the 2n x 2n matrix, or K and C for the second-order
// solver), and the failure message with the model's last refusal and state.
// Each adapter keeps its own solver memory and calls.
#pragma once

#include <memory>
#include <string>

#include "dae/penalty.h"
#include "integrators/common.h"
#include "integrators/second_order_ls.h"
#include "integrators/sundials_util.h"
#include "solver/first_order.h"

namespace evas {

class SundialsOdeIntegrator : public Integrator {
 public:
  bool takes_internal_states() const override { return true; }

 protected:
  /// The problem as an ODE: penalty forces for constraints (formulation=
  /// penalty, else refused), a mass matrix refused, the first-order form, y
  /// and ytmp made and y set to (q0, v0, z0). `who` names the adapter.
  void prepare(const std::string& who, Problem& p, double t0, const Vec& q0, const Vec& v0,
               const IntegratorSettings& s);
  /// The linear solver named by settings.linear_solver for the Newton
  /// iteration (klu, dense, or second-order: no internal states).
  void make_linear_solver(const std::string& who);

  void set_state(const Vec& q, const Vec& v);
  void get_state(const double* y, Vec& q, Vec& v) const;

  /// The right-hand side g(t, y) into yd (a callback's body).
  int rhs(double t, N_Vector y, N_Vector yd) {
    return guard_.run([&] { form_->rhs(t, N_VGetArrayPointer(y), N_VGetArrayPointer(yd)); });
  }
  /// dg/dy into J, or K and C alone for the second-order solver (which forms
  /// I - gamma J itself through the matrix's scaleaddi).
  int jacobian(double t, N_Vector y, SUNMatrix J);

  /// "<head>: <why> at t = ... s (solver message); the model refused ...;
  /// state: ..." with the state y at tn.
  std::string failure(const std::string& head, const std::string& why, double tn,
                      const double* y) const;

  /// SUNDIALS' error handler: keeps the last message.
  static void error_cb(int code, const char* module, const char* function, char* msg, void* user);

  // Declaration order matters: the context outlives everything created in it.
  sundials::Context ctx_;
  sundials::Vector y_, ytmp_;
  sundials::LinearSystem ls_;
  std::unique_ptr<dae::PenaltyProblem> penalty_;  // formulation=penalty
  std::unique_ptr<FirstOrderForm> form_;
  SpMat J_;
  Problem* p_ = nullptr;
  Problem* model_ = nullptr;  // p_ or its penalty form
  IntegratorSettings s_;
  int n_ = 0;
  double t_ = 0.0;
  IntegratorStats total_;
  mutable sundials::CallbackGuard guard_;
  std::string last_error_;
};

}  // namespace evas
