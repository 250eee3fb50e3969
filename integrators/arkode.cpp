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
// what evas study amplification measures).
// Additive (IMEX) pairs (Kennedy & Carpenter's ARK tables, Appl. Numer. Math.
// 44 (2003) 139-181 and 136 (2019) 183-205, ARKODE's
// ARKODE_ARK324L2SA_DIRK_4_2_3 / _ERK_4_2_3 and the like; the setting `table`
// names either half of a pair) split g = B + E with B the bodies' own modal
// stiffness and damping (Problem::body_operator: f = f0(t) + KB q + CB v +
// element loads, the split of the paper's Steps <4>-<6>),
//     B = [v; -(KB q + CB v); 0],   E = g - B
// (so the split is exact whatever f holds):
//   imex=body      B implicit and linear (ARKStepSetLinear: one Newton
//                  iteration per stage; linear_solver=second-order with K =
//                  KB, C = CB), E explicit: the high body modes cost no
//                  stability, the elements' stiffness bounds the step;
//   imex=elements  E implicit (its Jacobian dg/dy less B's, linear_solver klu
//                  or dense: it has no q' = v block), B explicit: the films'
//                  stiffness is implicit, the bodies' highest mode bounds the
//                  step.
// Both need modal bodies (KB, CB not all zero).
#include <arkode/arkode_arkstep.h>
#include <arkode/arkode_butcher_dirk.h>
#include <arkode/arkode_butcher_erk.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

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

// ARKODE's additive pairs: the DIRK and ERK halves of each name.
const std::vector<std::string>& ark_pairs() {
  static const std::vector<std::string> p = {"ARK324L2SA_%_4_2_3", "ARK436L2SA_%_6_3_4",
                                             "ARK437L2SA_%_7_3_4", "ARK548L2SA_%_8_4_5",
                                             "ARK548L2SAb_%_8_4_5"};
  return p;
}

std::string pair_half(const std::string& pattern, const std::string& kind) {
  std::string s = "ARKODE_" + pattern;
  s.replace(s.find('%'), 1, kind);
  return s;
}

