// Small dense solves in one fixed order of operations, for the consistent
// start of the DAE path (dae/consistent.cpp).
//
// Eigen's dense kernels (products, Householder reflections, LU) sum in as
// many partial sums as the vector unit has lanes and use fused multiply-adds
// where the target has them, so the same source gives results some rounding
// apart in the portable and the x86-64-v3 build (docs/problems.md,
// "Reproducible digits"). These loops are plain scalar code: GCC does not
// reorder a floating-point reduction without -ffast-math and evas is compiled
// with -ffp-contract=off, so every build adds in the order written here.
#pragma once

#include "model/types.h"

namespace evas::dae {

/// Solves A x = b by Gaussian elimination with partial pivoting (the first
/// largest pivot of a column). False when a pivot is zero or the solution is
/// not finite (x then undefined).
bool solve_fixed_order(Mat A, const Vec& b, Vec& x);

/// The minimum-norm solution x = G^T (G G^T)^-1 r of G x = r for G of full
/// row rank. False when G G^T is singular (x then undefined).
bool min_norm_fixed_order(const Mat& G, const Vec& r, Vec& x);

}  // namespace evas::dae
