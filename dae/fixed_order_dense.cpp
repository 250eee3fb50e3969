// Small dense solves in one fixed order (see fixed_order_dense.h): plain loops
// only, no Eigen expression that reduces (products, dot, norms, LU).
#include "dae/fixed_order_dense.h"

#include <cmath>
#include <utility>

namespace evas::dae {

bool solve_fixed_order(Mat A, const Vec& b, Vec& x) {
  const Eigen::Index n = A.rows();
  x = b;
  for (Eigen::Index k = 0; k < n; ++k) {
    Eigen::Index p = k;
    for (Eigen::Index i = k + 1; i < n; ++i)
      if (std::abs(A(i, k)) > std::abs(A(p, k))) p = i;
    if (!(A(p, k) != 0.0)) return false;
    if (p != k) {
      for (Eigen::Index j = 0; j < n; ++j) std::swap(A(k, j), A(p, j));
      std::swap(x[k], x[p]);
    }
    for (Eigen::Index i = k + 1; i < n; ++i) {
      const double l = A(i, k) / A(k, k);
      if (l == 0.0) continue;
      for (Eigen::Index j = k + 1; j < n; ++j) A(i, j) -= l * A(k, j);
      x[i] -= l * x[k];
    }
  }
  for (Eigen::Index i = n - 1; i >= 0; --i) {
    double s = x[i];
    for (Eigen::Index j = i + 1; j < n; ++j) s -= A(i, j) * x[j];
    x[i] = s / A(i, i);
  }
  for (Eigen::Index i = 0; i < n; ++i)
    if (!std::isfinite(x[i])) return false;
  return true;
}

bool min_norm_fixed_order(const Mat& G, const Vec& r, Vec& x) {
  const Eigen::Index m = G.rows(), n = G.cols();
  Mat GGt(m, m);
  for (Eigen::Index i = 0; i < m; ++i)
    for (Eigen::Index k = 0; k < m; ++k) {
      double s = 0.0;
      for (Eigen::Index j = 0; j < n; ++j) s += G(i, j) * G(k, j);
      GGt(i, k) = s;
    }
  Vec y;
  if (!solve_fixed_order(GGt, r, y)) return false;
  x.resize(n);
  for (Eigen::Index j = 0; j < n; ++j) {
    double s = 0.0;
    for (Eigen::Index i = 0; i < m; ++i) s += G(i, j) * y[i];
    x[j] = s;
  }
  return true;
}

}  // namespace evas::dae
