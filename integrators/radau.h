// Radau IIA, three stages, order 5 (integrators/radau.cpp): its tableau and the
// transformation of its Newton iteration, computed from the defining formulas
// (Hairer & Wanner, Solving ODEs II, 2nd ed. 1996, sections IV.5 and IV.8).
#pragma once

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <complex>
#include <utility>
#include <vector>

#include "model/types.h"

namespace evas {

struct RadauTableau {
  std::array<double, 3> c;
  Eigen::Matrix3d A, D;    // D = A^-1
  double g;                // real eigenvalue of D
  std::complex<double> l;  // complex eigenvalue of D (Im > 0)
  Eigen::Matrix3cd V;      // D = V diag(g, l, conj(l)) V^-1
  Eigen::Matrix3cd Vinv;
  double b0;                // weight of F(y_n) in the embedded formula: 1 / g
  std::array<double, 3> e;  // yhat - y = h b0 F(y_n) + sum_j e_j Z_j
};

/// The tableau (c, A), D = A^-1, its eigen-decomposition and the embedded
/// order-3 estimate's coefficients.
RadauTableau radau_iia5_tableau();

// Dense LU with partial pivoting of a complex matrix held as its real and
// imaginary parts (column-major), pivoting on |re| + |im| as LAPACK's zgetrf
// does (izamax): no complex modulus (a hypot per candidate) in the search, and
// the updates run over contiguous real columns.
class SplitComplexLU {
 public:
  void resize(int n) {
    n_ = n;
    re_.setZero(n, n);
    im_.setZero(n, n);
    perm_.assign(static_cast<std::size_t>(n), 0);
  }
  Mat& re() { return re_; }
  Mat& im() { return im_; }

  bool factor() {
    const int n = n_;
    for (int k = 0; k < n; ++k) {
      int p = k;
      double best = std::abs(re_(k, k)) + std::abs(im_(k, k));
      for (int i = k + 1; i < n; ++i) {
        const double m = std::abs(re_(i, k)) + std::abs(im_(i, k));
        if (m > best) {
          best = m;
          p = i;
        }
      }
      if (!(best > 0.0) || !std::isfinite(best)) return false;
      perm_[static_cast<std::size_t>(k)] = p;
      if (p != k) {
        re_.row(k).swap(re_.row(p));
        im_.row(k).swap(im_.row(p));
      }
      const double dr = re_(k, k), di = im_(k, k), den = dr * dr + di * di;
      const double ir = dr / den, ii = -di / den;
      double* lr = re_.col(k).data();
      double* li = im_.col(k).data();
      for (int i = k + 1; i < n; ++i) {
        const double ar = lr[i], ai = li[i];
        lr[i] = ar * ir - ai * ii;
        li[i] = ar * ii + ai * ir;
      }
      for (int j = k + 1; j < n; ++j) {
        const double ur = re_(k, j), ui = im_(k, j);
        double* rj = re_.col(j).data();
        double* ij = im_.col(j).data();
        for (int i = k + 1; i < n; ++i) {
          rj[i] -= lr[i] * ur - li[i] * ui;
          ij[i] -= lr[i] * ui + li[i] * ur;
        }
      }
    }
    return true;
  }

  /// (xr + i xi) = A^-1 (xr + i xi), in place.
  void solve(Vec& xr, Vec& xi) const {
    const int n = n_;
    for (int k = 0; k < n; ++k) {
      const int p = perm_[static_cast<std::size_t>(k)];
      if (p != k) {
        std::swap(xr[k], xr[p]);
        std::swap(xi[k], xi[p]);
      }
    }
    for (int k = 0; k < n; ++k) {  // L (unit diagonal), by columns
      const double br = xr[k], bi = xi[k];
      const double* lr = re_.col(k).data();
      const double* li = im_.col(k).data();
      for (int i = k + 1; i < n; ++i) {
        xr[i] -= lr[i] * br - li[i] * bi;
        xi[i] -= lr[i] * bi + li[i] * br;
      }
    }
    for (int k = n - 1; k >= 0; --k) {  // U, by columns
      const double dr = re_(k, k), di = im_(k, k), den = dr * dr + di * di;
      const double br = (xr[k] * dr + xi[k] * di) / den, bi = (xi[k] * dr - xr[k] * di) / den;
      xr[k] = br;
      xi[k] = bi;
      const double* ur = re_.col(k).data();
      const double* ui = im_.col(k).data();
      for (int i = 0; i < k; ++i) {
        xr[i] -= ur[i] * br - ui[i] * bi;
        xi[i] -= ur[i] * bi + ui[i] * br;
      }
    }
  }

 private:
  int n_ = 0;
  Mat re_, im_;
  std::vector<int> perm_;
};

}  // namespace evas
