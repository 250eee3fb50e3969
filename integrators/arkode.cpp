// ARKODE's ARKStep (SUNDIALS 6.4; D. R. Reynolds et al., "ARKODE: a flexible
// IVP solver infrastructure for one-step methods", ACM TOMS 49 (2023) 19) on
// the explicit first-order form yd = g(t, y) = [v; -f(t, q, v)], y = [q; v],
// with the Runge-Kutta table named by the setting `table` (ARKODE's names):
//   diagonally implicit (SDIRK, ESDIRK, the ARK pairs' DIRK halves, e.g.
//   ARKODE_ESDIRK324L2SA_4_2_3, the default: L-stable, stiffly accurate,
//   order 3 with an embedded order 2): the whole g implicit, Newton with the
//   analytic Jacobian dg/dy = [0, I; -K, -C] by KLU or dense LU, or the n x n
//   matrix K + C/gamma' + I/gamma'^2 (linear_solver=second-order) as cvode;
//   explicit (ERK, e.g. ARKODE_DORMAND_PRINCE_7_4_5): no linear solver.
// Steps: adaptive against rtol/atol (ARKODE's PID controller), or fixed at
// `step` with step_control=fixed (ARKStepSetFixedStep: no error control;
// what evas study amplification measures). The additive (IMEX) pairs are not
// offered: evas has no split of f into a stiff and a non-stiff part yet.
// Like cvode it takes M = I only: constrained problems run as penalty forces
// (formulation=penalty), a mass matrix is refused.
#include <arkode/arkode_arkstep.h>
#include <arkode/arkode_butcher_dirk.h>
#include <arkode/arkode_butcher_erk.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "dae/constraint_stats.h"
#include "integrators/sundials_ode.h"

namespace evas {

const std::vector<std::string>& arkode_implicit_tables() {
  static const std::vector<std::string> t = {"ARKODE_ESDIRK324L2SA_4_2_3",
                                             "ARKODE_SDIRK_2_1_2",
                                             "ARKODE_BILLINGTON_3_3_2",
                                             "ARKODE_TRBDF2_3_3_2",
                                             "ARKODE_KVAERNO_4_2_3",
                                             "ARKODE_ARK324L2SA_DIRK_4_2_3",
                                             "ARKODE_CASH_5_2_4",
                                             "ARKODE_CASH_5_3_4",
                                             "ARKODE_SDIRK_5_3_4",
                                             "ARKODE_KVAERNO_5_3_4",
                                             "ARKODE_ARK436L2SA_DIRK_6_3_4",
                                             "ARKODE_KVAERNO_7_4_5",
                                             "ARKODE_ARK548L2SA_DIRK_8_4_5",
                                             "ARKODE_ARK437L2SA_DIRK_7_3_4",
                                             "ARKODE_ARK548L2SAb_DIRK_8_4_5",
                                             "ARKODE_ESDIRK325L2SA_5_2_3",
                                             "ARKODE_ESDIRK32I5L2SA_5_2_3",
                                             "ARKODE_ESDIRK436L2SA_6_3_4",
                                             "ARKODE_ESDIRK43I6L2SA_6_3_4",
                                             "ARKODE_QESDIRK436L2SA_6_3_4",
                                             "ARKODE_ESDIRK437L2SA_7_3_4",
                                             "ARKODE_ESDIRK547L2SA_7_4_5",
                                             "ARKODE_ESDIRK547L2SA2_7_4_5"};
  return t;
}

const std::vector<std::string>& arkode_explicit_tables() {
  static const std::vector<std::string> t = {
      "ARKODE_HEUN_EULER_2_1_2",     "ARKODE_BOGACKI_SHAMPINE_4_2_3", "ARKODE_ARK324L2SA_ERK_4_2_3",
      "ARKODE_ZONNEVELD_5_3_4",      "ARKODE_ARK436L2SA_ERK_6_3_4",   "ARKODE_SAYFY_ABURUB_6_3_4",
      "ARKODE_CASH_KARP_6_4_5",      "ARKODE_FEHLBERG_6_4_5",         "ARKODE_DORMAND_PRINCE_7_4_5",
      "ARKODE_ARK548L2SA_ERK_8_4_5", "ARKODE_VERNER_8_5_6",           "ARKODE_FEHLBERG_13_7_8",
      "ARKODE_ARK437L2SA_ERK_7_3_4", "ARKODE_ARK548L2SAb_ERK_8_4_5"};
  return t;
}

namespace {

bool listed(const std::vector<std::string>& names, const std::string& name) {
  for (const auto& n : names)
    if (n == name) return true;
  return false;
}

class ArkodeIntegrator final : public SundialsOdeIntegrator {
 public:
  ArkodeIntegrator() = default;
  ~ArkodeIntegrator() override { free_memory(); }
  ArkodeIntegrator(const ArkodeIntegrator&) = delete;
  ArkodeIntegrator& operator=(const ArkodeIntegrator&) = delete;

