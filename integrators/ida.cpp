// IDA (variable-order, variable-step BDF; SUNDIALS 6.4) on the implicit residual
//     F(t, y, yd) = [ yd_q - v ; yd_v + f(t, q, v) ],   y = [q; v]
// with the analytic iteration matrix dF/dy + cj dF/dyd from FirstOrderForm,
// solved by KLU (sparse, fixed pattern) or dense LU.
//
// Consistent initial values need no IDACalcIC: the mass matrix is I, so
// yd = [v; -f(t, q, v)] exactly.
//
// Constrained problems and problems with a mass matrix (docs/theory.md
// section "Constrained systems (DAE)") run on the residual of the formulation
// chosen by settings.formulation (dae/formulation.h; default ggl), y = [q; v;
// lambda (; mu)], with IDASetId marking q, v differential and lambda, mu
// algebraic. Start: q, v projected onto the constraints, v' and lambda from the
// saddle-point system (dae/consistent.h); index-1 then calls IDACalcIC
// (IDA_YA_YDP_INIT), the only formulation whose algebraic part it can solve
// (SUNDIALS IDA user guide, IDACalcIC: semi-explicit index-one systems). The
// local error test leaves out lambda and mu (IDASetSuppressAlg) and, for
// index-3, also v (error_test_id, set with IDASetId after the start; Brenan,
// Campbell & Petzold 1996, ch. 5). The error weights of the higher-index
// components are scaled by h^(index - 1) (IDAWFtolerances,
// DaeForm::weight_power), which keeps round-off in g from failing the Newton
// test at small steps. formulation=penalty runs the ODE of dae/penalty.h.
// Problems with M = I and no constraints take the path above, unchanged.
//
// Element internal states z (Problem::internal_count()) also run on the DAE
// path, y = [q; v; lambda; mu; z], with z differential or algebraic as the
// element declares. Their start: the problem's initial z, the algebraic part
// solved by Newton (DaeForm::consistent_start), then IDACalcIC when the system
// is of index one (no constraints, or the index-1 formulation). With
// constraints, algebraic states leave the error test with lambda and mu;
// without, they stay in it (index one: their error is controlled like y's).
//
// Quasi-static coordinates (Problem::quasi_static) run on the path without
// constraints: their rows are f_i = 0 (no yd_v term; FirstOrderForm, or the
// second-order solver's mass diagonal), their velocities algebraic (index
// one, as f_i depends on v_i through the modal damping). The start gives them
// the static deflection (solver/quasi_static.h, done by the caller or here)
// and yd_v from the time derivative of their rows; their velocities leave the
// local error test (leave_out_quasi_static_velocities, where the reason is).
//
// Stepping: IDA runs in IDA_ONE_STEP mode inside advance() so every accepted
// step is seen (min/max step). Outputs that are not stops are interpolated
// with IDAGetDky (the same interpolant IDA_NORMAL uses); stops are reached
// exactly with IDASetStopTime. The stop time is also set to the problem's next
// stop when not landing, so IDA never steps across a stop it must land on later.
#include <ida/ida.h>
#include <ida/ida_ls.h>
#include <sunnonlinsol/sunnonlinsol_newton.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <memory>
#include <string>

#include "dae/constraint_stats.h"
#include "dae/formulation.h"
#include "dae/penalty.h"
#include "integrators/common.h"
#include "integrators/second_order_ls.h"
#include "integrators/sundials_util.h"
#include "solver/first_order.h"
#include "solver/quasi_static.h"

namespace evas {
namespace {

class IdaIntegrator final : public Integrator {
 public:
  IdaIntegrator() = default;
  ~IdaIntegrator() override { free_memory(); }
  IdaIntegrator(const IdaIntegrator&) = delete;
  IdaIntegrator& operator=(const IdaIntegrator&) = delete;

  std::string name() const override { return "ida"; }
  bool takes_internal_states() const override { return true; }
  bool takes_quasi_static() const override { return true; }

