// First-order views of a second-order Problem (see first_order.h for the layout).
//
// Both iteration matrices share one pattern on the 2n x 2n grid:
//   (q, q) block: full diagonal          (cj I in the residual form, 0 in the rhs form)
//   (q, v) block: diagonal               (-I, resp. +I)
//   (v, q) block: pattern of K           (K, resp. -K)
//   (v, v) block: pattern of C + diagonal (C + cj I, resp. -C)
// Full diagonals keep KLU's pivoting happy and let CVODE form I - gamma J in
// place. The positions of every contribution in the value array are found once
// here, so filling a matrix is a handful of indexed additions.
#include "solver/first_order.h"

#include <algorithm>
#include <stdexcept>

#include "dae/internal_blocks.h"
#include "solver/quasi_static.h"

namespace evas {

using dae::value_position;

FirstOrderForm::FirstOrderForm(Problem& p) : p_(p), n_(p.size()), nz_(p.internal_count()) {
  for (int i = 0; i < nz_; ++i)
    if (p.internal_algebraic(i))
      throw InputError(
          p.internal_name(i) +
          ": this integrator takes differential states only, not algebraic ones (use ida)");
  m_ = mass_diagonal(p);
  unit_mass_ = p.quasi_static().empty();
  K_ = p.jacobian_pattern();
  K_.makeCompressed();
  if (K_.rows() != n_ || K_.cols() != n_)
    throw std::logic_error("first_order: jacobian_pattern() is not size() x size()");
  C_ = K_;

  std::vector<Triplet> trip;
  trip.reserve(static_cast<std::size_t>(2 * K_.nonZeros() + 3 * n_));
  for (int i = 0; i < n_; ++i) {
    trip.emplace_back(i, i, 0.0);            // (q, q) diagonal
    trip.emplace_back(i, n_ + i, 0.0);       // (q, v) identity
    trip.emplace_back(n_ + i, n_ + i, 0.0);  // (v, v) diagonal
  }
  for (int c = 0; c < n_; ++c) {
    for (SpMat::InnerIterator it(K_, c); it; ++it) {
      trip.emplace_back(n_ + it.row(), c, 0.0);       // K in (v, q)
      trip.emplace_back(n_ + it.row(), n_ + c, 0.0);  // C in (v, v)
    }
  }
  const int z0 = 2 * n_;
  if (nz_ > 0) {
    zb_.place(p, trip, n_, z0);
  }
  Jres_.resize(size(), size());
  Jres_.setFromTriplets(trip.begin(), trip.end());
  Jres_.makeCompressed();
  Jres_.coeffs().setZero();
  Jrhs_ = Jres_;

  const std::size_t nnz = static_cast<std::size_t>(K_.nonZeros());
  res_K_.resize(nnz);
  res_C_.resize(nnz);
  // Value index k of K_ (column-major order) -> position in the big matrix.
  for (int c = 0; c < n_; ++c) {
    for (int k = K_.outerIndexPtr()[c]; k < K_.outerIndexPtr()[c + 1]; ++k) {
      const int r = K_.innerIndexPtr()[k];
      res_K_[static_cast<std::size_t>(k)] = value_position(Jres_, n_ + r, c);
      res_C_[static_cast<std::size_t>(k)] = value_position(Jres_, n_ + r, n_ + c);
    }
  }
  res_cjq_.resize(static_cast<std::size_t>(n_));
  res_cjv_.resize(static_cast<std::size_t>(n_));
  res_I_.resize(static_cast<std::size_t>(n_));
  for (int i = 0; i < n_; ++i) {
    const auto u = static_cast<std::size_t>(i);
    res_cjq_[u] = value_position(Jres_, i, i);
    res_cjv_[u] = value_position(Jres_, n_ + i, n_ + i);
    res_I_[u] = value_position(Jres_, i, n_ + i);
  }
  if (nz_ > 0) {
    zb_.locate(Jres_, n_, z0);
    for (int i = 0; i < nz_; ++i) pZZ_.push_back(value_position(Jres_, z0 + i, z0 + i));
  }
  // Identical patterns, so identical positions.
  rhs_K_ = res_K_;
  rhs_C_ = res_C_;
  rhs_I_ = res_I_;
}

void FirstOrderForm::residual(double t, const double* y, const double* yd, double* F) {
  const double* q = y;
  const double* v = y + n_;
  if (nz_ > 0) p_.set_internal(y + 2 * n_);
  p_.force(t, q, v, F + n_);
  for (int i = 0; i < n_; ++i) {
    F[i] = yd[i] - v[i];
    F[n_ + i] += m_[i] * yd[n_ + i];
  }
  if (nz_ == 0) return;
  double* Fz = F + 2 * n_;
  p_.internal_rate(t, q, v, Fz);
  for (int i = 0; i < nz_; ++i) Fz[i] = yd[2 * n_ + i] - Fz[i];
}

void FirstOrderForm::residual_jacobian(double t, const double* y, double cj, SpMat& J) {
  if (nz_ > 0) p_.set_internal(y + 2 * n_);
  p_.force_jacobian(t, y, y + n_, K_, C_);
  double* val = J.valuePtr();
  std::fill(val, val + J.nonZeros(), 0.0);
  const double* k = K_.valuePtr();
  const double* c = C_.valuePtr();
  const std::size_t nnz = res_K_.size();
  for (std::size_t e = 0; e < nnz; ++e) {
    val[res_K_[e]] += k[e];
    val[res_C_[e]] += c[e];
  }
  for (std::size_t i = 0; i < res_I_.size(); ++i) {
    val[res_cjq_[i]] += cj;
    val[res_cjv_[i]] += cj * m_[static_cast<Eigen::Index>(i)];
    val[res_I_[i]] -= 1.0;
  }
  if (nz_ == 0) return;
  zb_.add(p_, t, y, y + n_, val, 1.0);
  for (int pos : pZZ_) val[pos] += cj;
}

void FirstOrderForm::rhs(double t, const double* y, double* yd) {
  if (!unit_mass_)
    throw std::logic_error("first_order: rhs() of a problem with quasi-static coordinates");
  const double* q = y;
  const double* v = y + n_;
  if (nz_ > 0) p_.set_internal(y + 2 * n_);
  p_.force(t, q, v, yd + n_);
  for (int i = 0; i < n_; ++i) {
    yd[i] = v[i];
    yd[n_ + i] = -yd[n_ + i];
  }
  if (nz_ > 0) p_.internal_rate(t, q, v, yd + 2 * n_);
}

void FirstOrderForm::rhs_jacobian(double t, const double* y, SpMat& J) {
  if (!unit_mass_)
    throw std::logic_error(
        "first_order: rhs_jacobian() of a problem with quasi-static coordinates");
  if (nz_ > 0) p_.set_internal(y + 2 * n_);
  p_.force_jacobian(t, y, y + n_, K_, C_);
  double* val = J.valuePtr();
  std::fill(val, val + J.nonZeros(), 0.0);
  const double* k = K_.valuePtr();
  const double* c = C_.valuePtr();
  const std::size_t nnz = rhs_K_.size();
  for (std::size_t e = 0; e < nnz; ++e) {
    val[rhs_K_[e]] -= k[e];
    val[rhs_C_[e]] -= c[e];
  }
  for (std::size_t i = 0; i < rhs_I_.size(); ++i) val[rhs_I_[i]] += 1.0;
  if (nz_ == 0) return;
  zb_.add(p_, t, y, y + n_, val, -1.0);
}

}  // namespace evas