  std::string name() const override { return "arkode"; }

  void init(Problem& p, double t0, const Vec& q0, const Vec& v0,
            const IntegratorSettings& s) override {
    free_memory();
    implicit_ = listed(arkode_implicit_tables(), s.table);
    if (!implicit_ && !listed(arkode_explicit_tables(), s.table))
      throw InputError("arkode: table '" + s.table + "' is not one of ARKODE's (see table)");
    fixed_ = s.step_control == StepControl::fixed;
    if (fixed_ && !(s.step > 0.0))
      throw InputError("arkode: step must be > 0 with step_control=fixed");
    prepare("arkode", p, t0, q0, v0, s);

    mem_ = implicit_ ? ARKStepCreate(nullptr, &ArkodeIntegrator::rhs_cb, t0, y_.get(), ctx_)
                     : ARKStepCreate(&ArkodeIntegrator::rhs_cb, nullptr, t0, y_.get(), ctx_);
    if (!mem_) throw RunError("arkode: ARKStepCreate failed");
    void* self = static_cast<SundialsOdeIntegrator*>(this);
    check(ARKStepSetErrHandlerFn(mem_, &SundialsOdeIntegrator::error_cb, self),
          "ARKStepSetErrHandlerFn");
    check(ARKStepSetUserData(mem_, self), "ARKStepSetUserData");
    check(ARKStepSetTableName(mem_, implicit_ ? s.table.c_str() : "ARKODE_DIRK_NONE",
                              implicit_ ? "ARKODE_ERK_NONE" : s.table.c_str()),
          "ARKStepSetTableName");
    check(ARKStepSStolerances(mem_, s.rtol, s.atol), "ARKStepSStolerances");
    if (implicit_) {
      make_linear_solver("arkode");
      check(ARKStepSetLinearSolver(mem_, ls_.solver(), ls_.matrix()), "ARKStepSetLinearSolver");
      check(ARKStepSetJacFn(mem_, &ArkodeIntegrator::jacobian_cb), "ARKStepSetJacFn");
      // the stages' first guess from the last step's dense output at its full
      // order (ARKODE's predictor 1) in place of the last value (0): on the
      // paper's engine to 0.05 s at rtol 1e-4, 107,689 residuals in 6,481
      // steps against 305,848 in 7,709, 0.87 s against 2.2 s
      check(ARKStepSetPredictorMethod(mem_, 1), "ARKStepSetPredictorMethod");
      if (s.newton_coefficient > 0.0)
        check(ARKStepSetNonlinConvCoef(mem_, s.newton_coefficient), "ARKStepSetNonlinConvCoef");
      if (s.max_iterations > 0)
        check(ARKStepSetMaxNonlinIters(mem_, std::min(s.max_iterations, 100)),
              "ARKStepSetMaxNonlinIters");
    }
    if (fixed_) check(ARKStepSetFixedStep(mem_, s.step), "ARKStepSetFixedStep");
    if (s.max_step > 0.0) check(ARKStepSetMaxStep(mem_, s.max_step), "ARKStepSetMaxStep");
    check(ARKStepSetMaxNumSteps(mem_, s.max_steps), "ARKStepSetMaxNumSteps");
    {  // the table's order, reported as the run's last order
      ARKodeButcherTable b = implicit_ ? ARKodeButcherTable_LoadDIRKByName(s.table.c_str())
                                       : ARKodeButcherTable_LoadERKByName(s.table.c_str());
      if (!b) throw InputError("arkode: ARKODE does not know table '" + s.table + "'");
      order_ = b->q;
      ARKodeButcherTable_Free(b);
    }
    t_ = t0;
  }

  void advance(double tout, bool land, Vec& q, Vec& v) override {
    WallTimer timer(total_.wall_seconds);
    if (!mem_) throw RunError("arkode: advance() before init()");
    last_error_.clear();
    if (!(tout > t_)) {
      throw RunError("arkode: output time " + format_number(tout) + " s is not after " +
                     format_number(t_) + " s");
    }
    const double tstop = land ? tout : p_->next_stop(t_);
    if (std::isfinite(tstop) && tstop > current_time())
      check(ARKStepSetStopTime(mem_, tstop), "ARKStepSetStopTime");

    const bool exact = sundials::step_to(
        tout, s_.max_steps, ARK_TSTOP_RETURN, total_,
        [&](double& tret) { return ARKStepEvolve(mem_, tout, y_.get(), &tret, ARK_ONE_STEP); },
        [&] {
          double h = 0.0;
          ARKStepGetLastStep(mem_, &h);
          return h;
        },
        [&] { return current_time(); },
        [&](int flag, const std::string& why) {
          fail(flag < 0 ? sundials::flag_name(ARKStepGetReturnFlagName(flag)) : why);
        },
        [&](double t, double h) { step_done(t, h); });
    if (!exact) {
      const int flag = ARKStepGetDky(mem_, tout, 0, ytmp_.get());
      if (flag < 0) fail(sundials::flag_name(ARKStepGetReturnFlagName(flag)));
      get_state(ytmp_.data(), q, v);
    } else {
      get_state(y_.data(), q, v);
    }
    t_ = tout;
    if (p_->constraint_count() > 0) dae::note_constraints(*p_, tout, q, v, total_);
  }