  void init(Problem& p, double t0, const Vec& q0, const Vec& v0,
            const IntegratorSettings& s) override {
    free_memory();
    p_ = &p;
    s_ = s;
    n_ = p.size();
    total_ = IntegratorStats{};
    largest_.clear();
    form_.reset();
    dae_.reset();
    penalty_.reset();
    Problem* model = &p;
    auto formulation = dae::Formulation::ggl;
    if (p.constraint_count() > 0) {
      formulation = dae::parse_formulation(s.formulation, dae::Formulation::ggl);
      if (formulation == dae::Formulation::penalty) {
        penalty_ = std::make_unique<dae::PenaltyProblem>(p, s.penalty_stiffness, s.penalty_damping);
        model = penalty_.get();
      }
    }
    if (p.internal_count() > 0) {
      Vec z;
      p.internal_initial(t0, q0, v0, z);
      p.set_internal(z.data());
    }
    if (model->has_mass() || model->constraint_count() > 0 || model->internal_count() > 0) {
      if (!p.quasi_static().empty())
        throw InputError(
            "ida: quasi-static modes (" + p.describe_coordinate(p.quasi_static().front()) + ", " +
            std::to_string(p.quasi_static().size()) + " in all) are not yet combined with " +
            (model->constraint_count() > 0
                 ? std::string("joints as constraints (use formulation=penalty)")
             : model->has_mass() ? std::string("a mass matrix")
                                 : std::string("element internal states")));
      // (penalty: the wrapped problem has no constraints left, any formulation does)
      const auto f = formulation == dae::Formulation::penalty ? dae::Formulation::ggl : formulation;
      dae_ = std::make_unique<dae::DaeForm>(*model, f, s.baumgarte_alpha, s.baumgarte_beta);
      J_ = dae_->residual_pattern();
    } else {
      form_ = std::make_unique<FirstOrderForm>(*model);
      J_ = form_->residual_pattern();
    }
    const int size = dae_ ? dae_->size() : 2 * n_;

    y_.create(size, ctx_);
    yd_.create(size, ctx_);
    ytmp_.create(size, ctx_);
    if (dae_) id_.create(size, ctx_);
    set_state(t0, q0, v0);

    mem_ = IDACreate(ctx_);
    if (!mem_) throw RunError("ida: IDACreate failed");
    check(IDASetErrHandlerFn(mem_, &IdaIntegrator::error_cb, this), "IDASetErrHandlerFn");
    check(IDAInit(mem_, &IdaIntegrator::residual_cb, t0, y_.get(), yd_.get()), "IDAInit");
    if (dae_ && dae_->m() > 0) {
      check(IDAWFtolerances(mem_, &IdaIntegrator::weights_cb), "IDAWFtolerances");
      use_rescaling_convergence_test();
    } else
      check(IDASStolerances(mem_, s.rtol, s.atol), "IDASStolerances");
    check(IDASetUserData(mem_, this), "IDASetUserData");
    if (s.linear_solver == "second-order") {
      if (dae_)
        throw InputError(
            "ida: linear_solver second-order needs a problem with unit mass, no constraints and "
            "no internal states (this one has " +
            std::string(model->constraint_count() > 0 ? "constraints"
                        : model->has_mass()           ? "a mass matrix"
                                                      : "internal states") +
            "); use klu");
      ls_.create_second_order(model->jacobian_pattern(), ctx_);
      if (!model->quasi_static().empty())
        ls_.second_order()->set_mass_diagonal(mass_diagonal(*model));
      reuse_ = Reuse{};
    } else {
      ls_.create(s.linear_solver, J_, y_.get(), ctx_);
    }
    check(IDASetLinearSolver(mem_, ls_.solver(), ls_.matrix()), "IDASetLinearSolver");
    check(IDASetJacFn(mem_, &IdaIntegrator::jacobian_cb), "IDASetJacFn");
    if (s.max_step > 0.0) check(IDASetMaxStep(mem_, s.max_step), "IDASetMaxStep");
    if (s.max_order > 0) check(IDASetMaxOrd(mem_, std::min(s.max_order, 5)), "IDASetMaxOrd");
    if (s.newton_coefficient > 0.0)
      check(IDASetNonlinConvCoef(mem_, s.newton_coefficient), "IDASetNonlinConvCoef");
    check(IDASetMaxNumSteps(mem_, s.max_steps), "IDASetMaxNumSteps");
    t_ = t0;
    if (dae_) start_dae(t0);
    if (!dae_ && !model->quasi_static().empty()) leave_out_quasi_static_velocities(*model, size);
  }

  bool multipliers(Vec& lambda) const override {
    if (!dae_ || dae_->m() == 0) return false;
    lambda = lambda_;
    return true;
  }

