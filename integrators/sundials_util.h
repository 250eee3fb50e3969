// Private helpers shared by the SUNDIALS adapters (ida.cpp, cvode.cpp): RAII
// owners for SUNDIALS objects, the copy of an Eigen Jacobian into a SUNMatrix,
// and the bookkeeping common to both adaptive integrators. Not part of the
// public interface: nothing outside integrators/ includes this file.
#pragma once

#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>
#include <sundials/sundials_nonlinearsolver.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "integrators/common.h"
#include "integrators/fast_nvector.h"
#include "integrators/second_order_ls.h"

namespace evas {
namespace sundials {

/// The text of a return-flag name from IDAGetReturnFlagName or
/// CVodeGetReturnFlagName, which hand over a malloc'ed string: freed here.
inline std::string flag_name(char* owned) {
  const std::unique_ptr<char, void (*)(void*)> p(owned, &std::free);
  return p ? std::string(p.get()) : std::string("unknown flag");
}

/// One SUNContext per integrator instance.
class Context {
 public:
  Context() {
    if (SUNContext_Create(nullptr, &ctx_) != 0) throw RunError("SUNContext_Create failed");
  }
  ~Context() { SUNContext_Free(&ctx_); }
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;
  operator SUNContext() const { return ctx_; }

 private:
  SUNContext ctx_ = nullptr;
};

/// Owner of a serial N_Vector.
class Vector {
 public:
  Vector() = default;
  ~Vector() { reset(); }
  Vector(const Vector&) = delete;
  Vector& operator=(const Vector&) = delete;
  void create(int n, SUNContext ctx) {
    reset();
    v_ = N_VNew_Serial(n, ctx);
    if (!v_) throw RunError("N_VNew_Serial failed");
    use_fast_operations(v_);
  }
  void reset() {
    if (v_) N_VDestroy(v_);
    v_ = nullptr;
  }
  N_Vector get() const { return v_; }
  double* data() const { return N_VGetArrayPointer(v_); }

 private:
  N_Vector v_ = nullptr;
};

/// The matrix and direct linear solver of a Newton iteration, chosen by name
/// ("klu": CSC sparse + KLU, "dense": dense + LAPACK-free dense LU), together
/// with the copy of an Eigen matrix of fixed pattern into it.
///
/// Index arrays: SUNDIALS zeroes the whole sparse matrix (indices included,
/// SUNMatZero_Sparse) before every Jacobian call, so the CSC index arrays are
/// converted to sunindextype once here and copied back (memcpy-sized, no
/// allocation) together with the values on each call. The pattern never
/// changes, so KLU's first setup does the symbolic analysis and every later
/// setup only refactors numerically (SUNLinSol_KLU reuses its symbolic data).
class LinearSystem {
 public:
  LinearSystem() = default;
  ~LinearSystem() { reset(); }
  LinearSystem(const LinearSystem&) = delete;
  LinearSystem& operator=(const LinearSystem&) = delete;

  void create(const std::string& kind, const SpMat& pattern, N_Vector y, SUNContext ctx) {
    reset();
    const auto n = static_cast<sunindextype>(pattern.rows());
    if (kind == "klu") {
      sparse_ = true;
      const auto nnz = static_cast<sunindextype>(pattern.nonZeros());
      A_ = SUNSparseMatrix(n, n, nnz, CSC_MAT, ctx);
      if (!A_) throw RunError("SUNSparseMatrix failed");
      colptr_.assign(pattern.outerIndexPtr(), pattern.outerIndexPtr() + pattern.cols() + 1);
      rowind_.assign(pattern.innerIndexPtr(), pattern.innerIndexPtr() + pattern.nonZeros());
      LS_ = SUNLinSol_KLU(y, A_, ctx);
    } else if (kind == "dense") {
      sparse_ = false;
      A_ = SUNDenseMatrix(n, n, ctx);
      if (!A_) throw RunError("SUNDenseMatrix failed");
      LS_ = SUNLinSol_Dense(y, A_, ctx);
    } else {
      throw InputError("integrator: linear_solver '" + kind + "' is unknown (use klu or dense)");
    }
    if (!LS_) throw RunError("creating the " + kind + " linear solver failed");
  }

