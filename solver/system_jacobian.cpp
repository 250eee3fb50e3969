// The System's Jacobians: the pattern (body diagonal and body-pair blocks) and the
// pair rows built once, then per evaluation the bodies' own blocks, each element's
// D_ij through its body pairs' Y, the pair blocks scattered into K and C, and
// M^-1 applied with inertial elements (see solver/system.h).
#include <algorithm>

#include "solver/system.h"

namespace evas {

void System::build_pattern(const std::vector<char>& pair) {
  const auto& bodies = model_.bodies();
  const int nb = static_cast<int>(bodies.size());
  const int n = model_.size();
  std::vector<Triplet> trip;
  for (int bi = 0; bi < nb; ++bi)
    for (int bj = 0; bj < nb; ++bj) {
      if (!pair[bi * nb + bj]) continue;
      for (int c = 0; c < bodies[bj].n(); ++c)
        for (int r = 0; r < bodies[bi].n(); ++r)
          trip.emplace_back(bodies[bi].offset + r, bodies[bj].offset + c, 1.0);
    }
  pattern_.resize(n, n);
  pattern_.setFromTriplets(trip.begin(), trip.end());
  pattern_.makeCompressed();
  pattern_.coeffs().setZero();
  block_start_.assign(static_cast<std::size_t>(nb) * nb, {});
  for (int bi = 0; bi < nb; ++bi)
    for (int bj = 0; bj < nb; ++bj) {
      if (!pair[bi * nb + bj]) continue;
      auto& starts = block_start_[bi * nb + bj];
      starts.resize(bodies[bj].n());
      for (int c = 0; c < bodies[bj].n(); ++c) {
        const int col = bodies[bj].offset + c;
        const int* begin = pattern_.innerIndexPtr() + pattern_.outerIndexPtr()[col];
        const int* end = pattern_.innerIndexPtr() + pattern_.outerIndexPtr()[col + 1];
        const int* it = std::lower_bound(begin, end, bodies[bi].offset);
        starts[c] = static_cast<int>(it - pattern_.innerIndexPtr());
      }
    }
}

void System::build_pair_rows() {
  const auto& markers = model_.markers();
  const auto& elements = model_.elements();
  const int nb = static_cast<int>(model_.bodies().size());
  for (auto& pw : pairs_) pw.crow.assign(markers.size(), -1);
  std::vector<int> count(pairs_.size(), 0);
  for (std::size_t e = 0; e < elements.size(); ++e) {
    if (is_timed_[e]) continue;  // loads of time alone: D = 0
    const auto& ids = elements[e]->markers();
    for (int mi : ids)
      for (int mj : ids) {
        const int bi = markers[mi].body, bj = markers[mj].body;
        if (bi < 0 || bj < 0) continue;
        const int k = pair_index_[bi * nb + bj];
        PairWork& pw = pairs_[k];
        if (pw.crow[mi] < 0) {
          pw.crow[mi] = count[k];
          count[k] += 6;
        }
      }
  }
  for (std::size_t k = 0; k < pairs_.size(); ++k) {
    PairWork& pw = pairs_[k];
    const int nj = model_.bodies()[pw.bj].n();
    pw.Y = PairRowMat::Zero(count[k], 2 * nj);
    pw.Bc = PairRowMat::Zero(count[k], model_.bodies()[pw.bi].n());
    for (std::size_t m = 0; m < markers.size(); ++m)
      if (pw.crow[m] >= 0) pw.Bc.middleRows(pw.crow[m], 6) = bstack_[pw.bi].middleRows(mrow_[m], 6);
  }
}

void System::apply_inverse_mass(SpMat& A) {
  // A <- A + U Z^-1 (W^T A) on A's pattern (which holds every entry this fills)
  WtA_.noalias() = W_.transpose() * A;
  WtA_ = lu_.solve(WtA_);
  double* val = A.valuePtr();
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();
  for (int c = 0; c < A.cols(); ++c)
    for (int k = outer[c]; k < outer[c + 1]; ++k) val[k] += U_.row(inner[k]).dot(WtA_.col(c));
}

void System::add_block(double* values, int bi, int bj, const Eigen::Ref<const Mat>& B,
                       double scale) const {
  const auto& starts = block_start_[bi * static_cast<int>(model_.bodies().size()) + bj];
  for (Eigen::Index c = 0; c < B.cols(); ++c) {
    double* col = values + starts[c];
    for (Eigen::Index r = 0; r < B.rows(); ++r) col[r] += scale * B(r, c);
  }
}

void System::force_jacobian(double t, const double* q, const double* v, SpMat& K, SpMat& C) {
  jacobian(t, q, v, nullptr, K, &C);
}

void System::force_jacobian_combination(double t, const double* q, const double* v, double ck,
                                        double cc, SpMat& S) {
  const double comb[2] = {ck, cc};
  jacobian(t, q, v, comb, S, nullptr);
}

void System::jacobian(double t, const double* q, const double* v, const double* comb, SpMat& K,
                      SpMat* C) {
  ++counters.jac_evals;
  // inertial elements: solve the accelerations first (their D is taken there)
  // (force_impl updates the markers; without inertial elements update them here)
  if (rank_ > 0)
    force_impl(t, q, v, scratch_f_.data());
  else
    update_markers(t, q, v);
  if (comb) {  // ck KB + cc CB
    update_lof(t);
    K.coeffs().setZero();
    add_body_terms(K.valuePtr(), comb[0], comb[1]);
  } else {
    body_operator(t, K, *C);
  }
  for (auto& pw : pairs_) {
    if (comb)
      pw.Y.leftCols(pw.Y.cols() / 2).setZero();
    else
      pw.Y.setZero();
  }
  for (std::size_t e = 0; e < ework_.size(); ++e) {
    if (is_timed_[e]) continue;  // loads of time alone: D = 0
    element_derivatives(e, t);
    add_element_pairs(e, comb);
  }
  // f = ... - Q  =>  [K C] -= [Bu; Bt]_i^T [YK YC], over the loaded rows
  add_pair_blocks(comb, K, C);
  if (rank_ > 0) {  // M^-1 (ck K + cc C) = ck M^-1 K + cc M^-1 C
    apply_inverse_mass(K);
    if (!comb) apply_inverse_mass(*C);
  }
}

void System::element_derivatives(std::size_t e, double t) {
  const Element& el = *model_.elements()[e];
  ElementWork& w = ework_[e];
  const auto& ids = el.markers();
  if (el.inertia_rank() == 0)  // inertial ones keep the motion solve_inertia left
    for (std::size_t i = 0; i < ids.size(); ++i) w.motion[i] = motion_[ids[i]];
  if (zoff_[e] >= 0)
    el.derivatives_z(t, w.motion.data(), z_.data() + zoff_[e], w.D);
  else
    el.derivatives(t, w.motion.data(), w.D);
}

void System::add_element_pairs(std::size_t e, const double* comb) {
  const auto& markers = model_.markers();
  const int nb = static_cast<int>(model_.bodies().size());
  const Element& el = *model_.elements()[e];
  ElementWork& w = ework_[e];
  const auto& ids = el.markers();
  for (std::size_t i = 0; i < ids.size(); ++i) {
    const int bi = markers[ids[i]].body;
    if (bi < 0) continue;
    const Mat3& Ri = lof_[bi].R_GL;
    for (std::size_t j = 0; j < ids.size(); ++j) {
      const int bj = markers[ids[j]].body;
      if (bj < 0) continue;
      const Mat3& Rj = lof_[bj].R_GL;
      // D_ij's columns act on the motion (p, v, psi, w) of marker j, whose
      // derivatives are Pq = [Lu; skew(w) Lu; Lt; 0], Pv = [0; Lu; 0; Lt] with
      // Lu = R Bu, Lt = R Bt: D_ij Pq = EK [R Bu; R Bt], D_ij Pv = EC [R Bu; R Bt];
      // loads Lm_i^T = [Bu; Bt]^T diag(R^T, R^T): the 6 x 6 blocks in L components.
      const auto Dij = w.D.block(6 * i, 12 * j, 6, 12);
      Mat6 EK, EC;
      EK.leftCols<3>().noalias() = Dij.middleCols<3>(3) * skew(lof_[bj].w_GL_G);
      EK.leftCols<3>() += Dij.middleCols<3>(0);
      EK.rightCols<3>() = Dij.middleCols<3>(6);
      EC.leftCols<3>() = Dij.middleCols<3>(3);
      EC.rightCols<3>() = Dij.middleCols<3>(9);
      Mat6 LK, LC;
      for (int a = 0; a < 2; ++a)
        for (int c = 0; c < 2; ++c) {
          LK.block<3, 3>(3 * a, 3 * c).noalias() =
              Ri.transpose() * EK.block<3, 3>(3 * a, 3 * c) * Rj;
          LC.block<3, 3>(3 * a, 3 * c).noalias() =
              Ri.transpose() * EC.block<3, 3>(3 * a, 3 * c) * Rj;
        }
      PairWork& pw = pairs_[pair_index_[bi * nb + bj]];
      const auto Bj = bstack_[bj].middleRows<6>(mrow_[ids[j]]);
      const Eigen::Index nj = Bj.cols();
      const int r = pw.crow[static_cast<std::size_t>(ids[i])];
      if (comb) {
        const Mat6 L = comb[0] * LK + comb[1] * LC;
        pw.Y.block(r, 0, 6, nj).noalias() += L * Bj;
      } else {
        pw.Y.block(r, 0, 6, nj).noalias() += LK * Bj;
        pw.Y.block(r, nj, 6, nj).noalias() += LC * Bj;
      }
    }
  }
}

void System::add_pair_blocks(const double* comb, SpMat& K, SpMat* C) {
  for (auto& pw : pairs_) {
    if (pw.Y.rows() == 0) continue;  // coupled by elements of time alone only: D = 0
    const Eigen::Index nj = pw.Y.cols() / 2;
    if (comb) {  // (the left half of Y holds the combination)
      pw.blk.leftCols(nj).noalias() = -pw.Bc.transpose() * pw.Y.leftCols(nj);
      add_block(K.valuePtr(), pw.bi, pw.bj, pw.blk.leftCols(nj));
      continue;
    }
    pw.blk.noalias() = -pw.Bc.transpose() * pw.Y;
    add_block(K.valuePtr(), pw.bi, pw.bj, pw.blk.leftCols(nj));
    add_block(C->valuePtr(), pw.bi, pw.bj, pw.blk.rightCols(nj));
  }
}

void System::body_operator(double t, SpMat& KB, SpMat& CB) {
  update_lof(t);
  KB.coeffs().setZero();
  CB.coeffs().setZero();
  add_body_terms(KB.valuePtr(), 1.0, 0.0);
  add_body_terms(CB.valuePtr(), 0.0, 1.0);
}

void System::add_body_terms(double* values, double ck, double cc) const {
  const auto& bodies = model_.bodies();
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const Body& B = bodies[b];
    const int bi = static_cast<int>(b);
    if (ck != 0.0) add_block(values, bi, bi, bwork_[b].KW, ck);
    if (cc != 0.0) add_block(values, bi, bi, bwork_[b].G, cc);
    const auto& starts = block_start_[bi * static_cast<int>(bodies.size()) + bi];
    for (int k = 0; k < B.n(); ++k)
      values[starts[k] + k] += ck * B.data->eigenvalues[k] + cc * B.data->damping[k];
  }
}

}  // namespace evas