  void advance(double tout, bool land, Vec& q, Vec& v) override {
    WallTimer timer(total_.wall_seconds);
    if (!mem_) throw RunError("ida: advance() before init()");
    last_error_.clear();
    if (!(tout > t_)) {
      throw RunError("ida: output time " + format_number(tout) + " s is not after " +
                     format_number(t_) + " s");
    }
    const double tstop = land ? tout : p_->next_stop(t_);
    if (std::isfinite(tstop) && tstop > current_time())
      check(IDASetStopTime(mem_, tstop), "IDASetStopTime");

    const bool exact = sundials::step_to(
        tout, s_.max_steps, IDA_TSTOP_RETURN, total_,
        [&](double& tret) {
          return IDASolve(mem_, tout, &tret, y_.get(), yd_.get(), IDA_ONE_STEP);
        },
        [&] {
          double h = 0.0;
          IDAGetLastStep(mem_, &h);
          return h;
        },
        [&] { return current_time(); },
        [&](int flag, const std::string& why) {
          fail(flag < 0 ? sundials::flag_name(IDAGetReturnFlagName(flag)) : why);
        },
        [&](double t, double h) { step_done(t, h); });
    if (!exact) {
      const int flag = IDAGetDky(mem_, tout, 0, ytmp_.get());
      if (flag < 0) fail(sundials::flag_name(IDAGetReturnFlagName(flag)));
      get_state(ytmp_.data(), q, v);
    } else {
      get_state(y_.data(), q, v);
    }
    t_ = tout;
    if (p_->constraint_count() > 0) dae::note_constraints(*p_, tout, q, v, total_);
  }

  void restart(double t, const Vec& q, const Vec& v) override {
    WallTimer timer(total_.wall_seconds);
    if (!mem_) throw RunError("ida: restart() before init()");
    // IDAReInit resets IDA's counters: bank them first.
    sundials::add_segment(total_, segment());
    ++total_.restarts;
    if (dae_ && dae_->internal_count() > 0) p_->set_internal(y_.data() + dae_->z_offset());
    set_state(t, q, v);
    check(IDAReInit(mem_, t, y_.get(), yd_.get()), "IDAReInit");
    reuse_ = Reuse{};
    t_ = t;
    if (dae_) start_dae(t);
  }

  IntegratorStats stats() const override {
    IntegratorStats out = total_;
    out.refused_states = guard_.recoverable;
    if (!mem_) return out;
    sundials::add_segment(out, segment());
    double h = 0.0;
    int order = 0;
    IDAGetLastStep(mem_, &h);
    IDAGetLastOrder(mem_, &order);
    out.last_step = h;
    out.last_order = order;
    return out;
  }

 private:
  // y = [q; v], yd = [v; -f(t, q, v)] (consistent since the mass matrix is I);
  // quasi-static coordinates settled first, their yd_v from the time
  // derivative of their rows (quasi_static_accelerations); DAE path: the consistent start of
  // dae/consistent.h.
  void set_state(double t, const Vec& q, const Vec& v) {
    if (dae_) {
      dae_->consistent_start(t, q, v, y_.data(), yd_.data());
      return;
    }
    double* y = y_.data();
    double* yd = yd_.data();
    Problem& model = form_->problem();  // (penalty: the wrapped problem)
    const std::vector<int>& qs = model.quasi_static();
    if (qs.empty()) {
      for (int i = 0; i < n_; ++i) {
        y[i] = q[i];
        y[n_ + i] = v[i];
      }
      form_->rhs(t, y, yd);
      return;
    }
    Vec qq = q, vv = v;
    settle_quasi_static(model, t, qq, vv);
    for (int i = 0; i < n_; ++i) {
      y[i] = qq[i];
      y[n_ + i] = vv[i];
      yd[i] = vv[i];
    }
    model.force(t, y, y + n_, yd + n_);
    for (int i = 0; i < n_; ++i) yd[n_ + i] = -yd[n_ + i];
    Vec a = Eigen::Map<const Vec>(yd + n_, n_);
    quasi_static_accelerations(model, t, qq, vv, a);
    for (int i : qs) yd[n_ + i] = a[i];
  }

  void get_state(const double* y, Vec& q, Vec& v) {
    q.resize(n_);
    v.resize(n_);
    for (int i = 0; i < n_; ++i) {
      q[i] = y[i];
      v[i] = y[n_ + i];
    }
    if (dae_) lambda_ = Eigen::Map<const Vec>(y + 2 * n_, dae_->m());
    if (dae_ && dae_->internal_count() > 0) p_->set_internal(y + dae_->z_offset());
  }