  void restart(double t, const Vec& q, const Vec& v) override {
    WallTimer timer(total_.wall_seconds);
    if (!mem_) throw RunError("arkode: restart() before init()");
    sundials::add_segment(total_, segment());  // ARKStepReInit resets the counters
    ++total_.restarts;
    set_state(q, v);
    check(implicit_ ? ARKStepReInit(mem_, nullptr, &ArkodeIntegrator::rhs_cb, t, y_.get())
                    : ARKStepReInit(mem_, &ArkodeIntegrator::rhs_cb, nullptr, t, y_.get()),
          "ARKStepReInit");
    t_ = t;
  }

  IntegratorStats stats() const override {
    IntegratorStats out = total_;
    out.refused_states = guard_.recoverable;
    if (!mem_) return out;
    sundials::add_segment(out, segment());
    double h = 0.0;
    ARKStepGetLastStep(mem_, &h);
    out.last_step = h;
    out.last_order = order_;
    return out;
  }

 private:
  double current_time() const {
    double tn = t_;
    ARKStepGetCurrentTime(mem_, &tn);
    return tn;
  }

  // Counters since the last ARKStepCreate/ARKStepReInit.
  IntegratorStats segment() const {
    IntegratorStats s;
    long nfe = 0, nfi = 0;
    ARKStepGetNumSteps(mem_, &s.steps);
    ARKStepGetNumRhsEvals(mem_, &nfe, &nfi);
    s.residual_evals = nfe + nfi;
    if (implicit_) {
      long nfe_ls = 0, nni = 0;
      ARKStepGetNumLinRhsEvals(mem_, &nfe_ls);
      s.residual_evals += nfe_ls;
      ARKStepGetNumJacEvals(mem_, &s.jacobian_evals);
      ARKStepGetNumLinSolvSetups(mem_, &s.linear_setups);
      ARKStepGetNumNonlinSolvIters(mem_, &nni);
      s.nonlinear_iterations = nni;
      s.linear_solves = nni;
      ARKStepGetNumNonlinSolvConvFails(mem_, &s.convergence_failures);
    }
    ARKStepGetNumErrTestFails(mem_, &s.error_test_failures);
    return s;
  }

  void check(int flag, const char* what) {
    if (flag < 0) {
      throw RunError(std::string("arkode: ") + what + " failed with " +
                     sundials::flag_name(ARKStepGetReturnFlagName(flag)) +
                     (last_error_.empty() ? "" : " (" + last_error_ + ")"));
    }
  }

  [[noreturn]] void fail(const std::string& why) {
    const double tn = current_time();
    const double* y = y_.data();
    if (ARKStepGetDky(mem_, tn, 0, ytmp_.get()) == ARK_SUCCESS) y = ytmp_.data();
    throw RunError(failure("arkode (" + s_.table + ")", why, tn, y));
  }

  void free_memory() {
    if (mem_) ARKStepFree(&mem_);
    mem_ = nullptr;
    ls_.reset();
  }

  static ArkodeIntegrator* from(void* user) {
    return static_cast<ArkodeIntegrator*>(static_cast<SundialsOdeIntegrator*>(user));
  }
  static int rhs_cb(realtype t, N_Vector y, N_Vector yd, void* user) {
    return from(user)->rhs(t, y, yd);
  }
  static int jacobian_cb(realtype t, N_Vector y, N_Vector /*fy*/, SUNMatrix J, void* user, N_Vector,
                         N_Vector, N_Vector) {
    return from(user)->jacobian(t, y, J);
  }

  bool implicit_ = true, fixed_ = false;
  int order_ = 0;
  void* mem_ = nullptr;
};

}  // namespace

IntegratorEntry arkode_entry() {
  IntegratorCapabilities c;
  c.declared = true;
  c.adaptive = true;
  c.fixed_step = true;
  c.fixed_step_on_request = true;
  c.reads = {"rtol",           "atol",      "step",          "step_control",
             "max_step",       "table",     "linear_solver", "newton_coefficient",
             "max_iterations", "max_steps", "formulation",   "penalty_stiffness",
             "penalty_damping"};
  return {"arkode", [] { return std::make_unique<ArkodeIntegrator>(); },
          "ARKODE (SUNDIALS): implicit (DIRK, ESDIRK) or explicit Runge-Kutta tables by name", c};
}

}  // namespace evas
