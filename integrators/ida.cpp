// IDA (variable-order, variable-step BDF; SUNDIALS 6.4) on the implicit residual
//     F(t, y, yd) = [ yd_q - v ; yd_v + f(t, q, v) ],   y = [q; v]
// with the analytic iteration matrix dF/dy + cj dF/dyd from FirstOrderForm,
// solved by KLU (sparse, fixed pattern) or dense LU.
//
// Consistent initial values need no IDACalcIC: the mass matrix is I, so
// yd = [v; -f(t, q, v)] exactly.
//
// Stepping: IDA runs in IDA_ONE_STEP mode inside advance() so every accepted
// step is seen (min/max step). Outputs that are not stops are interpolated
// with IDAGetDky (the same interpolant IDA_NORMAL uses); stops are reached
// exactly with IDASetStopTime. The stop time is also set to the problem's next
// stop when not landing, so IDA never steps across a stop it must land on later.
#include <ida/ida.h>
#include <ida/ida_ls.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "integrators/common.h"
#include "integrators/sundials_util.h"
#include "solver/first_order.h"

namespace evas {
namespace {

class IdaIntegrator final : public Integrator {
 public:
  IdaIntegrator() = default;
  ~IdaIntegrator() override { free_memory(); }
  IdaIntegrator(const IdaIntegrator&) = delete;
  IdaIntegrator& operator=(const IdaIntegrator&) = delete;

  std::string name() const override { return "ida"; }

  void init(Problem& p, double t0, const Vec& q0, const Vec& v0,
            const IntegratorSettings& s) override {
    free_memory();
    p_ = &p;
    s_ = s;
    n_ = p.size();
    total_ = IntegratorStats{};
    form_ = std::make_unique<FirstOrderForm>(p);
    J_ = form_->residual_pattern();

    y_.create(2 * n_, ctx_);
    yd_.create(2 * n_, ctx_);
    ytmp_.create(2 * n_, ctx_);
    set_state(t0, q0, v0);

    mem_ = IDACreate(ctx_);
    if (!mem_) throw RunError("ida: IDACreate failed");
    check(IDASetErrHandlerFn(mem_, &IdaIntegrator::error_cb, this), "IDASetErrHandlerFn");
    check(IDAInit(mem_, &IdaIntegrator::residual_cb, t0, y_.get(), yd_.get()), "IDAInit");
    check(IDASStolerances(mem_, s.rtol, s.atol), "IDASStolerances");
    check(IDASetUserData(mem_, this), "IDASetUserData");
    ls_.create(s.linear_solver, J_, y_.get(), ctx_);
    check(IDASetLinearSolver(mem_, ls_.solver(), ls_.matrix()), "IDASetLinearSolver");
    check(IDASetJacFn(mem_, &IdaIntegrator::jacobian_cb), "IDASetJacFn");
    if (s.max_step > 0.0) check(IDASetMaxStep(mem_, s.max_step), "IDASetMaxStep");
    if (s.max_order > 0) check(IDASetMaxOrd(mem_, std::min(s.max_order, 5)), "IDASetMaxOrd");
    check(IDASetMaxNumSteps(mem_, s.max_steps), "IDASetMaxNumSteps");
    t_ = t0;
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
        [&](int flag) {
          fail(flag < 0 ? sundials::flag_name(IDAGetReturnFlagName(flag))
                        : "more than max_steps steps to reach the output");
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
  }

  void restart(double t, const Vec& q, const Vec& v) override {
    WallTimer timer(total_.wall_seconds);
    if (!mem_) throw RunError("ida: restart() before init()");
    // IDAReInit resets IDA's counters: bank them first.
    sundials::add_segment(total_, segment());
    ++total_.restarts;
    set_state(t, q, v);
    check(IDAReInit(mem_, t, y_.get(), yd_.get()), "IDAReInit");
    t_ = t;
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
  // y = [q; v], yd = [v; -f(t, q, v)] (consistent since the mass matrix is I).
  void set_state(double t, const Vec& q, const Vec& v) {
    double* y = y_.data();
    for (int i = 0; i < n_; ++i) {
      y[i] = q[i];
      y[n_ + i] = v[i];
    }
    form_->rhs(t, y, yd_.data());
  }

  void get_state(const double* y, Vec& q, Vec& v) const {
    q.resize(n_);
    v.resize(n_);
    for (int i = 0; i < n_; ++i) {
      q[i] = y[i];
      v[i] = y[n_ + i];
    }
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
    std::string msg = "ida: " + why + " at t = " + format_number(tn) + " s";
    if (!last_error_.empty()) msg += " (" + last_error_ + ")";
    const std::string cb = guard_.take_message();
    if (!cb.empty())
      msg += guard_.recoverable > 0 ? "; the model refused " + std::to_string(guard_.recoverable) +
                                          " trial states (the solver cut the step each time), "
                                          "last: " +
                                          cb
                                    : "; model error: " + cb;
    const double* y = y_.data();
    if (IDAGetDky(mem_, tn, 0, ytmp_.get()) == IDA_SUCCESS) y = ytmp_.data();
    msg += "; state: " + p_->describe_state(tn, y, y + n_);
    throw RunError(msg);
  }

  void free_memory() {
    if (mem_) IDAFree(&mem_);
    mem_ = nullptr;
  }

  static int residual_cb(realtype t, N_Vector y, N_Vector yd, N_Vector r, void* user) {
    auto* self = static_cast<IdaIntegrator*>(user);
    return self->guard_.run([&] {
      self->form_->residual(t, N_VGetArrayPointer(y), N_VGetArrayPointer(yd),
                            N_VGetArrayPointer(r));
    });
  }

  static int jacobian_cb(realtype t, realtype cj, N_Vector y, N_Vector /*yd*/, N_Vector /*r*/,
                         SUNMatrix J, void* user, N_Vector, N_Vector, N_Vector) {
    auto* self = static_cast<IdaIntegrator*>(user);
    return self->guard_.run([&] {
      self->form_->residual_jacobian(t, N_VGetArrayPointer(y), cj, self->J_);
      self->ls_.copy(self->J_, J);
    });
  }

  static void error_cb(int /*code*/, const char* module, const char* function, char* msg,
                       void* user) {
    auto* self = static_cast<IdaIntegrator*>(user);
    self->last_error_ = std::string(module) + "/" + function + ": " + msg;
  }

  // Declaration order matters: the context outlives everything created in it.
  sundials::Context ctx_;
  sundials::Vector y_, yd_, ytmp_;
  sundials::LinearSystem ls_;
  std::unique_ptr<FirstOrderForm> form_;
  SpMat J_;
  Problem* p_ = nullptr;
  IntegratorSettings s_;
  void* mem_ = nullptr;
  int n_ = 0;
  double t_ = 0.0;         // last time handed back to the caller
  IntegratorStats total_;  // finished segments, wall time, restarts, min/max step
  sundials::CallbackGuard guard_;
  std::string last_error_;
};

}  // namespace

std::unique_ptr<Integrator> make_ida_integrator() { return std::make_unique<IdaIntegrator>(); }

}  // namespace evas
