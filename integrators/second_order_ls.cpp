// Second-order linear solver (see second_order_ls.h for the reduction).
#include "integrators/second_order_ls.h"

#include <klu.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>
#include <sundials/sundials_nvector.h>

#include <algorithm>
#include <stdexcept>

#include "dae/sparse_util.h"

namespace evas {

namespace {
// Dense up to this size: a dense LU of the engine's full 72 x 72 matrix is
// several times faster than KLU's on the same entries; above it the cubic cost
// of a dense LU loses to KLU's on a sparse pattern.
constexpr int kDenseSize = 200;
// ... and up to kDenseFullSize when the pattern is this full already: modal
// bodies with static-correction modes couple every coordinate of a body with
// every other through the bearings (the engine on its 204-coordinate basis:
// 99 % of the entries), and KLU on such a pattern spends its time on the
// sparse bookkeeping; measured on that basis (IDA rtol 1e-7, six cycles):
// 15.4 s dense against 47.9 s KLU (docs/engine-bodies.md).
constexpr int kDenseFullSize = 800;
constexpr double kDenseFill = 0.25;
// Solves on one dense factorization before its inverse is formed (see solve_matrix).
constexpr int kInvertAfter = 40;
}  // namespace

struct SecondOrderSolver::Klu {
  klu_common common;
  klu_symbolic* symbolic = nullptr;
  klu_numeric* numeric = nullptr;
  Klu() { klu_defaults(&common); }
  ~Klu() {
    if (numeric) klu_free_numeric(&numeric, &common);
    if (symbolic) klu_free_symbolic(&symbolic, &common);
  }
  Klu(const Klu&) = delete;
  Klu& operator=(const Klu&) = delete;
};

SecondOrderSolver::SecondOrderSolver(const SpMat& pattern)
    : n_(static_cast<int>(pattern.rows())), K_(pattern), C_(pattern) {
  if (pattern.rows() != pattern.cols())
    throw std::logic_error("second-order solver: the Jacobian pattern is not square");
  K_.makeCompressed();
  C_.makeCompressed();
  // The reduced matrix has the pattern of K plus the diagonal.
  std::vector<Triplet> trip;
  trip.reserve(static_cast<std::size_t>(K_.nonZeros() + n_));
  for (int c = 0; c < n_; ++c) {
    trip.emplace_back(c, c, 0.0);
    for (SpMat::InnerIterator it(K_, c); it; ++it) trip.emplace_back(it.row(), c, 0.0);
  }
  Ss_.resize(n_, n_);
  Ss_.setFromTriplets(trip.begin(), trip.end());
  Ss_.makeCompressed();
  dense_ = n_ <= kDenseSize ||
           (n_ <= kDenseFullSize &&
            static_cast<double>(Ss_.nonZeros()) >= kDenseFill * static_cast<double>(n_) * n_);
  rhs_ = Vec::Zero(n_);
  xq_ = Vec::Zero(n_);
  if (dense_) {
    S_ = Mat::Identity(n_, n_);
    Cd_ = Mat::Zero(n_, n_);
    Sinv_ = Mat::Identity(n_, n_);
    inverse_work_.piv.assign(static_cast<std::size_t>(n_), 0);
    inverse_work_.U = Mat::Zero(n_, 4);
    inverse_work_.d.assign(4, 0.0);
    invert_after_ = kInvertAfter;
    lu_ = std::make_unique<Eigen::PartialPivLU<Eigen::Ref<Mat>>>(S_);
    Ss_.resize(0, 0);
  } else {
    // K's pattern must hold every entry of K_ in Ss_ at the same (row, col):
    // it does (Ss_ = K's pattern + diagonal), so values are added by position.
    diag_.resize(static_cast<std::size_t>(n_));
    for (int i = 0; i < n_; ++i)
      diag_[static_cast<std::size_t>(i)] = dae::value_position(Ss_, i, i);
    klu_ = std::make_unique<Klu>();
    klu_->symbolic = klu_analyze(n_, Ss_.outerIndexPtr(), Ss_.innerIndexPtr(), &klu_->common);
    if (!klu_->symbolic) throw RunError("second-order solver: KLU symbolic analysis failed");
  }
}

SecondOrderSolver::~SecondOrderSolver() = default;

void SecondOrderSolver::set_mass_diagonal(const Vec& m) {
  if (m.size() != 0 && m.size() != n_)
    throw std::logic_error("second-order solver: mass diagonal of the wrong size");
  m_ = m;
}

void SecondOrderSolver::set_coefficients(double a, double b, double c, double d, double e) {
  a_ = a;
  b_ = b;
  c_ = c;
  d_ = d;
  e_ = e;
}

bool SecondOrderSolver::factor() {
  if (!factor_matrix(b_ * c_, -a_ * e_, -a_ * d_)) return false;
  if (dense_) {  // C dense for the right-hand side of solve()
    Cd_.setZero();
    const int* outer = C_.outerIndexPtr();
    const int* inner = C_.innerIndexPtr();
    for (int col = 0; col < n_; ++col)
      for (int k = outer[col]; k < outer[col + 1]; ++k) Cd_(inner[k], col) = C_.valuePtr()[k];
  }
  fa_ = a_;
  fb_ = b_;
  fd_ = d_;
  fe_ = e_;
  return true;
}

bool SecondOrderSolver::factor_matrix(double kk, double cc, double ii) {
  const double* kv = K_.valuePtr();
  const double* cv = C_.valuePtr();
  const int* outer = K_.outerIndexPtr();
  const int* inner = K_.innerIndexPtr();
  if (dense_) {
    S_.setZero();
    for (int col = 0; col < n_; ++col) {
      double* s = S_.col(col).data();
      for (int k = outer[col]; k < outer[col + 1]; ++k) s[inner[k]] += kk * kv[k] + cc * cv[k];
    }
    if (m_.size() == 0)
      S_.diagonal().array() += ii;
    else
      S_.diagonal() += ii * m_;
    // a matrix like the last one, which served more solves than the inverse
    // costs, is inverted at once, without the LU (see solve_matrix); singular
    // when a pivot vanishes against the largest (no allocation, unlike rcond())
    const bool invert = solves_ > kInvertAfter;
    solves_ = 0;
    if (invert) {
      invert_after_ = 0;
      Sinv_ = S_;
      double pmin = 0.0, pmax = 0.0;
      inverse_ready_ = invert_in_place(Sinv_, inverse_work_, pmin, pmax);
      return inverse_ready_ && pmin > 1e-15 * pmax;
    }
    invert_after_ = kInvertAfter;
    inverse_ready_ = false;
    lu_->compute(S_);  // in place: S_ now holds L and U
    const auto u = S_.diagonal().cwiseAbs();
    return u.minCoeff() > 1e-15 * u.maxCoeff();
  }
  // Ss_ has K's pattern plus the diagonal, in the same column order: walk both.
  double* sv = Ss_.valuePtr();
  std::fill(sv, sv + Ss_.nonZeros(), 0.0);
  const int* souter = Ss_.outerIndexPtr();
  const int* sinner = Ss_.innerIndexPtr();
  for (int col = 0; col < n_; ++col) {
    int p = souter[col];
    for (int k = outer[col]; k < outer[col + 1]; ++k) {
      while (sinner[p] != inner[k]) ++p;
      sv[p] += kk * kv[k] + cc * cv[k];
    }
  }
  for (int i = 0; i < n_; ++i)
    sv[diag_[static_cast<std::size_t>(i)]] += m_.size() == 0 ? ii : ii * m_[i];
  // refactorize with the old pivots (allocates nothing); a full factorization
  // (allocates) the first time and when the pivots have gone bad
  constexpr double kKluRcond = 1e-12;
  Klu& k = *klu_;
  int* cp = Ss_.outerIndexPtr();
  int* ri = Ss_.innerIndexPtr();
  bool ok = k.numeric && klu_refactor(cp, ri, sv, k.symbolic, k.numeric, &k.common) &&
            klu_rcond(k.symbolic, k.numeric, &k.common) && k.common.rcond > kKluRcond;
  if (!ok) {
    if (k.numeric) klu_free_numeric(&k.numeric, &k.common);
    k.numeric = klu_factor(cp, ri, sv, k.symbolic, &k.common);
    ok = k.numeric && klu_rcond(k.symbolic, k.numeric, &k.common) && k.common.rcond > 1e-15;
  }
  return ok;
}

void SecondOrderSolver::solve_matrix(const double* r, double* x) {
  Eigen::Map<const Vec> rv(r, n_);
  if (dense_) {
    // After kInvertAfter solves on one factorization, S^-1 = U^-1 L^-1 P is
    // formed from the factors and each further solve is one matrix-vector
    // product: at n = 72 (x86-64-v3) 0.34 us against 1.2 us for the two
    // triangular solves, which vectorize less well. Forming it takes 37 us,
    // paid back after about 40 solves: a matrix refactorized sooner (IDA,
    // ~30 solves per factorization on the engine) is never inverted, one kept
    // long (generalized-alpha, ~110) is, and either way the cost is at most
    // twice that of the better choice made in hindsight (the rent-or-buy
    // argument). A matrix that follows one which served more than kInvertAfter
    // solves is inverted at once by Gauss-Jordan, without an LU (n^3 against
    // 4 n^3 / 3 multiply-adds): an integrator that keeps its matrices long
    // keeps doing so (that gives up the bound of two for a matrix that, unlike
    // the one before it, serves few solves). The inverse's error, of order
    // cond(S) eps, only slows a modified Newton iteration that already runs on
    // an old matrix (Higham, Accuracy and Stability of Numerical Algorithms,
    // 2nd ed. 2002, ch. 14).
    if (++solves_ <= invert_after_) {
      xq_.noalias() = lu_->permutationP() * rv;
      S_.triangularView<Eigen::UnitLower>().solveInPlace(xq_);
      S_.triangularView<Eigen::Upper>().solveInPlace(xq_);
    } else {
      if (!inverse_ready_) {
        inverse_ready_ = true;
        // P as a matrix, column i holding a 1 in row indices(i) (an in-place
        // permutation product would allocate its bookkeeping)
        const auto& perm = lu_->permutationP().indices();
        Sinv_.setZero();
        for (int i = 0; i < n_; ++i) Sinv_(perm[i], i) = 1.0;
        S_.triangularView<Eigen::UnitLower>().solveInPlace(Sinv_);
        S_.triangularView<Eigen::Upper>().solveInPlace(Sinv_);
      }
      xq_.noalias() = Sinv_ * rv;
    }
  } else {
    xq_ = rv;
    klu_solve(klu_->symbolic, klu_->numeric, n_, 1, xq_.data(), &klu_->common);
  }
  Eigen::Map<Vec>(x, n_) = xq_;
}

void SecondOrderSolver::solve(const double* r, double* x) {
  Eigen::Map<const Vec> rq(r, n_), rv(r + n_, n_);
  // rhs = b r_v - d r_q - e C r_q
  if (dense_)
    rhs_.noalias() = Cd_ * rq;
  else
    rhs_.noalias() = C_ * rq;
  if (m_.size() == 0)
    rhs_ = fb_ * rv - fd_ * rq - fe_ * rhs_;
  else
    rhs_ = fb_ * rv - fd_ * m_.cwiseProduct(rq) - fe_ * rhs_;
  solve_matrix(rhs_.data(), rhs_.data());  // rhs_ now holds x_q
  Eigen::Map<Vec> xq(x, n_), xv(x + n_, n_);
  xv = (rq - fa_ * rhs_) / fb_;  // reads r_q before x_q overwrites it (r may alias x)
  xq = rhs_;
}

// ---- SUNDIALS wrappers ----
namespace sundials {
namespace {

SUNMatrix_ID matrix_id(SUNMatrix) { return SUNMATRIX_CUSTOM; }
int matrix_zero(SUNMatrix) { return 0; }  // the callback writes K, C afresh
int matrix_copy(SUNMatrix, SUNMatrix) { return 0; }
int matrix_scale_add_identity(realtype c, SUNMatrix A) {
  auto* solver = static_cast<SecondOrderSolver*>(A->content);
  solver->set_coefficients(1.0, c, -c, 1.0, -c);
  return 0;
}
void matrix_destroy(SUNMatrix A) {
  A->content = nullptr;  // the solver is owned by the caller
  SUNMatFreeEmpty(A);
}
SUNMatrix matrix_clone(SUNMatrix A) {
  return second_order_matrix(A->sunctx, static_cast<SecondOrderSolver*>(A->content));
}

SUNLinearSolver_Type ls_type(SUNLinearSolver) { return SUNLINEARSOLVER_DIRECT; }
SUNLinearSolver_ID ls_id(SUNLinearSolver) { return SUNLINEARSOLVER_CUSTOM; }
int ls_initialize(SUNLinearSolver) { return SUNLS_SUCCESS; }
int ls_setup(SUNLinearSolver S, SUNMatrix) {
  auto* solver = static_cast<SecondOrderSolver*>(S->content);
  return solver->factor() ? SUNLS_SUCCESS : SUNLS_LUFACT_FAIL;
}
int ls_solve(SUNLinearSolver S, SUNMatrix, N_Vector x, N_Vector b, realtype) {
  auto* solver = static_cast<SecondOrderSolver*>(S->content);
  solver->solve(N_VGetArrayPointer(b), N_VGetArrayPointer(x));
  return SUNLS_SUCCESS;
}
sunindextype ls_last_flag(SUNLinearSolver) { return 0; }
int ls_free(SUNLinearSolver S) {
  S->content = nullptr;  // owned by the caller
  SUNLinSolFreeEmpty(S);
  return SUNLS_SUCCESS;
}

}  // namespace

SUNMatrix second_order_matrix(SUNContext ctx, SecondOrderSolver* solver) {
  SUNMatrix A = SUNMatNewEmpty(ctx);
  if (!A) throw RunError("second-order solver: SUNMatNewEmpty failed");
  A->ops->getid = matrix_id;
  A->ops->zero = matrix_zero;
  A->ops->copy = matrix_copy;
  A->ops->scaleaddi = matrix_scale_add_identity;
  A->ops->clone = matrix_clone;
  A->ops->destroy = matrix_destroy;
  A->content = solver;
  return A;
}

SUNLinearSolver second_order_linear_solver(SUNContext ctx, SecondOrderSolver* solver) {
  SUNLinearSolver S = SUNLinSolNewEmpty(ctx);
  if (!S) throw RunError("second-order solver: SUNLinSolNewEmpty failed");
  S->ops->gettype = ls_type;
  S->ops->getid = ls_id;
  S->ops->initialize = ls_initialize;
  S->ops->setup = ls_setup;
  S->ops->solve = ls_solve;
  S->ops->lastflag = ls_last_flag;
  S->ops->free = ls_free;
  S->content = solver;
  return S;
}

}  // namespace sundials
}  // namespace evas