// The (DIRK, ERK) pair that `table` is half of; false when none.
bool ark_pair(const std::string& table, std::string& dirk, std::string& erk) {
  for (const auto& p : ark_pairs()) {
    dirk = pair_half(p, "DIRK");
    erk = pair_half(p, "ERK");
    if (table == dirk || table == erk) return true;
  }
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
    split_ = s.imex == "body" ? Split::body : s.imex == "elements" ? Split::elements : Split::none;
    imex_ = split_ != Split::none;
    std::string dirk = s.table, erk = s.table;
    if (imex_) {
      const std::string who = "arkode: imex=" + s.imex;
      if (!ark_pair(s.table, dirk, erk)) {
        std::string names;
        for (const auto& q : ark_pairs())
          names += (names.empty() ? "" : ", ") + pair_half(q, "DIRK");
        throw InputError(who + " needs an additive pair's table (" + names +
                         ", or their _ERK_ halves), not '" + s.table + "'");
      }
      if (split_ == Split::body && s.linear_solver != "second-order")
        throw InputError(who +
                         " needs linear_solver=second-order (its implicit part is the bodies' K "
                         "and C), not " +
                         s.linear_solver);
      if (split_ == Split::elements && s.linear_solver == "second-order")
        throw InputError(who +
                         " needs linear_solver=klu or dense (its implicit part has no q' = v "
                         "block, which the second-order solver eliminates)");
      implicit_ = true;
    }
    prepare("arkode", p, t0, q0, v0, s);

    if (imex_) {
      kb_ = model_->jacobian_pattern();
      cb_ = kb_;
      model_->body_operator(t0, kb_, cb_);
      kb_t_ = t0;
      if (kb_.coeffs().isZero(0.0) && cb_.coeffs().isZero(0.0))
        throw InputError("arkode: imex=" + s.imex +
                         " needs modal bodies (their stiffness and damping are one of the two "
                         "parts); this problem has none");
      mem_ = ARKStepCreate(explicit_fn(), implicit_fn(), t0, y_.get(), ctx_);
    } else {
      mem_ = implicit_ ? ARKStepCreate(nullptr, &ArkodeIntegrator::rhs_cb, t0, y_.get(), ctx_)
                       : ARKStepCreate(&ArkodeIntegrator::rhs_cb, nullptr, t0, y_.get(), ctx_);
    }
    if (!mem_) throw RunError("arkode: ARKStepCreate failed");
    void* self = static_cast<SundialsOdeIntegrator*>(this);
    check(ARKStepSetErrHandlerFn(mem_, &SundialsOdeIntegrator::error_cb, self),
          "ARKStepSetErrHandlerFn");
    check(ARKStepSetUserData(mem_, self), "ARKStepSetUserData");
    if (imex_)
      check(ARKStepSetTableName(mem_, dirk.c_str(), erk.c_str()), "ARKStepSetTableName");
    else
      check(ARKStepSetTableName(mem_, implicit_ ? s.table.c_str() : "ARKODE_DIRK_NONE",
                                implicit_ ? "ARKODE_ERK_NONE" : s.table.c_str()),
            "ARKStepSetTableName");
    check(ARKStepSStolerances(mem_, s.rtol, s.atol), "ARKStepSStolerances");
    if (implicit_) {
      make_linear_solver("arkode");
      check(ARKStepSetLinearSolver(mem_, ls_.solver(), ls_.matrix()), "ARKStepSetLinearSolver");
      check(ARKStepSetJacFn(mem_, &ArkodeIntegrator::jacobian_cb), "ARKStepSetJacFn");
      // imex=body: the implicit part is linear in y (KB, CB may change with t:
      // the Jacobian is evaluated anew at each setup)
      if (split_ == Split::body) check(ARKStepSetLinear(mem_, 1), "ARKStepSetLinear");
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
      ARKodeButcherTable b = implicit_ ? ARKodeButcherTable_LoadDIRKByName(dirk.c_str())
                                       : ARKodeButcherTable_LoadERKByName(s.table.c_str());
      if (!b) throw InputError("arkode: ARKODE does not know table '" + s.table + "'");
      order_ = b->q;
      ARKodeButcherTable_Free(b);
    }
    t_ = t0;
  }

 private:
  bool has_solver() const override { return mem_ != nullptr; }
  int solver_step(double tout, double& tret) override {
    return ARKStepEvolve(mem_, tout, y_.get(), &tret, ARK_ONE_STEP);
  }
  int solver_set_stop(double tstop) override { return ARKStepSetStopTime(mem_, tstop); }
  int solver_dky(double t, N_Vector out) const override { return ARKStepGetDky(mem_, t, 0, out); }
  double solver_time() const override {
    double tn = t_;
    ARKStepGetCurrentTime(mem_, &tn);
    return tn;
  }
  double solver_last_step() const override {
    double h = 0.0;
    ARKStepGetLastStep(mem_, &h);
    return h;
  }
  int solver_last_order() const override { return order_; }
  int solver_reinit(double t) override {
    return imex_       ? ARKStepReInit(mem_, explicit_fn(), implicit_fn(), t, y_.get())
           : implicit_ ? ARKStepReInit(mem_, nullptr, &ArkodeIntegrator::rhs_cb, t, y_.get())
                       : ARKStepReInit(mem_, &ArkodeIntegrator::rhs_cb, nullptr, t, y_.get());
  }
  std::string solver_flag_name(int flag) const override {
    return sundials::flag_name(ARKStepGetReturnFlagName(flag));
  }
  int tstop_return() const override { return ARK_TSTOP_RETURN; }
  std::string failure_head() const override { return "arkode (" + s_.table + ")"; }

  // Counters since the last ARKStepCreate/ARKStepReInit.
  IntegratorStats segment() const override {
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
    ArkodeIntegrator* self = from(user);
    switch (self->split_) {
      case Split::none:
        return self->jacobian(t, y, J);
      case Split::body:  // the implicit part's K and C: the bodies' own
        return self->guard_.run([&] {
          SecondOrderSolver* so = self->ls_.second_order();
          self->model_->body_operator(t, so->K(), so->C());
        });
      case Split::elements:
        return self->guard_.run([&] { self->rest_jacobian(t, N_VGetArrayPointer(y), J); });
    }
    return -1;
  }
  // The two parts of g (see above): the body part [v; -(KB q + CB v); 0] and
  // the rest, g minus it.
  static int body_cb(realtype t, N_Vector y, N_Vector yd, void* user) {
    ArkodeIntegrator* self = from(user);
    return self->guard_.run(
        [&] { self->body_part(t, N_VGetArrayPointer(y), N_VGetArrayPointer(yd)); });
  }
  static int rest_cb(realtype t, N_Vector y, N_Vector yd, void* user) {
    ArkodeIntegrator* self = from(user);
    return self->guard_.run([&] {
      const double* yv = N_VGetArrayPointer(y);
      double* out = N_VGetArrayPointer(yd);
      self->form_->rhs(t, yv, out);  // [v; -f; z']
      Vec& bi = self->body_rhs_;
      bi.resize(self->form_->size());
      self->body_part(t, yv, bi.data());
      for (int i = 0; i < 2 * self->n_; ++i) out[i] -= bi[i];
    });
  }
  ARKRhsFn explicit_fn() const {
    return split_ == Split::body ? &ArkodeIntegrator::rest_cb : &ArkodeIntegrator::body_cb;
  }
  ARKRhsFn implicit_fn() const {
    return split_ == Split::body ? &ArkodeIntegrator::body_cb : &ArkodeIntegrator::rest_cb;
  }
  void update_body_operator(double t) {
    if (t != kb_t_) {
      model_->body_operator(t, kb_, cb_);
      kb_t_ = t;
    }
  }
  // [v; -(KB q + CB v); 0] at t into out (KB, CB evaluated once per t)
  void body_part(double t, const double* y, double* out) {
    update_body_operator(t);
    Eigen::Map<const Vec> q(y, n_), v(y + n_, n_);
    Eigen::Map<Vec> oq(out, n_), ov(out + n_, n_);
    oq = v;
    ov.noalias() = -(kb_ * q);
    ov.noalias() -= cb_ * v;
    for (int i = 2 * n_; i < form_->size(); ++i) out[i] = 0.0;
  }
  // imex=elements: the Jacobian of the rest, dg/dy - [0, I, 0; -KB, -CB, 0; 0, 0, 0]
  void rest_jacobian(double t, const double* y, SUNMatrix J) {
    form_->rhs_jacobian(t, y, J_);
    update_body_operator(t);
    for (int c = 0; c < J_.outerSize(); ++c)
      for (SpMat::InnerIterator it(J_, c); it; ++it) {
        const int r = static_cast<int>(it.row()), col = static_cast<int>(it.col());
        if (r < n_ && col >= n_ && col < 2 * n_ && r == col - n_)
          it.valueRef() = 0.0;  // q' = v is the body part's
        else if (r >= n_ && r < 2 * n_ && col < n_)
          it.valueRef() += kb_.coeff(r - n_, col);
        else if (r >= n_ && r < 2 * n_ && col < 2 * n_)
          it.valueRef() += cb_.coeff(r - n_, col - n_);
      }
    ls_.copy(J_, J);
  }

  enum class Split { none, body, elements };
  Split split_ = Split::none;
  bool implicit_ = true, fixed_ = false, imex_ = false;
  SpMat kb_, cb_;  // imex: the body operator at kb_t_
  double kb_t_ = 0.0;
  Vec body_rhs_;
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
  c.reads = {"rtol",
             "atol",
             "step",
             "step_control",
             "max_step",
             "table",
             "imex",
             "linear_solver",
             "newton_coefficient",
             "max_iterations",
             "max_steps",
             "formulation",
             "penalty_stiffness",
             "penalty_damping"};
  return {"arkode", [] { return std::make_unique<ArkodeIntegrator>(); },
          "ARKODE (SUNDIALS): implicit (DIRK, ESDIRK), explicit or additive (IMEX) Runge-Kutta "
          "tables by name",
          c};
}

}  // namespace evas
