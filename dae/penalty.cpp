// The penalty formulation as an ODE Problem (see penalty.h).
#include "dae/penalty.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "dae/sparse_util.h"

namespace evas::dae {

PenaltyProblem::PenaltyProblem(Problem& base, double stiffness, double damping)
    : base_(base), k_(stiffness), c_(damping), n_(base.size()), m_(base.constraint_count()) {
  if (!(stiffness > 0.0) || !(damping >= 0.0))
    throw InputError("penalty: penalty_stiffness must be > 0 and penalty_damping >= 0");
  Kb_ = base.jacobian_pattern();
  Kb_.makeCompressed();
  Cb_ = Kb_;
  G_ = base.constraint_pattern();
  G_.makeCompressed();
  if (m_ > 0 && (G_.rows() != m_ || G_.cols() != n_))
    throw InputError("problem: constraint_pattern() is not constraint_count() x size()");
  std::vector<Triplet> trip;
  for (int c = 0; c < Kb_.outerSize(); ++c)
    for (SpMat::InnerIterator it(Kb_, c); it; ++it) trip.emplace_back(it.row(), c, 0.0);
  const std::vector<Triplet> gtg = m_ > 0 ? gtg_entries(G_) : std::vector<Triplet>{};
  trip.insert(trip.end(), gtg.begin(), gtg.end());
  pattern_ = pattern_from(n_, n_, trip);

  pos_base_.resize(static_cast<std::size_t>(Kb_.nonZeros()));
  for (int c = 0; c < n_; ++c)
    for (int e = Kb_.outerIndexPtr()[c]; e < Kb_.outerIndexPtr()[c + 1]; ++e)
      pos_base_[static_cast<std::size_t>(e)] = value_position(pattern_, Kb_.innerIndexPtr()[e], c);
  // G^T G: for each constraint row, every pair of its entries.
  std::vector<std::vector<std::pair<int, int>>> rows(static_cast<std::size_t>(m_));
  for (int c = 0; c < n_ && m_ > 0; ++c)
    for (int e = G_.outerIndexPtr()[c]; e < G_.outerIndexPtr()[c + 1]; ++e)
      rows[static_cast<std::size_t>(G_.innerIndexPtr()[e])].emplace_back(c, e);
  for (const auto& r : rows)
    for (const auto& [ca, ea] : r)
      for (const auto& [cb, eb] : r) gtg_.push_back({value_position(pattern_, ca, cb), ea, eb});
  std::vector<std::map<int, int>> cols(static_cast<std::size_t>(n_));
  if (!base.constraints_linear())
    for (const Triplet& e : gtg)
      cols[static_cast<std::size_t>(e.col())][e.row()] = value_position(pattern_, e.row(), e.col());
  fd_.resize(cols.size());
  for (std::size_t j = 0; j < cols.size(); ++j) fd_[j].assign(cols[j].begin(), cols[j].end());
  G0_ = G_;
  g_.resize(m_);
  gv_.resize(m_);
  w_.resize(m_);
  h0_.resize(n_);
  h1_.resize(n_);
  qh_.resize(n_);
}

void PenaltyProblem::force(double t, const double* q, const double* v, double* f) {
  ++counters.f_evals;
  base_.force(t, q, v, f);
  if (m_ == 0) return;
  base_.constraint_jacobian(t, q, G_);
  base_.constraint(t, q, v, g_.data(), gv_.data(), nullptr);
  const double* val = G_.valuePtr();
  for (int c = 0; c < n_; ++c)
    for (int e = G_.outerIndexPtr()[c]; e < G_.outerIndexPtr()[c + 1]; ++e) {
      const int k = G_.innerIndexPtr()[e];
      f[c] += val[e] * (k_ * g_[k] + c_ * gv_[k]);
    }
}

// G(q)^T w + c G0^T (G v + g_t)(q, v), with w and G0 frozen at the base point.
void PenaltyProblem::second_derivative_terms(double t, const double* q, const double* v, Vec& out) {
  out.setZero();
  base_.constraint_jacobian(t, q, G_);
  base_.constraint(t, q, v, nullptr, gv_.data(), nullptr);
  const double *val = G_.valuePtr(), *val0 = G0_.valuePtr();
  for (int c = 0; c < n_; ++c)
    for (int e = G_.outerIndexPtr()[c]; e < G_.outerIndexPtr()[c + 1]; ++e) {
      const int k = G_.innerIndexPtr()[e];
      out[c] += val[e] * w_[k] + c_ * val0[e] * gv_[k];
    }
}

void PenaltyProblem::force_jacobian(double t, const double* q, const double* v, SpMat& K,
                                    SpMat& C) {
  ++counters.jac_evals;
  base_.force_jacobian(t, q, v, Kb_, Cb_);
  double *kv = K.valuePtr(), *cv = C.valuePtr();
  std::fill(kv, kv + K.nonZeros(), 0.0);
  std::fill(cv, cv + C.nonZeros(), 0.0);
  for (std::size_t e = 0; e < pos_base_.size(); ++e) {
    kv[pos_base_[e]] += Kb_.valuePtr()[e];
    cv[pos_base_[e]] += Cb_.valuePtr()[e];
  }
  if (m_ == 0) return;
  base_.constraint_jacobian(t, q, G0_);
  const double* g0 = G0_.valuePtr();
  for (const auto& [pos, a, b] : gtg_) {
    const double gg = g0[a] * g0[b];
    kv[pos] += k_ * gg;
    cv[pos] += c_ * gg;
  }
  if (base_.constraints_linear()) return;
  base_.constraint(t, q, v, g_.data(), gv_.data(), nullptr);
  for (int k = 0; k < m_; ++k) w_[k] = k_ * g_[k] + c_ * gv_[k];
  const double sq = std::sqrt(std::numeric_limits<double>::epsilon());
  std::copy(q, q + n_, qh_.data());
  second_derivative_terms(t, q, v, h0_);
  for (int j = 0; j < n_; ++j) {
    const auto u = static_cast<std::size_t>(j);
    if (fd_[u].empty()) continue;
    const double h = sq * std::max(1.0, std::abs(q[j]));
    qh_[j] = q[j] + h;
    second_derivative_terms(t, qh_.data(), v, h1_);
    qh_[j] = q[j];
    for (const auto& [row, pos] : fd_[u]) kv[pos] += (h1_[row] - h0_[row]) / h;
  }
}

void PenaltyProblem::body_operator(double t, SpMat& KB, SpMat& CB) {
  base_.body_operator(t, Kb_, Cb_);
  double *kv = KB.valuePtr(), *cv = CB.valuePtr();
  std::fill(kv, kv + KB.nonZeros(), 0.0);
  std::fill(cv, cv + CB.nonZeros(), 0.0);
  for (std::size_t e = 0; e < pos_base_.size(); ++e) {
    kv[pos_base_[e]] += Kb_.valuePtr()[e];
    cv[pos_base_[e]] += Cb_.valuePtr()[e];
  }
}

}  // namespace evas::dae
