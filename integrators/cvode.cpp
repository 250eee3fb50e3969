// CVODE (SUNDIALS 6.4) on the explicit first-order form
//     yd = g(t, y) = [ v ; -f(t, q, v) ],   y = [q; v]
// method "bdf":   CV_BDF + Newton (CVODE's default nonlinear solver) with the
//                 analytic Jacobian dg/dy = [0, I; -K, -C], KLU or dense LU;
// method "adams": CV_ADAMS + fixed-point iteration (no Jacobian, non-stiff runs).
//
// Stepping, landing on stops and dense output work as in ida.cpp: CV_ONE_STEP
// inside advance(), CVodeSetStopTime for stops (and for the next stop of the
// problem when not landing), CVodeGetDky for interpolated outputs.
//
// CVODE integrates ODEs with M = I only: a problem with a mass matrix is
// refused, and so is a constrained one unless formulation=penalty, which runs
// the ODE of dae/penalty.h (constraint forces G^T (k g + c g')).
#include <cvode/cvode.h>
#include <cvode/cvode_ls.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include <memory>
#include <string>

#include "integrators/sundials_ode.h"

namespace evas {
namespace {

class CvodeIntegrator final : public SundialsOdeIntegrator {
 public:
  CvodeIntegrator() = default;
  ~CvodeIntegrator() override { free_memory(); }
  CvodeIntegrator(const CvodeIntegrator&) = delete;
  CvodeIntegrator& operator=(const CvodeIntegrator&) = delete;

  std::string name() const override { return "cvode"; }

  void init(Problem& p, double t0, const Vec& q0, const Vec& v0,
            const IntegratorSettings& s) override {
    free_memory();
    if (s.method != "bdf" && s.method != "adams")
      throw InputError("cvode: method '" + s.method + "' is unknown (use bdf or adams)");
    newton_ = s.method == "bdf";
    prepare("cvode", p, t0, q0, v0, s);

    mem_ = CVodeCreate(newton_ ? CV_BDF : CV_ADAMS, ctx_);
    if (!mem_) throw RunError("cvode: CVodeCreate failed");
    void* self = static_cast<SundialsOdeIntegrator*>(this);
    check(CVodeSetErrHandlerFn(mem_, &SundialsOdeIntegrator::error_cb, self),
          "CVodeSetErrHandlerFn");
    check(CVodeInit(mem_, &CvodeIntegrator::rhs_cb, t0, y_.get()), "CVodeInit");
    check(CVodeSStolerances(mem_, s.rtol, s.atol), "CVodeSStolerances");
    check(CVodeSetUserData(mem_, self), "CVodeSetUserData");
    if (newton_) {
      make_linear_solver("cvode");
      check(CVodeSetLinearSolver(mem_, ls_.solver(), ls_.matrix()), "CVodeSetLinearSolver");
      check(CVodeSetJacFn(mem_, &CvodeIntegrator::jacobian_cb), "CVodeSetJacFn");
    } else {
      nls_.set(SUNNonlinSol_FixedPoint(y_.get(), 0, ctx_));
      if (!nls_.get()) throw RunError("cvode: SUNNonlinSol_FixedPoint failed");
      check(CVodeSetNonlinearSolver(mem_, nls_.get()), "CVodeSetNonlinearSolver");
    }
    if (s.max_step > 0.0) check(CVodeSetMaxStep(mem_, s.max_step), "CVodeSetMaxStep");
    if (s.max_order > 0) check(CVodeSetMaxOrd(mem_, s.max_order), "CVodeSetMaxOrd");
    if (s.newton_coefficient > 0.0)
      check(CVodeSetNonlinConvCoef(mem_, s.newton_coefficient), "CVodeSetNonlinConvCoef");
    check(CVodeSetMaxNumSteps(mem_, s.max_steps), "CVodeSetMaxNumSteps");
    t_ = t0;
  }

 private:
  bool has_solver() const override { return mem_ != nullptr; }
  int solver_step(double tout, double& tret) override {
    return CVode(mem_, tout, y_.get(), &tret, CV_ONE_STEP);
  }
  int solver_set_stop(double tstop) override { return CVodeSetStopTime(mem_, tstop); }
  int solver_dky(double t, N_Vector out) const override { return CVodeGetDky(mem_, t, 0, out); }
  double solver_time() const override {
    double tn = t_;
    CVodeGetCurrentTime(mem_, &tn);
    return tn;
  }
  double solver_last_step() const override {
    double h = 0.0;
    CVodeGetLastStep(mem_, &h);
    return h;
  }
  int solver_last_order() const override {
    int order = 0;
    CVodeGetLastOrder(mem_, &order);
    return order;
  }
  int solver_reinit(double t) override { return CVodeReInit(mem_, t, y_.get()); }
  std::string solver_flag_name(int flag) const override {
    return sundials::flag_name(CVodeGetReturnFlagName(flag));
  }
  int tstop_return() const override { return CV_TSTOP_RETURN; }
  std::string failure_head() const override { return "cvode (" + s_.method + ")"; }

  // Counters since the last CVodeInit/CVodeReInit.
  IntegratorStats segment() const override {
    IntegratorStats s;
    long nni = 0;
    CVodeGetNumSteps(mem_, &s.steps);
    CVodeGetNumRhsEvals(mem_, &s.residual_evals);
    if (newton_) {
      long nfe_ls = 0;  // rhs evaluations for FD Jacobians: 0 with the analytic one
      CVodeGetNumLinRhsEvals(mem_, &nfe_ls);
      s.residual_evals += nfe_ls;
      CVodeGetNumJacEvals(mem_, &s.jacobian_evals);
    }
    CVodeGetNumLinSolvSetups(mem_, &s.linear_setups);
    CVodeGetNumNonlinSolvIters(mem_, &nni);
    s.nonlinear_iterations = nni;
    s.linear_solves = newton_ ? nni : 0;  // direct solver: one solve per Newton iteration
    CVodeGetNumErrTestFails(mem_, &s.error_test_failures);
    CVodeGetNumNonlinSolvConvFails(mem_, &s.convergence_failures);
    return s;
  }

  void free_memory() {
    if (mem_) CVodeFree(&mem_);
    mem_ = nullptr;
    nls_.reset();
    ls_.reset();
  }

  static int rhs_cb(realtype t, N_Vector y, N_Vector yd, void* user) {
    return static_cast<CvodeIntegrator*>(static_cast<SundialsOdeIntegrator*>(user))->rhs(t, y, yd);
  }

  static int jacobian_cb(realtype t, N_Vector y, N_Vector /*fy*/, SUNMatrix J, void* user, N_Vector,
                         N_Vector, N_Vector) {
    return static_cast<CvodeIntegrator*>(static_cast<SundialsOdeIntegrator*>(user))
        ->jacobian(t, y, J);
  }

  sundials::NonlinearSolver nls_;
  bool newton_ = true;
  void* mem_ = nullptr;
};

}  // namespace

IntegratorEntry cvode_entry() {
  IntegratorCapabilities c;
  c.declared = true;
  c.adaptive = true;
  c.reads = {"rtol",
             "atol",
             "max_step",
             "linear_solver",
             "method",
             "max_order",
             "newton_coefficient",
             "max_steps",
             "formulation",
             "penalty_stiffness",
             "penalty_damping"};
  return {"cvode", [] { return std::make_unique<CvodeIntegrator>(); },
          "CVODE (SUNDIALS): BDF + Newton or Adams", c};
}

}  // namespace evas
