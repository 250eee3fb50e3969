// In-place inverse of a dense square matrix by Gauss-Jordan elimination with
// partial pivoting (Higham, Accuracy and Stability of Numerical Algorithms,
// 2nd ed. 2002, section 14.4; the elimination with partial pivoting: Golub &
// Van Loan, Matrix Computations, 4th ed. 2013, section 3.4): n^3
// multiply-adds, against n^3/3 + n^3 for an LU and the inverse formed from
// its factors. The pivots are those
// of the LU with partial pivoting (the elimination above the diagonal does not
// change the rows below it), so the same singularity test applies.
#pragma once

#include <vector>

#include "model/types.h"

namespace evas {

struct DenseInverseWork {
  std::vector<int> piv;   ///< row exchanged with row k at step k
  Mat U;                  ///< n x 4: the steps of a block of pivots (dense_inverse.cpp)
  std::vector<double> d;  ///< their reciprocal pivots
};

/// A := A^-1 (A square, column-major). Returns the smallest and largest |pivot|
/// in pmin, pmax; false (A then undefined) when a pivot is exactly zero or not
/// finite. Allocates nothing once `w` has served a matrix of this size.
bool invert_in_place(Mat& A, DenseInverseWork& w, double& pmin, double& pmax);

}  // namespace evas