  // The velocities of quasi-static coordinates leave the local error test
  // (IDASetSuppressAlg; their positions stay in it). Such a velocity is
  // algebraic of index one, v_i = -(f_i without c_i v_i) / c_i, but its
  // equation is ill-conditioned at the steps the mode no longer sets: a
  // position error d of the mode moves it by d / tau, tau = c_i / lambda_i =
  // 2 zeta / omega_i (3.2 us at 1 kHz, zeta 0.01). In the error test it asked
  // for steps below tau: on a two-mode check (tests/test_quasi_static.cpp,
  // rtol 1e-11) IDA did not pass 6e-8 s in 10^7 steps; left out, the run
  // takes 40 ms. Measured on the engine (quasi-static above 2 kHz, rtol
  // 1e-5): 96,891 steps in the test, 38,275 left out (docs/engine-speed.md).
  void leave_out_quasi_static_velocities(const Problem& model, int size) {
    id_.create(size, ctx_);
    for (int i = 0; i < size; ++i) id_.data()[i] = 1.0;
    for (int i : model.quasi_static()) id_.data()[n_ + i] = 0.0;
    check(IDASetId(mem_, id_.get()), "IDASetId");
    check(IDASetSuppressAlg(mem_, SUNTRUE), "IDASetSuppressAlg");
  }

  // After IDAInit/IDAReInit on the DAE path: ids, IDACalcIC (index-1), the
  // error-test ids, and the constraint residuals of the start.
  void start_dae(double t0) {
    std::copy(dae_->differential_id().data(), dae_->differential_id().data() + dae_->size(),
              id_.data());
    check(IDASetId(mem_, id_.get()), "IDASetId");
    const bool algebraic = dae_->m() > 0;
    const bool index1 =
        algebraic ? dae_->formulation() == dae::Formulation::index1 : dae_->has_algebraic_states();
    // the multipliers leave the local error test, in every formulation. The
    // SUNDIALS IDA guide discourages this for index-1 systems; measured with
    // index-1's lambda in the test (2026-11-28, docs/problems.md): car axis
    // +0.3 to +0.6 digits, Andrews -1.3 to -2.6 digits and a failure at
    // rtol 1e-12, atol 1e-14. Not kept.
    if (algebraic) check(IDASetSuppressAlg(mem_, SUNTRUE), "IDASetSuppressAlg");
    if (index1) {
      const double span = s_.max_step > 0.0 ? s_.max_step : 1e-3;
      check(IDACalcIC(mem_, IDA_YA_YDP_INIT, t0 + span), "IDACalcIC");
      check(IDAGetConsistentIC(mem_, y_.get(), yd_.get()), "IDAGetConsistentIC");
    }
    if (dae_->error_test_id() != dae_->differential_id()) {
      std::copy(dae_->error_test_id().data(), dae_->error_test_id().data() + dae_->size(),
                id_.data());
      check(IDASetId(mem_, id_.get()), "IDASetId");
    }
    Vec q, v;
    get_state(y_.data(), q, v);
    if (p_->constraint_count() > 0) dae::note_constraints(*p_, t0, q, v, total_);
  }

  double current_time() const {
    double tn = t_;
    IDAGetCurrentTime(mem_, &tn);
    return tn;
  }

  // Counters since the last IDAInit/IDAReInit.
  IntegratorStats segment() const {
    IntegratorStats s;
    long nre_ls = 0, nni = 0;
    IDAGetNumSteps(mem_, &s.steps);
    IDAGetNumResEvals(mem_, &s.residual_evals);
    IDAGetNumLinResEvals(mem_, &nre_ls);  // residual evaluations for FD Jacobians: 0 here
    s.residual_evals += nre_ls;
    IDAGetNumJacEvals(mem_, &s.jacobian_evals);
    if (ls_.second_order())
      s.jacobian_evals = reuse_.evaluations;  // K, C evaluated (the rest re-formed)
    IDAGetNumLinSolvSetups(mem_, &s.linear_setups);
    IDAGetNumNonlinSolvIters(mem_, &nni);
    s.nonlinear_iterations = nni;
    s.linear_solves = nni;  // direct solver: one solve per Newton iteration
    IDAGetNumErrTestFails(mem_, &s.error_test_failures);
    IDAGetNumNonlinSolvConvFails(mem_, &s.convergence_failures);
    return s;
  }