  /// Copy J (with the pattern given to create()) into the SUNMatrix A.
  void copy(const SpMat& J, SUNMatrix A) const {
    if (sparse_) {
      std::copy(colptr_.begin(), colptr_.end(), SUNSparseMatrix_IndexPointers(A));
      std::copy(rowind_.begin(), rowind_.end(), SUNSparseMatrix_IndexValues(A));
      std::copy(J.valuePtr(), J.valuePtr() + J.nonZeros(), SUNSparseMatrix_Data(A));
    } else {
      SUNMatZero(A);
      for (int c = 0; c < J.outerSize(); ++c) {
        double* col = SUNDenseMatrix_Column(A, c);
        for (SpMat::InnerIterator it(J, c); it; ++it) col[it.row()] = it.value();
      }
    }
  }

  void reset() {
    if (LS_) SUNLinSolFree(LS_);
    if (A_) SUNMatDestroy(A_);
    LS_ = nullptr;
    A_ = nullptr;
    so_.reset();  // after the SUNDIALS objects that point at it
  }

  /// The second-order solver (integrators/second_order_ls.h) on `pattern`, the
  /// pattern of K and C; the Jacobian callback writes K, C into second_order().
  void create_second_order(const SpMat& pattern, SUNContext ctx) {
    reset();
    so_ = std::make_unique<SecondOrderSolver>(pattern);
    A_ = second_order_matrix(ctx, so_.get());
    LS_ = second_order_linear_solver(ctx, so_.get());
    sparse_ = false;
  }
  /// The second-order solver, or nullptr for klu and dense.
  SecondOrderSolver* second_order() const { return so_.get(); }

  SUNMatrix matrix() const { return A_; }
  SUNLinearSolver solver() const { return LS_; }

 private:
  bool sparse_ = true;
  SUNMatrix A_ = nullptr;
  SUNLinearSolver LS_ = nullptr;
  std::vector<sunindextype> colptr_, rowind_;
  std::unique_ptr<SecondOrderSolver> so_;  // linear_solver=second-order
};

/// Owner of a nonlinear solver (CVODE Adams + fixed point).
class NonlinearSolver {
 public:
  NonlinearSolver() = default;
  ~NonlinearSolver() { reset(); }
  NonlinearSolver(const NonlinearSolver&) = delete;
  NonlinearSolver& operator=(const NonlinearSolver&) = delete;
  void set(SUNNonlinearSolver s) {
    reset();
    s_ = s;
  }
  void reset() {
    if (s_) SUNNonlinSolFree(s_);
    s_ = nullptr;
  }
  SUNNonlinearSolver get() const { return s_; }

