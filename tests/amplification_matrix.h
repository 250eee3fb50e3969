// Test-only: figures of a one-step amplification matrix A of the undamped
// oscillator at Omega = omega h (state (q, h v, h^2 a)): its spectral radius,
// and the algorithmic damping ratio and relative period error of its
// principal (complex) root p, xi = -ln|p|^2 / (2 arg p), (T_bar - T)/T =
// Omega / arg p - 1 (Hilber, Hughes & Taylor 1977; Chung & Hulbert 1993).
#pragma once

#include <Eigen/Eigenvalues>
#include <cmath>
#include <complex>

namespace amplification_matrix {

inline double spectral_radius(const Eigen::Matrix3d& A) {
  return Eigen::EigenSolver<Eigen::Matrix3d>(A, false).eigenvalues().cwiseAbs().maxCoeff();
}

struct RootFigures {
  double damping_ratio = 0.0, period_error = 0.0;
};

inline RootFigures principal_root_figures(const Eigen::Matrix3d& A, double W) {
  const auto ev = Eigen::EigenSolver<Eigen::Matrix3d>(A, false).eigenvalues();
  std::complex<double> p = 0;
  for (Eigen::Index j = 0; j < 3; ++j)
    if (ev[j].imag() > 0) p = ev[j];
  const double bar = std::arg(p);
  return {-std::log(std::norm(p)) / (2 * bar), W / bar - 1};
}

}  // namespace amplification_matrix
