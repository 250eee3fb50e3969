// The analytic Jacobian of a Problem (K = df/dq, C = df/dv) against central
// finite differences of f, column by column.
#pragma once

#include <algorithm>
#include <iostream>

#include "model/problem.h"

namespace evas::test_fd {

struct JacobianError {
  double K = 0.0, C = 0.0;
};

/// Largest deviation of a column from its central difference (steps hq on q,
/// hv on v), relative to 1 + max|column| (or 1 + max|matrix| when
/// scale_by_matrix). Columns beyond 1e-6 are printed for diagnosis.
inline JacobianError jacobian_fd_error(Problem& p, double t, Vec q, Vec v, double hq, double hv,
                                       bool scale_by_matrix = false) {
  const int n = p.size();
  SpMat K = p.jacobian_pattern(), C = p.jacobian_pattern();
  p.force_jacobian(t, q.data(), v.data(), K, C);
  const Mat Kd = Mat(K), Cd = Mat(C);
  Vec fp(n), fm(n);
  JacobianError err;
  for (int j = 0; j < n; ++j)
    for (int which = 0; which < 2; ++which) {
      Vec& x = which == 0 ? q : v;
      const double x0 = x[j], h = which == 0 ? hq : hv;
      x[j] = x0 + h;
      p.force(t, q.data(), v.data(), fp.data());
      x[j] = x0 - h;
      p.force(t, q.data(), v.data(), fm.data());
      x[j] = x0;
      const Vec col = (fp - fm) / (2 * h);
      const Mat& J = which == 0 ? Kd : Cd;
      const double scale =
          1.0 + (scale_by_matrix ? J.cwiseAbs().maxCoeff() : J.col(j).cwiseAbs().maxCoeff());
      Eigen::Index r;
      const double e = (col - J.col(j)).cwiseAbs().maxCoeff(&r) / scale;
      if (e > 1e-6)
        std::cout << (which ? "C" : "K") << " col " << j << " row " << r << " fd " << col[r]
                  << " an " << J(r, j) << "\n";
      double& worst = which == 0 ? err.K : err.C;
      worst = std::max(worst, e);
    }
  return err;
}

}  // namespace evas::test_fd
