// Dense kernels in one fixed order of operations for the first-order implicit
// DAE path (integrators/implicit_radau.cpp, dae/implicit_form.cpp): LU with
// partial pivoting, matrix-vector products and a weighted squared norm.
//
// Eigen's PartialPivLU (blocked, GEMM updates), its matrix-vector products and
// squaredNorm sum in as many partial sums as the vector unit has lanes and use
// fused multiply-adds with AVX2, so Radau IIA's digits differed between the
// portable and the x86-64-v3 build (Andrews index-3, rtol 1e-10: 4.30 and 3.43
// digits; docs/problems.md, "Reproducible digits"). These are plain loops
// (see dae/fixed_order_dense.h): every build adds in the order written here.
#pragma once

#include <vector>

#include "model/types.h"

namespace evas::dae {

/// LU with partial pivoting (the first largest |pivot| of a column), row
/// operations in a fixed order.
class FixedOrderLU {
 public:
  /// Factors A; false when a pivot is zero or not finite.
  bool factor(const Mat& A);
  /// x = A^-1 b (x may not alias b).
  void solve(const Vec& b, Vec& x) const;

 private:
  Mat lu_;
  std::vector<Eigen::Index> perm_;
};

/// y = A x, each row summed from the first column on (y may not alias x).
void mat_vec_fixed_order(const Mat& A, const Vec& x, Vec& y);

/// sum_i (a_i w_i)^2 from i = 0 on.
double weighted_squared_norm(const Vec& a, const Vec& w);

}  // namespace evas::dae