  void check(int flag, const char* what) {
    if (flag < 0) {
      throw RunError(std::string("ida: ") + what + " failed with " +
                     sundials::flag_name(IDAGetReturnFlagName(flag)) +
                     (last_error_.empty() ? "" : " (" + last_error_ + ")"));
    }
  }

  [[noreturn]] void fail(const std::string& why) {
    const double tn = current_time();
    std::string msg = sundials::failure_message("ida", why, tn, last_error_, guard_);
    const double* y = y_.data();
    if (IDAGetDky(mem_, tn, 0, ytmp_.get()) == IDA_SUCCESS) y = ytmp_.data();
    msg += "; state: " + p_->describe_state(tn, y, y + n_);
    msg += where_error_is_largest();
    throw RunError(msg);
  }

  // The component with the largest weighted local error estimate of the last
  // step (IDAGetEstLocalErrors x IDAGetErrWeights): where the step control
  // gave up, e.g. "; largest local error: velocity of body 'block', mode 12".
  // Components left out of the error test (IDASetSuppressAlg: the
  // multipliers, and the velocities of index-3) are not named: their
  // estimates did not fail any test (a corrector failure is named by IDA's
  // own message).
  std::string where_error_is_largest() {
    const long size = static_cast<long>(N_VGetLength(y_.get()));
    sundials::Vector ele, w;
    ele.create(static_cast<int>(size), ctx_);
    w.create(static_cast<int>(size), ctx_);
    if (IDAGetEstLocalErrors(mem_, ele.get()) != IDA_SUCCESS ||
        IDAGetErrWeights(mem_, w.get()) != IDA_SUCCESS)
      return "";
    long best = -1;
    double worst = 0.0;
    const bool suppressed = dae_ && dae_->m() > 0;  // as start_dae sets it
    for (long i = 0; i < size; ++i) {
      if (suppressed && dae_->error_test_id()[i] == 0.0) continue;
      const double e = std::abs(ele.data()[i] * w.data()[i]);
      if (std::isfinite(e) && e > worst) {
        worst = e;
        best = i;
      }
    }
    if (best < 0) return "";
    std::string what;
    if (best < n_)
      what = "position of " + p_->describe_coordinate(static_cast<int>(best));
    else if (best < 2 * n_)
      what = "velocity of " + p_->describe_coordinate(static_cast<int>(best - n_));
    else if (dae_ && best >= dae_->z_offset())
      what = p_->internal_name(static_cast<int>(best - dae_->z_offset()));
    else
      what = "algebraic variable " + std::to_string(best - 2 * n_) + " (multipliers)";
    return "; largest local error (weighted " + format_number(worst) + "): " + what;
  }

  void free_memory() {
    if (mem_) IDAFree(&mem_);
    mem_ = nullptr;
    if (nls_) SUNNonlinSolFree(nls_);
    nls_ = nullptr;
  }

  // The h^p weights of the multipliers (weights_cb) are computed once per
  // step, at the step first tried. After a failed Newton iteration IDA retries
  // with h cut by 4 (up to 10 times) and the same weights, while the round-off
  // of g in the multipliers' corrections grows as 1/h: each retry then fails
  // more surely than the last, and a step at a tight atol never converges
  // (Andrews, GGL, rtol 1e-10, atol 1e-12: ten retries down to h = 2e-15 s).
  // RADAU5 rescales its weights at every change of h (Hairer & Wanner 1996,
  // VII.8). Here IDA's own Newton solver is kept, and its convergence test is
  // wrapped: before IDA's test, the weights of the h^p components are
  // rescaled to the step now tried. Only constrained problems take this path.
  void use_rescaling_convergence_test() {
    nls_ = SUNNonlinSol_Newton(y_.get(), ctx_);
    if (!nls_) throw RunError("ida: SUNNonlinSol_Newton failed");
    check(IDASetNonlinearSolver(mem_, nls_), "IDASetNonlinearSolver");
    const auto* c = static_cast<SUNNonlinearSolverContent_Newton>(nls_->content);
    ida_ctest_ = c->CTest;  // IDA's own test, set by IDASetNonlinearSolver
    ida_ctest_data_ = c->ctest_data;
    if (!ida_ctest_) throw RunError("ida: no convergence test to wrap");
    if (SUNNonlinSolSetConvTestFn(nls_, &IdaIntegrator::conv_test_cb, this) != SUN_NLS_SUCCESS)
      throw RunError("ida: SUNNonlinSolSetConvTestFn failed");
  }

