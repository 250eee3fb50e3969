// What the two SUNDIALS adapters on the explicit first-order form yd = g(t, y),
// y = [q; v; z] (solver/first_order.h), share: cvode (CVODE) and arkode
// (ARKODE's ARKStep). The problem they integrate (constraints only as penalty
// forces, no mass matrix), the state vector and its packing, the Jacobian
// callback's body (the 2n x 2n matrix, or K and C for the second-order
// solver), the failure message with the model's last refusal and state, and
// the stepping to outputs and stops (advance, restart, stats) on the solver's
// calls, which each adapter gives (its own solver memory: the solver_* hooks).
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

  /// One internal step at a time to tout (sundials::step_to), landing on
  /// stops (the solver's stop time) and interpolating outputs between steps.
  void advance(double tout, bool land, Vec& q, Vec& v) override;
  /// A new start at (t, q, v); the counters of the segment before are banked
  /// (the solver's re-initialization resets them).
  void restart(double t, const Vec& q, const Vec& v) override;
  IntegratorStats stats() const override;

 protected:
  // ---- the solver's calls (each adapter's) ----
  virtual bool has_solver() const = 0;
  /// One internal step towards tout (the solver's ONE_STEP mode); its flag.
  virtual int solver_step(double tout, double& tret) = 0;
  virtual int solver_set_stop(double tstop) = 0;
  /// The dense output y(t) into out; the solver's flag.
  virtual int solver_dky(double t, N_Vector out) const = 0;
  virtual double solver_time() const = 0;
  virtual double solver_last_step() const = 0;
  virtual int solver_last_order() const = 0;
  /// Re-initializes at (t, y_) after a restart.
  virtual int solver_reinit(double t) = 0;
  virtual std::string solver_flag_name(int flag) const = 0;
  /// The flag of a return at the stop time (CV_TSTOP_RETURN, ARK_TSTOP_RETURN).
  virtual int tstop_return() const = 0;
  /// Counters since the last (re-)initialization.
  virtual IntegratorStats segment() const = 0;
  /// "cvode (bdf)", "arkode (TABLE)": the head of a failure message.
  virtual std::string failure_head() const = 0;

  /// Throws RunError "<name>: <what> failed with <flag> (<last message>)" for
  /// a negative flag.
  void check(int flag, const char* what) const;
  /// Throws RunError with the reason, the time and the state where it stopped.
  [[noreturn]] void fail(const std::string& why) const;

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
