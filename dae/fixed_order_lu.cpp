// Dense kernels in one fixed order (see fixed_order_lu.h): plain loops only.
#include "dae/fixed_order_lu.h"

#include <cmath>
#include <utility>

namespace evas::dae {

bool FixedOrderLU::factor(const Mat& A) {
  lu_ = A;
  const Eigen::Index n = lu_.rows();
  perm_.assign(static_cast<std::size_t>(n), 0);
  for (Eigen::Index k = 0; k < n; ++k) {
    Eigen::Index p = k;
    for (Eigen::Index i = k + 1; i < n; ++i)
      if (std::abs(lu_(i, k)) > std::abs(lu_(p, k))) p = i;
    perm_[static_cast<std::size_t>(k)] = p;
    const double piv = lu_(p, k);
    if (!(piv != 0.0) || !std::isfinite(piv)) return false;
    if (p != k)
      for (Eigen::Index j = 0; j < n; ++j) std::swap(lu_(k, j), lu_(p, j));
    // multipliers, then the trailing block column by column (column-major)
    for (Eigen::Index i = k + 1; i < n; ++i) lu_(i, k) /= piv;
    for (Eigen::Index j = k + 1; j < n; ++j) {
      const double u = lu_(k, j);
      if (u == 0.0) continue;
      for (Eigen::Index i = k + 1; i < n; ++i) lu_(i, j) -= lu_(i, k) * u;
    }
  }
  return true;
}

void FixedOrderLU::solve(const Vec& b, Vec& x) const {
  const Eigen::Index n = lu_.rows();
  x = b;
  for (Eigen::Index k = 0; k < n; ++k) {
    const Eigen::Index p = perm_[static_cast<std::size_t>(k)];
    if (p != k) std::swap(x[k], x[p]);
  }
  for (Eigen::Index k = 0; k < n; ++k) {  // L (unit diagonal), by columns
    const double xk = x[k];
    if (xk == 0.0) continue;
    for (Eigen::Index i = k + 1; i < n; ++i) x[i] -= lu_(i, k) * xk;
  }
  for (Eigen::Index k = n - 1; k >= 0; --k) {  // U, by columns
    x[k] /= lu_(k, k);
    const double xk = x[k];
    if (xk == 0.0) continue;
    for (Eigen::Index i = 0; i < k; ++i) x[i] -= lu_(i, k) * xk;
  }
}

void mat_vec_fixed_order(const Mat& A, const Vec& x, Vec& y) {
  const Eigen::Index m = A.rows(), n = A.cols();
  y.setZero(m);
  // by columns (contiguous in memory): each y_i still sums j = 0, 1, ... in order
  for (Eigen::Index j = 0; j < n; ++j) {
    const double xj = x[j];
    if (xj == 0.0) continue;
    for (Eigen::Index i = 0; i < m; ++i) y[i] += A(i, j) * xj;
  }
}

double weighted_squared_norm(const Vec& a, const Vec& w) {
  double s = 0.0;
  for (Eigen::Index i = 0; i < a.size(); ++i) {
    const double v = a[i] * w[i];
    s += v * v;
  }
  return s;
}

}  // namespace evas::dae