  static int conv_test_cb(SUNNonlinearSolver nls, N_Vector ycor, N_Vector del, realtype tol,
                          N_Vector ewt, void* user) {
    auto* self = static_cast<IdaIntegrator*>(user);
    double h = 0.0;
    IDAGetCurrentStep(self->mem_, &h);
    h = std::abs(h);
    // weights made at h = 0 (the first step) are zero: they stay so
    if (h > 0.0 && self->weights_h_ > 0.0 && h != self->weights_h_) {
      double* wv = N_VGetArrayPointer(ewt);
      const std::vector<int>& power = self->dae_->weight_power();
      for (std::size_t i = 0; i < power.size(); ++i)
        if (power[i] != 0) wv[i] = self->weights_base_[i] * std::pow(h, power[i]);
      self->weights_h_ = h;
    }
    return self->ida_ctest_(nls, ycor, del, tol, ewt, self->ida_ctest_data_);
  }

  static int residual_cb(realtype t, N_Vector y, N_Vector yd, N_Vector r, void* user) {
    auto* self = static_cast<IdaIntegrator*>(user);
    return self->guard_.run([&] {
      if (self->dae_)
        self->dae_->residual(t, N_VGetArrayPointer(y), N_VGetArrayPointer(yd),
                             N_VGetArrayPointer(r));
      else
        self->form_->residual(t, N_VGetArrayPointer(y), N_VGetArrayPointer(yd),
                              N_VGetArrayPointer(r));
    });
  }

  static int jacobian_cb(realtype t, realtype cj, N_Vector y, N_Vector yd, N_Vector /*r*/,
                         SUNMatrix J, void* user, N_Vector, N_Vector, N_Vector) {
    auto* self = static_cast<IdaIntegrator*>(user);
    return self->guard_.run([&] {
      if (self->ls_.second_order()) {
        self->second_order_jacobian(t, cj, N_VGetArrayPointer(y));
        return;
      }
      if (self->dae_)
        self->dae_->residual_jacobian(t, N_VGetArrayPointer(y), N_VGetArrayPointer(yd), cj,
                                      self->J_);
      else
        self->form_->residual_jacobian(t, N_VGetArrayPointer(y), cj, self->J_);
      self->ls_.copy(self->J_, J);
    });
  }

  // linear_solver=second-order: K and C at (t, y) unless the last ones may be
  // reused (younger than jacobian_age steps, no convergence failure since), then
  // the coefficients of IDA's matrix [cj I, -I; K, C + cj I] for the factorization.
  void second_order_jacobian(double t, double cj, const double* y) {
    long steps = 0, fails = 0;
    IDAGetNumSteps(mem_, &steps);
    IDAGetNumNonlinSolvConvFails(mem_, &fails);
    // (IDA's counters restart at IDAReInit, which also resets reuse_)
    const bool fresh = !reuse_.valid || fails != reuse_.fails ||
                       steps - reuse_.step >= static_cast<long>(s_.jacobian_age);
    SecondOrderSolver& so = *ls_.second_order();
    if (fresh) {
      form_->problem().force_jacobian(t, y, y + n_, so.K(), so.C());
      reuse_.valid = true;
      reuse_.step = steps;
      reuse_.fails = fails;
      ++reuse_.evaluations;
    }
    so.set_coefficients(cj, -1.0, 1.0, cj, 1.0);
  }