 private:
  SUNNonlinearSolver s_ = nullptr;
};

/// Exceptions must not cross the C callbacks: a callback stores what it caught
/// here and returns a failure flag; the adapter reports it when the solver
/// fails. A RangeError (a trial state outside an element's valid range) is
/// recoverable (+1: IDA and CVODE cut the step and retry, counted in
/// `recoverable`); anything else is unrecoverable (-1: the solver stops).
struct CallbackGuard {
  std::exception_ptr error;
  long recoverable = 0;
  template <class F>
  int run(F&& f) noexcept {
    try {
      f();
      return 0;
    } catch (const RangeError&) {
      error = std::current_exception();
      ++recoverable;
      return 1;
    } catch (...) {
      error = std::current_exception();
      return -1;
    }
  }
  /// Message of the stored exception ("" if none) and clear it.
  std::string take_message() {
    if (!error) return {};
    std::string msg;
    try {
      std::rethrow_exception(error);
    } catch (const std::exception& e) {
      msg = e.what();
    } catch (...) {
      msg = "unknown exception";
    }
    error = nullptr;
    return msg;
  }
};

/// The failure message of a SUNDIALS adapter: "<head>: <why> at t = ... s
/// (solver's message); the model refused N trial states ..., last: ... (or
/// model error: ...)"; the caller adds the state. Takes the guard's message.
inline std::string failure_message(const std::string& head, const std::string& why, double tn,
                                   const std::string& solver_message, CallbackGuard& guard) {
  std::string msg = head + ": " + why + " at t = " + format_number(tn) + " s";
  if (!solver_message.empty()) msg += " (" + solver_message + ")";
  const std::string cb = guard.take_message();
  if (!cb.empty())
    msg += guard.recoverable > 0 ? "; the model refused " + std::to_string(guard.recoverable) +
                                       " trial states (the solver cut the step each time), "
                                       "last: " +
                                       cb
                                 : "; model error: " + cb;
  return msg;
}

/// Add the counters of a finished segment (before a ReInit) to a running total.
inline void add_segment(IntegratorStats& total, const IntegratorStats& seg) {
  total.steps += seg.steps;
  total.residual_evals += seg.residual_evals;
  total.jacobian_evals += seg.jacobian_evals;
  total.linear_setups += seg.linear_setups;
  total.linear_solves += seg.linear_solves;
  total.nonlinear_iterations += seg.nonlinear_iterations;
  total.error_test_failures += seg.error_test_failures;
  total.convergence_failures += seg.convergence_failures;
}

/// A step below this fraction of |t| moves t by at most about a thousand units
/// in the last place: the solution no longer advances (see step_to).
constexpr double kStalledStepRatio = 1000.0 * std::numeric_limits<double>::epsilon();
/// Steps in a row below kStalledStepRatio |t| that end the run.
constexpr long kStalledSteps = 1000;

/// The stepping loop shared by the IDA and CVODE adapters: one internal step at
/// a time towards tout (so that every step size is seen), stopping early when
/// the solver returns at its stop time exactly at tout. `step(tret)` takes one
/// step and returns the solver flag; `fail(flag, why)` reports a negative
/// flag (why empty), or with flag 0 the loop's own reason: more than max_steps
/// steps, or kStalledSteps steps in a row below kStalledStepRatio |t| (IDA and
/// CVODE keep stepping when t + h rounds to t: on the paper's engine with a
/// clearance of 1 um IDA took 933,717 steps down to 4.9e-36 s in two minutes
/// without leaving t = 7.7e-4 s). `on_step(t, h)` sees every accepted step
/// (the run's step monitor: it may throw to end the run). Returns true when
/// the solver's state is the solution at exactly tout (else the caller
/// interpolates).
template <class Step, class LastStep, class Time, class Fail, class OnStep>
bool step_to(double tout, long max_steps, int tstop_return, IntegratorStats& total, Step step,
             LastStep last_step, Time time, Fail fail, OnStep on_step) {
  long steps = 0, stalled = 0;
  for (double tn = time(); tn < tout;) {
    double tret = tn;
    const int flag = step(tret);
    if (flag < 0) fail(flag, std::string());
    const double h = last_step();
    note_step(total, h);
    tn = time();
    on_step(tn, h);
    if (flag == tstop_return && tret == tout) return true;
    if (++steps > max_steps) fail(0, "more than max_steps steps to reach the output");
    stalled = std::abs(h) <= kStalledStepRatio * std::abs(tn) ? stalled + 1 : 0;
    if (stalled >= kStalledSteps) {
      char text[160];
      std::snprintf(text, sizeof text,
                    "%ld steps in a row below %.2g |t| (the last %.3g s): t no longer advances",
                    kStalledSteps, kStalledStepRatio, h);
      fail(0, text);
    }
  }
  return false;
}

}  // namespace sundials
}  // namespace evas
