// Residuals and iteration matrices of the DAE formulations (see formulation.h).
//
// Pattern of J = dF/dy + cj dF/dy' (rows/columns: q, v, lambda, mu):
//   (q, q)  cj I                    (+ d(G^T mu)/dq on pattern G^T G, ggl, nonlinear)
//   (q, v)  -I
//   (q, mu) G^T                     (ggl)
//   (v, q)  K (+ d(M v')/dq on pattern M) (+ d(G^T lambda)/dq on G^T G, nonlinear)
//   (v, v)  C + cj M (cj I without a mass matrix)
//   (v, lambda) G^T
//   (c, q)  G (index-3, ggl's g rows, index-1 as beta^2 G + FD), FD (index-2, ggl's g' rows)
//   (c, v)  G (index-2, ggl's g' rows), cj G + 2 alpha G + d(ga)/dv (index-1)
// Constraint rows c have no diagonal: KLU's block-triangular ordering finds a
// zero-free diagonal (Davis & Palamadai Natarajan, ACM TOMS 37 (2010) 36).
#include "dae/formulation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "dae/consistent.h"
#include "dae/sparse_util.h"
#include "model/types.h"

namespace evas::dae {

Formulation parse_formulation(const std::string& name, Formulation fallback) {
  if (name == "default") return fallback;
  for (Formulation f : {Formulation::index3, Formulation::index2, Formulation::ggl,
                        Formulation::index1, Formulation::penalty})
    if (formulation_name(f) == name) return f;
  throw InputError("formulation: '" + name +
                   "' is unknown (expected one of: default, index-3, index-2, ggl, index-1, "
                   "penalty)");
}

std::string formulation_name(Formulation f) {
  switch (f) {
    case Formulation::index3:
      return "index-3";
    case Formulation::index2:
      return "index-2";
    case Formulation::ggl:
      return "ggl";
    case Formulation::index1:
      return "index-1";
    case Formulation::penalty:
      return "penalty";
  }
  return "?";
}

DaeForm::DaeForm(Problem& p, Formulation f, double alpha, double beta)
    : p_(p), f_(f), alpha_(alpha), beta_(beta), n_(p.size()), m_(p.constraint_count()) {
  if (f == Formulation::penalty)
    throw std::logic_error("DaeForm: the penalty formulation is an ODE (dae/penalty.h)");
  const bool ggl = f == Formulation::ggl;
  size_ = 2 * n_ + m_ + (ggl ? m_ : 0);
  z0_ = size_;
  nz_ = p.internal_count();
  size_ += nz_;
  mass_ = p.has_mass();
  nonlinear_ = m_ > 0 && !p.constraints_linear();
  fd_ = mass_ || nonlinear_;
  K_ = p.jacobian_pattern();
  K_.makeCompressed();
  C_ = K_;
  if (K_.rows() != n_ || K_.cols() != n_)
    throw InputError("problem: jacobian_pattern() is not size() x size()");
  if (mass_) {
    M_ = p.mass_pattern();
    M_.makeCompressed();
    if (M_.rows() != n_ || M_.cols() != n_)
      throw InputError("problem: mass_pattern() is not size() x size()");
  }
  if (m_ > 0) {
    G_ = p.constraint_pattern();
    G_.makeCompressed();
    if (G_.rows() != m_ || G_.cols() != n_)
      throw InputError("problem: constraint_pattern() is not constraint_count() x size()");
  }
  const int v0 = n_, l0 = 2 * n_, c0 = 2 * n_, mu0 = 2 * n_ + m_;

  // Entries of J, and those filled by finite differences.
  std::vector<Triplet> trip, fdq, fdv;
  for (int i = 0; i < n_; ++i) {
    trip.emplace_back(i, i, 0.0);
    trip.emplace_back(i, v0 + i, 0.0);
    trip.emplace_back(v0 + i, v0 + i, 0.0);
  }
  for (int c = 0; c < n_; ++c)
    for (SpMat::InnerIterator it(K_, c); it; ++it) {
      trip.emplace_back(v0 + it.row(), c, 0.0);
      trip.emplace_back(v0 + it.row(), v0 + c, 0.0);
    }
  if (mass_)
    for (int c = 0; c < n_; ++c)
      for (SpMat::InnerIterator it(M_, c); it; ++it) {
        trip.emplace_back(v0 + it.row(), v0 + c, 0.0);
        fdq.emplace_back(v0 + it.row(), c, 0.0);
      }
  for (int c = 0; c < n_ && m_ > 0; ++c)
    for (SpMat::InnerIterator it(G_, c); it; ++it) {
      const int k = it.row();
      trip.emplace_back(v0 + c, l0 + k, 0.0);  // G^T in the lambda column
      if (ggl) trip.emplace_back(c, mu0 + k, 0.0);
      switch (f_) {
        case Formulation::index3:
          trip.emplace_back(c0 + k, c, 0.0);
          break;
        case Formulation::index2:
          trip.emplace_back(c0 + k, v0 + c, 0.0);
          if (nonlinear_) fdq.emplace_back(c0 + k, c, 0.0);
          break;
        case Formulation::ggl:
          trip.emplace_back(c0 + k, c, 0.0);
          trip.emplace_back(mu0 + k, v0 + c, 0.0);
          if (nonlinear_) fdq.emplace_back(mu0 + k, c, 0.0);
          break;
        case Formulation::index1:
          trip.emplace_back(c0 + k, c, 0.0);
          trip.emplace_back(c0 + k, v0 + c, 0.0);
          if (nonlinear_) {
            fdq.emplace_back(c0 + k, c, 0.0);
            fdv.emplace_back(c0 + k, v0 + c, 0.0);
          }
          break;
        case Formulation::penalty:
          break;
      }
    }
  if (nonlinear_)
    for (const Triplet& e : gtg_entries(G_)) {
      fdq.emplace_back(v0 + e.row(), e.col(), 0.0);
      if (ggl) fdq.emplace_back(e.row(), e.col(), 0.0);
    }
  if (nz_ > 0) {
    zb_.place(p, trip, v0, z0_);
  }
  trip.insert(trip.end(), fdq.begin(), fdq.end());
  trip.insert(trip.end(), fdv.begin(), fdv.end());
  J_ = pattern_from(size_, size_, trip);

  // Value positions.
  const auto nk = static_cast<std::size_t>(K_.nonZeros());
  pK_.resize(nk);
  pC_.resize(nk);
  for (int c = 0; c < n_; ++c)
    for (int e = K_.outerIndexPtr()[c]; e < K_.outerIndexPtr()[c + 1]; ++e) {
      const int r = K_.innerIndexPtr()[e];
      pK_[static_cast<std::size_t>(e)] = value_position(J_, v0 + r, c);
      pC_[static_cast<std::size_t>(e)] = value_position(J_, v0 + r, v0 + c);
    }
  if (mass_) {
    pM_.resize(static_cast<std::size_t>(M_.nonZeros()));
    for (int c = 0; c < n_; ++c)
      for (int e = M_.outerIndexPtr()[c]; e < M_.outerIndexPtr()[c + 1]; ++e)
        pM_[static_cast<std::size_t>(e)] = value_position(J_, v0 + M_.innerIndexPtr()[e], v0 + c);
  }
  for (int i = 0; i < n_; ++i) {
    pQQ_.push_back(value_position(J_, i, i));
    pQV_.push_back(value_position(J_, i, v0 + i));
    pVV_.push_back(value_position(J_, v0 + i, v0 + i));
  }
  if (m_ > 0) {
    const auto ng = static_cast<std::size_t>(G_.nonZeros());
    pGtLam_.resize(ng);
    if (ggl) pGtMu_.resize(ng);
    pGq_.assign(ng, -1);
    pGv_.assign(ng, -1);
    for (int c = 0; c < n_; ++c)
      for (int e = G_.outerIndexPtr()[c]; e < G_.outerIndexPtr()[c + 1]; ++e) {
        const auto u = static_cast<std::size_t>(e);
        const int k = G_.innerIndexPtr()[e];
        pGtLam_[u] = value_position(J_, v0 + c, l0 + k);
        if (ggl) pGtMu_[u] = value_position(J_, c, mu0 + k);
        if (f_ != Formulation::index2) pGq_[u] = value_position(J_, c0 + k, c);
        if (f_ == Formulation::index2 || f_ == Formulation::index1)
          pGv_[u] = value_position(J_, c0 + k, v0 + c);
        if (ggl) pGv_[u] = value_position(J_, mu0 + k, v0 + c);
      }
  }
  auto columns = [&](const std::vector<Triplet>& fd, int col0) {
    std::vector<std::map<int, int>> cols(static_cast<std::size_t>(n_));
    for (const Triplet& e : fd)
      cols[static_cast<std::size_t>(e.col() - col0)][e.row()] =
          value_position(J_, e.row(), e.col());
    std::vector<std::vector<std::pair<int, int>>> out(cols.size());
    for (std::size_t j = 0; j < cols.size(); ++j) out[j].assign(cols[j].begin(), cols[j].end());
    return out;
  };
  fdq_ = columns(fdq, 0);
  fdv_ = columns(fdv, v0);

  if (nz_ > 0) {
    zb_.locate(J_, v0, z0_);
    for (int i = 0; i < nz_; ++i) {
      if (p.internal_algebraic(i))
        zalg_.push_back(i);
      else
        pZdiag_.push_back(value_position(J_, z0_ + i, z0_ + i));
    }
  }
  diff_id_ = Vec::Zero(size_);
  diff_id_.head(2 * n_).setOnes();
  for (int i = 0; i < nz_; ++i) diff_id_[z0_ + i] = p.internal_algebraic(i) ? 0.0 : 1.0;
  err_id_ = diff_id_;
  if (f_ == Formulation::index3 && m_ > 0) err_id_.segment(v0, n_).setZero();
  weight_power_.assign(static_cast<std::size_t>(size_), 0);
  if (m_ > 0 && f_ != Formulation::index1) {
    const int lam_power = f_ == Formulation::index3 ? 2 : 1;
    for (int i = l0; i < z0_; ++i) weight_power_[static_cast<std::size_t>(i)] = 1;
    for (int k = 0; k < m_; ++k) weight_power_[static_cast<std::size_t>(l0 + k)] = lam_power;
    if (f_ == Formulation::index3)
      for (int i = 0; i < n_; ++i) weight_power_[static_cast<std::size_t>(v0 + i)] = 1;
  }
  g_.resize(m_);
  gv_.resize(m_);
  ga_.resize(m_);
  A0_.resize(size_);
  A1_.resize(size_);
  qh_.resize(n_);
  vh_.resize(n_);
}

// out[i] += sign * (G^T w)_i
void DaeForm::gt_times(const double* w, double* out, double sign) const {
  const double* val = G_.valuePtr();
  for (int c = 0; c < n_; ++c)
    for (int e = G_.outerIndexPtr()[c]; e < G_.outerIndexPtr()[c + 1]; ++e)
      out[c] += sign * val[e] * w[G_.innerIndexPtr()[e]];
}

void DaeForm::g_jacobian(double t, const double* q) {
  // constant when the constraints are linear (Problem::constraints_linear)
  if (nonlinear_ || !g_cached_) p_.constraint_jacobian(t, q, G_);
  g_cached_ = !nonlinear_;
}

void DaeForm::residual(double t, const double* y, const double* yd, double* F) {
  const double *q = y, *v = y + n_, *lam = y + 2 * n_, *mu = y + 2 * n_ + m_;
  const double *qd = yd, *vd = yd + n_;
  double* Fv = F + n_;
  double* Fc = F + 2 * n_;
  if (nz_ > 0) p_.set_internal(y + z0_);
  p_.force(t, q, v, Fv);
  for (int i = 0; i < n_; ++i) F[i] = qd[i] - v[i];
  if (mass_) {
    p_.mass(t, q, M_);
    const double* val = M_.valuePtr();
    for (int c = 0; c < n_; ++c)
      for (int e = M_.outerIndexPtr()[c]; e < M_.outerIndexPtr()[c + 1]; ++e)
        Fv[M_.innerIndexPtr()[e]] += val[e] * vd[c];
  } else {
    for (int i = 0; i < n_; ++i) Fv[i] += vd[i];
  }
  if (nz_ > 0) {
    double* Fz = F + z0_;
    p_.internal_rate(t, q, v, Fz);
    for (int i = 0; i < nz_; ++i) Fz[i] = diff_id_[z0_ + i] * yd[z0_ + i] - Fz[i];
  }
  if (m_ == 0) return;
  g_jacobian(t, q);
  const bool want_g = f_ != Formulation::index2;
  const bool want_gv = f_ != Formulation::index3;
  const bool want_ga = f_ == Formulation::index1;
  p_.constraint(t, q, v, want_g ? g_.data() : nullptr, want_gv ? gv_.data() : nullptr,
                want_ga ? ga_.data() : nullptr);
  gt_times(lam, Fv);
  switch (f_) {
    case Formulation::index3:
      for (int k = 0; k < m_; ++k) Fc[k] = g_[k];
      break;
    case Formulation::index2:
      for (int k = 0; k < m_; ++k) Fc[k] = gv_[k];
      break;
    case Formulation::ggl:
      gt_times(mu, F);
      for (int k = 0; k < m_; ++k) {
        Fc[k] = g_[k];
        Fc[m_ + k] = gv_[k];
      }
      break;
    case Formulation::index1: {
      for (int k = 0; k < m_; ++k) Fc[k] = ga_[k] + 2.0 * alpha_ * gv_[k] + beta_ * beta_ * g_[k];
      const double* val = G_.valuePtr();
      for (int c = 0; c < n_; ++c)
        for (int e = G_.outerIndexPtr()[c]; e < G_.outerIndexPtr()[c + 1]; ++e)
          Fc[G_.innerIndexPtr()[e]] += val[e] * vd[c];
      break;
    }
    case Formulation::penalty:
      break;
  }
}

void DaeForm::nonlinear_terms(double t, const double* q, const double* v, const double* y,
                              const double* yd, Vec& out) {
  out.setZero();
  const double *lam = y + 2 * n_, *mu = y + 2 * n_ + m_, *vd = yd + n_;
  double* o = out.data();
  if (mass_) {
    p_.mass(t, q, M_);
    const double* val = M_.valuePtr();
    for (int c = 0; c < n_; ++c)
      for (int e = M_.outerIndexPtr()[c]; e < M_.outerIndexPtr()[c + 1]; ++e)
        o[n_ + M_.innerIndexPtr()[e]] += val[e] * vd[c];
  }
  if (!nonlinear_) return;
  p_.constraint_jacobian(t, q, G_);
  gt_times(lam, o + n_);
  double* oc = o + 2 * n_;
  switch (f_) {
    case Formulation::index3:
    case Formulation::penalty:
      break;
    case Formulation::index2:
      p_.constraint(t, q, v, nullptr, oc, nullptr);
      break;
    case Formulation::ggl:
      gt_times(mu, o);
      p_.constraint(t, q, v, nullptr, oc + m_, nullptr);
      break;
    case Formulation::index1: {
      p_.constraint(t, q, v, nullptr, gv_.data(), ga_.data());
      for (int k = 0; k < m_; ++k) oc[k] = ga_[k] + 2.0 * alpha_ * gv_[k];
      const double* val = G_.valuePtr();
      for (int c = 0; c < n_; ++c)
        for (int e = G_.outerIndexPtr()[c]; e < G_.outerIndexPtr()[c + 1]; ++e)
          oc[G_.innerIndexPtr()[e]] += val[e] * vd[c];
      break;
    }
  }
}

void DaeForm::residual_jacobian(double t, const double* y, const double* yd, double cj, SpMat& J) {
  const double *q = y, *v = y + n_;
  double* val = J.valuePtr();
  std::fill(val, val + J.nonZeros(), 0.0);
  if (nz_ > 0) {
    p_.set_internal(y + z0_);
    zb_.add(p_, t, q, v, val, 1.0);
    for (int pos : pZdiag_) val[pos] += cj;
  }
  p_.force_jacobian(t, q, v, K_, C_);
  for (std::size_t e = 0; e < pK_.size(); ++e) {
    val[pK_[e]] += K_.valuePtr()[e];
    val[pC_[e]] += C_.valuePtr()[e];
  }
  for (int i = 0; i < n_; ++i) {
    const auto u = static_cast<std::size_t>(i);
    val[pQQ_[u]] += cj;
    val[pQV_[u]] -= 1.0;
  }
  if (mass_) {
    p_.mass(t, q, M_);
    for (std::size_t e = 0; e < pM_.size(); ++e) val[pM_[e]] += cj * M_.valuePtr()[e];
  } else {
    for (int i = 0; i < n_; ++i) val[pVV_[static_cast<std::size_t>(i)]] += cj;
  }
  if (m_ > 0) {
    g_jacobian(t, q);
    const double* gval = G_.valuePtr();
    for (std::size_t e = 0; e < pGtLam_.size(); ++e) {
      const double gk = gval[e];
      val[pGtLam_[e]] += gk;
      if (!pGtMu_.empty()) val[pGtMu_[e]] += gk;
      switch (f_) {
        case Formulation::index3:
        case Formulation::ggl:
          val[pGq_[e]] += gk;
          if (pGv_[e] >= 0) val[pGv_[e]] += gk;
          break;
        case Formulation::index2:
          val[pGv_[e]] += gk;
          break;
        case Formulation::index1:
          val[pGq_[e]] += beta_ * beta_ * gk;
          val[pGv_[e]] += (cj + 2.0 * alpha_) * gk;
          break;
        case Formulation::penalty:
          break;
      }
    }
  }
  if (!fd_) return;
  // Forward differences of the second-derivative terms (formulation.h).
  const double sq = std::sqrt(std::numeric_limits<double>::epsilon());
  std::copy(q, q + n_, qh_.data());
  std::copy(v, v + n_, vh_.data());
  nonlinear_terms(t, q, v, y, yd, A0_);
  for (int j = 0; j < n_; ++j) {
    const auto u = static_cast<std::size_t>(j);
    if (fdq_[u].empty()) continue;
    const double h = sq * std::max(1.0, std::abs(q[j]));
    qh_[j] = q[j] + h;
    nonlinear_terms(t, qh_.data(), v, y, yd, A1_);
    qh_[j] = q[j];
    for (const auto& [row, pos] : fdq_[u]) val[pos] += (A1_[row] - A0_[row]) / h;
  }
  if (f_ != Formulation::index1 || !nonlinear_) return;
  // d(ga)/dv only: the 2 alpha G part is analytic above
  p_.constraint(t, q, v, nullptr, nullptr, A0_.data());
  for (int j = 0; j < n_; ++j) {
    const auto u = static_cast<std::size_t>(j);
    if (fdv_[u].empty()) continue;
    const double h = sq * std::max(1.0, std::abs(v[j]));
    vh_[j] = v[j] + h;
    p_.constraint(t, q, vh_.data(), nullptr, nullptr, A1_.data());
    vh_[j] = v[j];
    for (const auto& [row, pos] : fdv_[u]) {
      const int k = row - 2 * n_;
      val[pos] += (A1_[k] - A0_[k]) / h;
    }
  }
}

void DaeForm::solve_algebraic_states(double t, const Vec& q, const Vec& v) {
  if (zalg_.empty()) return;
  zcur_ = Eigen::Map<const Vec>(p_.internal(), nz_);
  Vec h(nz_);
  const int na = static_cast<int>(zalg_.size());
  Mat A(na, na);
  Vec r(na);
  for (int it = 0; it < 20; ++it) {
    p_.set_internal(zcur_.data());
    p_.internal_rate(t, q.data(), v.data(), h.data());
    double worst = 0.0;
    for (int a = 0; a < na; ++a) {
      r[a] = h[zalg_[static_cast<std::size_t>(a)]];
      worst = std::max(worst, std::abs(r[a]));
    }
    if (!(worst > 1e-14 * (1.0 + zcur_.cwiseAbs().maxCoeff()))) return;
    p_.internal_jacobian(t, q.data(), v.data(), zb_.Fz, zb_.Hq, zb_.Hv, zb_.Hz);
    const Mat Hz(zb_.Hz);
    for (int a = 0; a < na; ++a)
      for (int b = 0; b < na; ++b)
        A(a, b) = Hz(zalg_[static_cast<std::size_t>(a)], zalg_[static_cast<std::size_t>(b)]);
    const Vec dz = A.fullPivLu().solve(r);
    if (!dz.allFinite())
      throw RunError("consistent start at t = " + format_number(t) +
                     " s: the algebraic internal states cannot be solved (dh/dz singular at " +
                     p_.internal_name(zalg_[0]) + ")");
    for (int a = 0; a < na; ++a) zcur_[zalg_[static_cast<std::size_t>(a)]] -= dz[a];
  }
  p_.set_internal(zcur_.data());
}

double DaeForm::consistent_start(double t, const Vec& q, const Vec& v, double* y, double* yd) {
  solve_algebraic_states(t, q, v);
  ConsistentState s = consistent_state(p_, t, q, v);
  if (!zalg_.empty() && m_ > 0) {  // the projection moved (q, v): solve again there
    solve_algebraic_states(t, s.q, s.v);
    s = consistent_state(p_, t, s.q, s.v);
  }
  std::fill(y, y + size_, 0.0);
  std::fill(yd, yd + size_, 0.0);
  for (int i = 0; i < n_; ++i) {
    y[i] = s.q[i];
    y[n_ + i] = s.v[i];
    yd[i] = s.v[i];
    yd[n_ + i] = s.a[i];
  }
  for (int k = 0; k < m_; ++k) y[2 * n_ + k] = s.lambda[k];
  if (nz_ > 0) {
    std::copy(p_.internal(), p_.internal() + nz_, y + z0_);
    Vec h(nz_);
    p_.internal_rate(t, s.q.data(), s.v.data(), h.data());
    for (int i = 0; i < nz_; ++i) yd[z0_ + i] = diff_id_[z0_ + i] * h[i];
  }
  Vec F(size_);
  residual(t, y, yd, F.data());
  return size_ > 0 ? F.cwiseAbs().maxCoeff() : 0.0;
}

}  // namespace evas::dae