  // Error weights 1/(rtol |y_i| + atol_i), times h^p_i for the higher-index
  // components (DaeForm::weight_power); h = 0 before the first step. atol_i
  // is atol, but never below what rounding lets the variable reach: 10 eps
  // times the largest |y_i| the run has seen; for the h-scaled components
  // (multipliers, GGL's mu, index-3's v), whose h^p y_i moves the positions,
  // 1000 eps times the largest |q| seen, as the rounding of g(q) reaches them
  // amplified by the constraints' conditioning. An atol below that asks the
  // corrector and the error test to resolve rounding, which no step can:
  // Andrews at atol 1e-14 stalled at steps of 5e-19 s on a velocity of |v|
  // up to 1.4e3 (eps |v| = 3e-13), and GGL's mu failed every step. The factor
  // 1000 is measured: of 100, 300, 1000 and 3000 the smallest with which
  // GGL completes Andrews at rtol 1e-12, atol 1e-14 (docs/problems.md).
  static int weights_cb(N_Vector y, N_Vector w, void* user) {
    auto* self = static_cast<IdaIntegrator*>(user);
    double h = 0.0;
    IDAGetCurrentStep(self->mem_, &h);
    h = std::abs(h);
    const double* yv = N_VGetArrayPointer(y);
    double* wv = N_VGetArrayPointer(w);
    const std::vector<int>& power = self->dae_->weight_power();
    std::vector<double>& seen = self->largest_;
    if (seen.size() != power.size()) seen.assign(power.size(), 0.0);
    double qmax = 0.0;  // the largest |q| seen
    for (std::size_t i = 0; i < power.size(); ++i) {
      seen[i] = std::max(seen[i], std::abs(yv[i]));
      if (i < static_cast<std::size_t>(self->n_)) qmax = std::max(qmax, seen[i]);
    }
    constexpr double kRounding = 10.0 * std::numeric_limits<double>::epsilon();
    constexpr double kAlgebraic = 1000.0 * std::numeric_limits<double>::epsilon();
    self->weights_base_.resize(power.size());
    for (std::size_t i = 0; i < power.size(); ++i) {
      const double atol =
          std::max(self->s_.atol, power[i] == 0 ? kRounding * seen[i] : kAlgebraic * qmax);
      // one rounding for rtol |y| + atol (std::fma) in every build: a build
      // that contracts it to an FMA and one that does not gave weights a bit
      // apart, and the pendulum's digits moved by 0.55 (docs/problems.md)
      const double base = 1.0 / std::fma(self->s_.rtol, std::abs(yv[i]), atol);
      self->weights_base_[i] = base;
      wv[i] = power[i] == 0 ? base : base * std::pow(h, power[i]);
    }
    self->weights_h_ = h;
    return 0;
  }

  static void error_cb(int /*code*/, const char* module, const char* function, char* msg,
                       void* user) {
    auto* self = static_cast<IdaIntegrator*>(user);
    self->last_error_ = std::string(module) + "/" + function + ": " + msg;
  }

  // Declaration order matters: the context outlives everything created in it.
  sundials::Context ctx_;
  sundials::Vector y_, yd_, ytmp_, id_;
  sundials::LinearSystem ls_;
  std::unique_ptr<dae::PenaltyProblem> penalty_;  // formulation=penalty: the ODE run
  std::unique_ptr<FirstOrderForm> form_;          // M = I, no constraints (or penalty)
  std::unique_ptr<dae::DaeForm> dae_;             // mass matrix or constraints
  struct Reuse {
    bool valid = false;    // K, C in the second-order solver are from an evaluation of this segment
    long step = 0;         // IDA's step count at that evaluation
    long fails = 0;        // ... and its convergence-failure count
    long evaluations = 0;  // K, C evaluations in this segment
  } reuse_;
  Vec lambda_;  // multipliers at the last state returned
  SpMat J_;
  Problem* p_ = nullptr;
  IntegratorSettings s_;
  void* mem_ = nullptr;
  SUNNonlinearSolver nls_ = nullptr;  // constrained problems: IDA's Newton, its test wrapped
  SUNNonlinSolConvTestFn ida_ctest_ = nullptr;
  void* ida_ctest_data_ = nullptr;
  std::vector<double> weights_base_;  // 1 / (rtol |y_i| + atol_i) at the last weights
  std::vector<double> largest_;       // the largest |y_i| of this run (weights_cb)
  double weights_h_ = 0.0;            // the h the weights were made for
  int n_ = 0;
  double t_ = 0.0;         // last time handed back to the caller
  IntegratorStats total_;  // finished segments, wall time, restarts, min/max step
  sundials::CallbackGuard guard_;
  std::string last_error_;
};

}  // namespace

IntegratorEntry ida_entry() {
  IntegratorCapabilities c;
  c.declared = true;
  c.adaptive = true;
  c.formulations = {"ggl", "index-3", "index-2", "index-1"};
  c.reads = {"rtol",
             "atol",
             "max_step",
             "linear_solver",
             "jacobian_age",
             "max_order",
             "newton_coefficient",
             "max_steps",
             "formulation",
             "baumgarte_alpha",
             "baumgarte_beta",
             "penalty_stiffness",
             "penalty_damping"};
  return {"ida", [] { return std::make_unique<IdaIntegrator>(); },
          "IDA (SUNDIALS): variable-order BDF on the implicit residual", c};
}

}  // namespace evas
