#include "integrators/implicit_ida.h"

#include <ida/ida.h>
#include <ida/ida_ls.h>

#include <chrono>
#include <cmath>

#include "integrators/sundials_util.h"

namespace evas {

namespace {

struct Data {
  ImplicitDae* p;
  Mat M, J;
  Vec f;
  sundials::CallbackGuard guard;
  std::string ida_message;  // IDA's own last error message (not printed)
};

void error_message(int, const char*, const char*, char* msg, void* user) {
  static_cast<Data*>(user)->ida_message = msg ? msg : "";
}

int residual(double t, N_Vector y, N_Vector yp, N_Vector r, void* user) {
  auto* d = static_cast<Data*>(user);
  return d->guard.run([&] {
    const int n = d->p->size();
    const double* Y = N_VGetArrayPointer(y);
    const double* YP = N_VGetArrayPointer(yp);
    double* R = N_VGetArrayPointer(r);
    ++d->p->rhs_evals;
    d->p->rhs(t, Y, d->f.data());
    const Eigen::Map<const Vec> ypv(YP, n);
    Eigen::Map<Vec>(R, n).noalias() = d->M * ypv - d->f;
    for (int i = 0; i < n; ++i)
      if (!std::isfinite(R[i]))
        throw RangeError("the residual of " + d->p->component_name(i) + " is not finite");
  });
}

int jacobian(double t, double cj, N_Vector y, N_Vector, N_Vector, SUNMatrix A, void* user, N_Vector,
             N_Vector, N_Vector) {
  auto* d = static_cast<Data*>(user);
  return d->guard.run([&] {
    const int n = d->p->size();
    ++d->p->jacobian_evals;
    d->p->rhs_jacobian(t, N_VGetArrayPointer(y), d->J);
    for (int c = 0; c < n; ++c) {
      double* col = SUNDenseMatrix_Column(A, c);
      for (int r = 0; r < n; ++r) col[r] = cj * d->M(r, c) - d->J(r, c);
    }
  });
}

}  // namespace

ImplicitRun integrate_implicit_ida(ImplicitDae& p, double t_end, const IntegratorSettings& s) {
  if (!(s.rtol > 0.0) || !(s.atol > 0.0)) throw InputError("ida: rtol and atol must be > 0");
  const auto started = std::chrono::steady_clock::now();
  const int n = p.size();
  Data d{&p, p.mass(), Mat::Zero(n, n), Vec::Zero(n), {}, {}};
  ImplicitRun out;
  Vec y0, yp0;
  p.initial(y0, yp0);
  sundials::Context ctx;
  sundials::Vector y, yp, id;
  y.create(n, ctx);
  yp.create(n, ctx);
  id.create(n, ctx);
  bool suppress = false;
  for (int i = 0; i < n; ++i) {
    y.data()[i] = y0(i);
    yp.data()[i] = yp0(i);
    // 1: in the error test; 0: a component of index > 1, left out of it
    id.data()[i] = p.component_index(i) > 1 ? 0.0 : 1.0;
    suppress = suppress || p.component_index(i) > 1;
  }
  void* mem = IDACreate(ctx);
  if (!mem) throw RunError("ida: IDACreate failed");
  struct Free {
    void*& m;
    ~Free() { IDAFree(&m); }
  } free_mem{mem};
  SUNMatrix A = SUNDenseMatrix(n, n, ctx);
  SUNLinearSolver LS = SUNLinSol_Dense(y.get(), A, ctx);
  struct FreeLs {
    SUNMatrix A;
    SUNLinearSolver LS;
    ~FreeLs() {
      SUNLinSolFree(LS);
      SUNMatDestroy(A);
    }
  } free_ls{A, LS};
  auto check = [](int flag, const char* what) {
    if (flag < 0)
      throw RunError(std::string("ida: ") + what + " failed (flag " + std::to_string(flag) + ")");
  };
  check(IDAInit(mem, residual, 0.0, y.get(), yp.get()), "IDAInit");
  check(IDASStolerances(mem, s.rtol, s.atol), "IDASStolerances");
  check(IDASetUserData(mem, &d), "IDASetUserData");
  check(IDASetErrHandlerFn(mem, error_message, &d), "IDASetErrHandlerFn");
  check(IDASetLinearSolver(mem, LS, A), "IDASetLinearSolver");
  check(IDASetJacFn(mem, jacobian), "IDASetJacFn");
  check(IDASetMaxNumSteps(mem, s.max_steps), "IDASetMaxNumSteps");
  if (s.max_order > 0) check(IDASetMaxOrd(mem, s.max_order), "IDASetMaxOrd");
  if (s.max_step > 0.0) check(IDASetMaxStep(mem, s.max_step), "IDASetMaxStep");
  if (suppress) {
    check(IDASetId(mem, id.get()), "IDASetId");
    check(IDASetSuppressAlg(mem, SUNTRUE), "IDASetSuppressAlg");
  }
  check(IDASetStopTime(mem, t_end), "IDASetStopTime");
  double t = 0.0;
  const int flag = IDASolve(mem, t_end, &t, y.get(), yp.get(), IDA_NORMAL);
  out.t = t;
  out.y = Eigen::Map<const Vec>(y.data(), n);
  if (flag < 0) {
    std::string why = d.guard.take_message();
    if (why.empty()) why = d.ida_message;
    double h = 0.0;
    IDAGetCurrentStep(mem, &h);
    out.failure = "ida: " + sundials::flag_name(IDAGetReturnFlagName(flag)) + " at t = " + g6(t) +
                  " (step " + g6(h) + ")" + (why.empty() ? std::string() : ": " + why);
  }
  long v = 0;
  IDAGetNumSteps(mem, &v);
  out.stats.steps = v;
  IDAGetNumResEvals(mem, &v);
  out.stats.residual_evals = v;
  IDAGetNumJacEvals(mem, &v);
  out.stats.jacobian_evals = v;
  IDAGetNumLinSolvSetups(mem, &v);
  out.stats.linear_setups = v;
  IDAGetNumNonlinSolvIters(mem, &v);
  out.stats.nonlinear_iterations = v;
  out.stats.linear_solves = v;
  IDAGetNumErrTestFails(mem, &v);
  out.stats.error_test_failures = v;
  IDAGetNumNonlinSolvConvFails(mem, &v);
  out.stats.convergence_failures = v;
  int order = 0;
  IDAGetLastOrder(mem, &order);
  out.stats.last_order = order;
  IDAGetLastStep(mem, &out.stats.last_step);
  out.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  out.stats.wall_seconds = out.wall;
  return out;
}

}  // namespace evas
