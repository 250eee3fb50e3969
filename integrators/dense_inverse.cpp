#include "integrators/dense_inverse.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace evas {

// Step k of the elimination (after the row exchange): with m the pivot column,
// d = 1 / a_kk and u = -d m without its row k (u_k = 0), every column j becomes
// a_j + u a_kj in its rows i != k and d a_kj in row k; column k itself, which
// would become e_k, stores u + d e_k instead (the inverse builds up in place).
// Row k is set, not updated: a_kj + (d - 1) a_kj would lose the digits of a
// small d. Steps are taken in blocks of kBlock pivots: within a block every
// step is applied at once to the block's own columns, which hold the pivots,
// and the u and d are kept; the other columns then take the block's steps
// together, a_j <- a_j + U c with c_l = a_kj + sum_{i<l} U_ki c_i (k = k0 + l:
// the values a_kj as each step would have found them), then rows k set to
// d_l c_l + sum_{i>l} U_ki c_i, so that each column is read and written once
// per block instead of once per step.
bool invert_in_place(Mat& A, DenseInverseWork& w, double& pmin, double& pmax) {
  constexpr int kBlock = 4;
  const int n = static_cast<int>(A.rows());
  if (static_cast<int>(w.piv.size()) != n) w.piv.assign(static_cast<std::size_t>(n), 0);
  if (w.U.rows() != n) w.U.resize(n, kBlock);
  w.d.resize(kBlock);
  double* a = A.data();
  const auto col = [&](int j) { return a + static_cast<std::ptrdiff_t>(j) * n; };
  pmin = std::numeric_limits<double>::infinity();
  pmax = 0.0;
  for (int k0 = 0; k0 < n; k0 += kBlock) {
    const int nb = std::min(kBlock, n - k0);
    for (int l = 0; l < nb; ++l) {
      const int k = k0 + l;
      double* ak = col(k);
      int p = k;
      double big = std::abs(ak[k]);
      for (int i = k + 1; i < n; ++i)
        if (std::abs(ak[i]) > big) {
          big = std::abs(ak[i]);
          p = i;
        }
      if (!(big > 0.0) || !std::isfinite(big)) return false;
      pmin = std::min(pmin, big);
      pmax = std::max(pmax, big);
      w.piv[static_cast<std::size_t>(k)] = p;
      if (p != k) {
        for (int j = 0; j < n; ++j) std::swap(col(j)[k], col(j)[p]);
        for (int i = 0; i < l; ++i) std::swap(w.U(k, i), w.U(p, i));
      }
      const double d = 1.0 / ak[k];
      w.d[static_cast<std::size_t>(l)] = d;
      double* __restrict u = w.U.col(l).data();
      for (int i = 0; i < n; ++i) u[i] = -d * ak[i];
      u[k] = 0.0;
      for (int j = k0; j < k0 + nb; ++j) {  // the block's columns at once
        if (j == k) continue;
        double* __restrict aj = col(j);
        const double s = aj[k];
        for (int i = 0; i < n; ++i) aj[i] += u[i] * s;
        aj[k] = d * s;
      }
      for (int i = 0; i < n; ++i) ak[i] = u[i];
      ak[k] = d;
    }
    // the other columns take the block's nb steps together
    for (int j = 0; j < n; ++j) {
      if (j >= k0 && j < k0 + nb) continue;
      double* __restrict aj = col(j);
      double c[kBlock] = {0.0, 0.0, 0.0, 0.0};
      for (int l = 0; l < nb; ++l) {
        double s = aj[k0 + l];
        for (int i = 0; i < l; ++i) s += w.U(k0 + l, i) * c[i];
        c[l] = s;
      }
      if (nb == kBlock) {
        const double* __restrict u0 = w.U.col(0).data();
        const double* __restrict u1 = w.U.col(1).data();
        const double* __restrict u2 = w.U.col(2).data();
        const double* __restrict u3 = w.U.col(3).data();
        for (int i = 0; i < n; ++i)
          aj[i] += u0[i] * c[0] + u1[i] * c[1] + u2[i] * c[2] + u3[i] * c[3];
      } else {
        for (int l = 0; l < nb; ++l) {
          const double* __restrict ul = w.U.col(l).data();
          for (int i = 0; i < n; ++i) aj[i] += ul[i] * c[l];
        }
      }
      for (int l = 0; l < nb; ++l) {
        double s = w.d[static_cast<std::size_t>(l)] * c[l];
        for (int i = l + 1; i < nb; ++i) s += w.U(k0 + l, i) * c[i];
        aj[k0 + l] = s;
      }
    }
  }
  // row exchanges of A are column exchanges of A^-1, undone in reverse order
  for (int k = n - 1; k >= 0; --k) {
    const int p = w.piv[static_cast<std::size_t>(k)];
    if (p != k) A.col(k).swap(A.col(p));
  }
  return true;
}

}  // namespace evas
