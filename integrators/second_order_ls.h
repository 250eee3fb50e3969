// A linear solver for the Newton iterations of a second-order problem
// (qdd + f(t, q, v) = 0, K = df/dq, C = df/dv) posed in first order, y = [q; v].
// Both first-order iteration matrices have the block form
//     A = [ a I    b I     ]      IDA  (dF/dy + cj dF/dyd):  a = cj, b = -1, c = 1,  d = cj, e = 1
//         [ c K    d I + e C ]    CVODE (I - gamma J):       a = 1,  b = -gamma, c = gamma, d = 1,
//         e = gamma
// so the velocity block can be eliminated: from the first block row
// x_v = (r_q - a x_q) / b, and the second becomes the n x n system
//     (b c K - a e C - a d I) x_q = b r_v - (d I + e C) r_q,
// whose matrix for IDA is -(K + cj C + cj^2 I): the effective stiffness of a
// Newmark-type method (Geradin & Rixen, Mechanical Vibrations, 3rd ed. 2015,
// section 7.2). It is half the size of A, so a factorization costs about an
// eighth and a solve a quarter of A's (dense counts).
//
// The reduced matrix is factorized dense (partial-pivoting LU; inverted once
// it has served a number of solves, which are then matrix-vector products) up to n = 200
// (the engine: n = 72, body blocks dense and coupled), by KLU above. K and C are kept between
// factorizations: a caller may form the matrix again at a new (a..e) without evaluating the
// Jacobian (Jacobian reuse, counted by the caller).
#pragma once

#include <memory>

#include "integrators/dense_inverse.h"
#include "model/types.h"

struct _generic_SUNMatrix;
struct _generic_SUNLinearSolver;
struct _SUNContext;

namespace evas {

class SecondOrderSolver {
 public:
  /// pattern: the pattern of K and C (Problem::jacobian_pattern()).
  explicit SecondOrderSolver(const SpMat& pattern);
  ~SecondOrderSolver();
  SecondOrderSolver(const SecondOrderSolver&) = delete;
  SecondOrderSolver& operator=(const SecondOrderSolver&) = delete;

  int size() const { return n_; }
  bool dense() const { return dense_; }
  /// K and C to write (values only, on the pattern given).
  SpMat& K() { return K_; }
  SpMat& C() { return C_; }

  /// The mass diagonal m replacing I in the velocity block (d m + e C) and in
  /// factor_matrix's ii term: 0 for quasi-static coordinates
  /// (solver/quasi_static.h). Empty (the default): the identity.
  void set_mass_diagonal(const Vec& m);
  /// Sets the coefficients of A for the next factor().
  void set_coefficients(double a, double b, double c, double d, double e);
  /// Forms the reduced matrix of A from the current K, C and coefficients and
  /// factorizes it; false when the factorization fails (singular).
  bool factor();
  /// x = A^-1 r for the (a..e) of the last factor(); r and x are 2n long and
  /// may alias.
  void solve(const double* r, double* x);

  /// The n x n matrix alone: S = kk K + cc C + ii I (ii diag(m) with a mass
  /// diagonal) from the current K and C,
  /// factorized (false when singular); the Newmark family's effective
  /// stiffness (generalized-alpha, linear acceleration).
  bool factor_matrix(double kk, double cc, double ii);
  /// x = S^-1 r for the last factorization (n long; may alias).
  void solve_matrix(const double* r, double* x);

 private:
  int n_;
  bool dense_;
  SpMat K_, C_;
  Vec m_;                                         // mass diagonal (empty: the identity)
  double a_ = 0, b_ = 0, c_ = 0, d_ = 0, e_ = 0;  // coefficients of the next factor()
  double fa_ = 0, fb_ = 0, fd_ = 0, fe_ = 0;      // ... of the factorization held
  // dense path: S_ factorized in place (LU with partial pivoting); Sinv_ its
  // inverse, formed from the factors on solve invert_after_ + 1 of the
  // factorization, or at once by Gauss-Jordan (dense_inverse.h) in place of the
  // LU when the matrix before served more than kInvertAfter solves
  Mat S_, Cd_, Sinv_;
  long solves_ = 0;        // on the factorization held
  long invert_after_ = 0;  // solves on it before it is inverted
  bool inverse_ready_ = false;
  DenseInverseWork inverse_work_;
  std::unique_ptr<Eigen::PartialPivLU<Eigen::Ref<Mat>>> lu_;
  // sparse path: KLU, refactorizing with the pivots of the last full factorization
  // while its reciprocal condition estimate stays above kKluRcond
  SpMat Ss_;
  std::vector<int> diag_;  // positions of the diagonal in Ss_
  struct Klu;              // KLU's objects (second_order_ls.cpp)
  std::unique_ptr<Klu> klu_;
  Vec rhs_, xq_;
};

namespace sundials {

/// A SUNMatrix that stands for the iteration matrix A of a SecondOrderSolver:
/// it holds no values (the Jacobian callback writes K, C into the solver).
/// zero and copy do nothing (K, C stay in the solver until the next
/// evaluation, which serves as CVODE's saved Jacobian), clone shares the
/// solver, and CVODE's A = c A + I (c = -gamma) sets the coefficients of
/// I - gamma [0, I; -K, -C].
_generic_SUNMatrix* second_order_matrix(_SUNContext* ctx, SecondOrderSolver* solver);
/// A direct SUNLinearSolver on a SecondOrderSolver: setup = factor() (a
/// singular matrix is a recoverable failure), solve = solve().
_generic_SUNLinearSolver* second_order_linear_solver(_SUNContext* ctx, SecondOrderSolver* solver);

}  // namespace sundials
}  // namespace evas
