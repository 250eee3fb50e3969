#include "solver/system.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace evas {

System::System(Model& model) : model_(model) {
  auto& bodies = model_.bodies();
  const int nb = static_cast<int>(bodies.size());
  const int n = model_.size();
  lof_.resize(nb);
  bwork_.resize(nb);
  for (int b = 0; b < nb; ++b) {
    const int nbm = bodies[b].n();
    bwork_[b].f0 = Vec::Zero(nbm);
    bwork_[b].KW = Mat::Zero(nbm, nbm);
    bwork_[b].G = Mat::Zero(nbm, nbm);
  }
  const auto& markers = model_.markers();
  motion_.resize(markers.size());
  axes_.assign(markers.size(), Mat3::Identity());
  static const LofState ground;
  for (std::size_t m = 0; m < markers.size(); ++m)
    if (markers[m].on_ground()) marker_motion(markers[m], ground, nullptr, nullptr, motion_[m]);
  Lm_.resize(markers.size());
  Pq_.resize(markers.size());
  Pv_.resize(markers.size());
  for (std::size_t m = 0; m < markers.size(); ++m) {
    if (markers[m].on_ground()) continue;
    const int nm = bodies[markers[m].body].n();
    Lm_[m] = Mat::Zero(6, nm);
    Pq_[m] = Mat::Zero(12, nm);
    Pv_[m] = Mat::Zero(12, nm);
  }
  mrow_.assign(markers.size(), -1);
  std::vector<int> rows(static_cast<std::size_t>(nb), 0);
  for (std::size_t m = 0; m < markers.size(); ++m)
    if (!markers[m].on_ground()) {
      mrow_[m] = rows[markers[m].body];
      rows[markers[m].body] += 6;
    }
  bstack_.resize(nb);
  bq_.resize(nb);
  bv_.resize(nb);
  bload_.resize(nb);
  for (int b = 0; b < nb; ++b) {
    bstack_[b] = Mat::Zero(rows[b], bodies[b].n());
    bq_[b] = Vec::Zero(rows[b]);
    bv_[b] = Vec::Zero(rows[b]);
    bload_[b] = Vec::Zero(rows[b]);
  }
  for (std::size_t m = 0; m < markers.size(); ++m)
    if (mrow_[m] >= 0) {
      bstack_[markers[m].body].middleRows(mrow_[m], 3) = markers[m].Bu;
      bstack_[markers[m].body].middleRows(mrow_[m] + 3, 3) = markers[m].Bt;
    }
  bstackT_.resize(nb);
  for (int b = 0; b < nb; ++b) bstackT_[b] = bstack_[b].transpose();

  // Pattern: dense diagonal body blocks plus body-pair blocks of every element.
  std::vector<char> pair(static_cast<std::size_t>(nb) * nb, 0);
  for (int b = 0; b < nb; ++b) pair[b * nb + b] = 1;
  ework_.resize(model_.elements().size());
  pair_index_.assign(static_cast<std::size_t>(nb) * nb, -1);
  for (std::size_t e = 0; e < model_.elements().size(); ++e) {
    const auto& el = *model_.elements()[e];
    const std::size_t k = el.markers().size();
    ework_[e].motion.resize(k);
    ework_[e].loads.resize(k);
    ework_[e].D = Mat::Zero(6 * k, 12 * k);
    for (int mi : el.markers())
      for (int mj : el.markers()) {
        const int bi = markers[mi].body, bj = markers[mj].body;
        if (bi < 0 || bj < 0) continue;
        pair[bi * nb + bj] = 1;
        if (pair_index_[bi * nb + bj] < 0) {
          pair_index_[bi * nb + bj] = static_cast<int>(pairs_.size());
          PairWork pw;
          pw.bi = bi;
          pw.bj = bj;
          pw.blk = Mat::Zero(bodies[bi].n(), 2 * bodies[bj].n());
          pairs_.push_back(std::move(pw));
        }
      }
    if (const int r = el.inertia_rank(); r > 0) {
      inertial_.push_back(static_cast<int>(e));
      piecewise_ = piecewise_ || el.inertia_piecewise();
      ework_[e].P = Mat::Zero(6 * k, r);
      ework_[e].Q = Mat::Zero(6 * k, r);
      ework_[e].dacc = Vec::Zero(6 * k);
      ework_[e].r_1 = Vec::Zero(r);
      ework_[e].col = rank_;
      rank_ += r;
    }
  }
  build_row_sets();
  build_pair_rows();
  if (rank_ > 0) {
    // M^-1 K = K + U Z^-1 W^T K fills rows of the inertial bodies in the columns of
    // their neighbours (the bodies their rows of K reach).
    std::vector<char> inert(static_cast<std::size_t>(nb), 0),
        reach(static_cast<std::size_t>(nb), 0);
    for (int e : inertial_)
      for (int mi : model_.elements()[e]->markers())
        if (markers[mi].body >= 0) inert[markers[mi].body] = 1;
    for (int bi = 0; bi < nb; ++bi)
      for (int bj = 0; bj < nb; ++bj)
        if (inert[bi] && pair[bi * nb + bj]) reach[bj] = 1;
    for (int bi = 0; bi < nb; ++bi)
      for (int bj = 0; bj < nb; ++bj)
        if (inert[bi] && reach[bj]) pair[bi * nb + bj] = 1;
    U_ = Mat::Zero(n, rank_);
    W_ = Mat::Zero(n, rank_);
    Z_ = Mat::Zero(rank_, rank_);
    WtA_ = Mat::Zero(rank_, n);
    f0_ = Vec::Zero(n);
    y_ = Vec::Zero(rank_);
    lu_ = Eigen::PartialPivLU<Mat>(rank_);
  }
  scratch_f_ = Vec::Zero(n);
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
  setup_joints();
  setup_internal();
}

void System::initial_state(Vec& q, Vec& v) const {
  q.resize(size());
  v.resize(size());
  for (const auto& b : model_.bodies()) {
    q.segment(b.offset, b.n()) = b.q0;
    v.segment(b.offset, b.n()) = b.v0;
  }
}

void System::update_lof(double t) {
  if (t == t_lof_) return;
  auto& bodies = model_.bodies();
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const LofState& L = lof_[b] = bodies[b].lof.at(t);
    const Vec3 a_L = L.R_GL.transpose() * (L.a_GL - model_.gravity);
    const Vec3 w_L = L.R_GL.transpose() * L.w_GL_G;
    const Vec3 al_L = L.R_GL.transpose() * L.al_GL_G;
    BodyWork& w = bwork_[b];
    const Mat3 Om = skew(w_L);
    const Mat3 W = skew(al_L) + Om * Om;
    frame_force(bodies[b].inv, a_L, W, w.f0);
    // KW and G cost O(n^2): rebuild them only when the frame's rotation rates change
    // (never for a fixed LOF, a constant-speed spin or between tracking anchors).
    const double tol = 1e-13 * (1.0 + W.norm() + Om.norm());
    if (!w.built || (W - w.W).norm() > tol || (Om - w.Om).norm() > tol) {
      frame_matrices(bodies[b].inv, W, Om, w.KW, w.G);
      add_rotation_correction(bodies[b], w_L, al_L, w.KW);
      w.frame_free = w.KW.isZero(0.0) && w.G.isZero(0.0);
      w.W = W;
      w.Om = Om;
      w.built = true;
    }
  }
  // the marker axes of the bodies whose frame turned since they were formed
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    BodyWork& w = bwork_[b];
    w.axes_current = w.axes_built && lof_[b].R_GL == w.R_axes;
    w.R_axes = lof_[b].R_GL;
    w.axes_built = true;
  }
  const auto& markers = model_.markers();
  for (std::size_t m = 0; m < markers.size(); ++m) {
    const int b = markers[m].body;
    if (b >= 0 && !bwork_[b].axes_current) axes_[m].noalias() = lof_[b].R_GL * markers[m].R_LM;
  }
  t_lof_ = t;
}

void System::add_rotation_correction(const Body& B, const Vec3& w_L, const Vec3& al_L, Mat& KW) {
  bool any = false;
  for (int k = 3; k < 6; ++k) any = any || B.rigid[k] >= 0;
  if (!any) return;  // no explicit rotation basis: nothing linearised to correct
  // theta = T q_R with T = E diag(1/sqrt(J_k)) (solver/modal_body.cpp rigid_basis).
  // A body with only some rotation modes (e.g. a disk that only turns about its
  // axis) gets the sub-block of the present ones: the others are held fixed.
  Mat3 T;
  for (int k = 0; k < 3; ++k)
    T.col(k) = B.mp.principal_axes.col(k) / std::sqrt(B.mp.principal_moments[k]);
  const Mat3 Kq = T.transpose() * rigid_rotation_correction(B.mp.inertia, w_L, al_L) * T;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (B.rigid[3 + i] >= 0 && B.rigid[3 + j] >= 0)
        KW(B.rigid[3 + i], B.rigid[3 + j]) += Kq(i, j);
}

void System::build_row_sets() {
  const auto& markers = model_.markers();
  const auto& elements = model_.elements();
  // rows read: per marker the union of its elements' motion_reads()
  std::vector<unsigned> reads(markers.size(), 0u), loaded(markers.size(), 0u),
      timed_load(markers.size(), 0u);
  for (const auto& el : elements)
    for (std::size_t i = 0; i < el->markers().size(); ++i)
      reads[el->markers()[i]] |= el->motion_reads(i);
  // loads of time alone (the prescribed piston): once per t into ftime_ on the
  // rows of their markers; the other elements' loads on the rows of theirs
  timed_.clear();
  loaded_.clear();
  is_timed_.assign(elements.size(), 0);
  for (std::size_t e = 0; e < elements.size(); ++e) {
    const Element& el = *elements[e];
    const bool timed = !el.state_dependent() && el.inertia_rank() == 0 && el.internal_count() == 0;
    if (timed) {
      timed_.push_back(static_cast<int>(e));
      is_timed_[e] = 1;
    } else if (el.inertia_rank() == 0) {
      loaded_.push_back(static_cast<int>(e));
    }
    if (el.inertia_rank() == 0)
      for (std::size_t i = 0; i < el.markers().size(); ++i)
        (timed ? timed_load : loaded)[el.markers()[i]] |= el.load_parts(i);
  }
  unread_.resize(markers.size());
  for (std::size_t m = 0; m < markers.size(); ++m) unread_[m] = reads[m] == 0u;
  rset_ = row_sets(reads);
  lset_ = row_sets(loaded);
  tset_ = row_sets(timed_load);
  ftime_ = Vec::Zero(model_.size());
  ftime_full_ = Vec::Zero(model_.size());
  t_time_ = t_time_full_ = std::numeric_limits<double>::quiet_NaN();
  build_slot_rows();
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

std::vector<System::RowSet> System::row_sets(const std::vector<unsigned>& parts) const {
  const auto& markers = model_.markers();
  const auto& bodies = model_.bodies();
  std::vector<RowSet> sets(bodies.size());
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    RowSet& set = sets[b];
    set.tpos.assign(markers.size(), -1);
    set.rpos.assign(markers.size(), -1);
    for (std::size_t m = 0; m < markers.size(); ++m) {
      if (markers[m].body != static_cast<int>(b)) continue;
      for (int half = 0; half < 2; ++half) {
        if (!(parts[m] & (half == 0 ? 1u : 2u))) continue;
        (half == 0 ? set.tpos : set.rpos)[m] = static_cast<int>(set.rows.size());
        for (int k = 0; k < 3; ++k) set.rows.push_back(mrow_[m] + 3 * half + k);
      }
    }
    set.all = static_cast<Eigen::Index>(set.rows.size()) == bstack_[b].rows();
    set.stack = Mat(static_cast<Eigen::Index>(set.rows.size()), bodies[b].n());
    for (std::size_t k = 0; k < set.rows.size(); ++k)
      set.stack.row(static_cast<Eigen::Index>(k)) = bstack_[b].row(set.rows[k]);
    set.stackT = set.stack.transpose();
    set.y = Vec::Zero(set.stack.rows());
    set.z = Vec::Zero(set.stack.rows());
  }
  return sets;
}

void System::update_markers(double t, const double* q, const double* v, bool reads_only) {
  update_lof(t);
  const auto& markers = model_.markers();
  const auto& bodies = model_.bodies();
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    Eigen::Map<const Vec> qb(q + bodies[b].offset, bodies[b].n()),
        vb(v + bodies[b].offset, bodies[b].n());
    RowSet& set = rset_[b];
    if (!reads_only || set.all) {
      bq_[b].noalias() = bstack_[b] * qb;
      bv_[b].noalias() = bstack_[b] * vb;
      continue;
    }
    set.y.noalias() = set.stack * qb;
    set.z.noalias() = set.stack * vb;
    // rows no element reads are zero, not left from an earlier full update: a
    // wrong motion_reads() then changes the loads (tests compare them)
    bq_[b].setZero();
    bv_[b].setZero();
    for (std::size_t k = 0; k < set.rows.size(); ++k) {
      bq_[b][set.rows[k]] = set.y[k];
      bv_[b][set.rows[k]] = set.z[k];
    }
  }
  for (std::size_t m = 0; m < markers.size(); ++m) {
    const int b = markers[m].body;
    if (b < 0) continue;             // ground: constant, set by the constructor
    if (reads_only && unread_[m]) {  // only the axes (from the frame) are read
      motion_[m].R = axes_[m];
      continue;
    }
    const int r = mrow_[m];
    marker_motion(markers[m], lof_[b], axes_[m], bq_[b].segment<3>(r), bq_[b].segment<3>(r + 3),
                  bv_[b].segment<3>(r), bv_[b].segment<3>(r + 3), motion_[m]);
  }
}

void System::force(double t, const double* q, const double* v, double* f) {
  ++counters.f_evals;
  force_impl(t, q, v, f, reads_only_ && rank_ == 0);
}

void System::apply_load(int id, const Vec3& F, const Vec3& M, double* f) const {
  const Marker& m = model_.markers()[id];
  if (m.on_ground()) return;
  const Body& B = model_.bodies()[m.body];
  const Mat3& R = lof_[m.body].R_GL;
  Eigen::Map<Vec> fb(f + B.offset, B.n());
  const Vec3 F_L = R.transpose() * F;
  const Vec3 M_L = R.transpose() * M;
  fb.noalias() -= m.Bu.transpose() * F_L;
  fb.noalias() -= m.Bt.transpose() * M_L;
}

void System::accumulate_load(int id, const Vec3& F, const Vec3& M) {
  const int b = model_.markers()[id].body;
  if (b < 0) return;
  const Mat3& R = lof_[b].R_GL;
  const int r = mrow_[id];
  bload_[b].segment<3>(r).noalias() += R.transpose() * F;
  bload_[b].segment<3>(r + 3).noalias() += R.transpose() * M;
}

void System::load_element(int e, double t) {
  gather_motion(static_cast<std::size_t>(e));
  evaluate_element(e, t);
  const ElementWork& w = ework_[e];
  const auto& ids = model_.elements()[e]->markers();
  for (std::size_t i = 0; i < ids.size(); ++i) accumulate_load(ids[i], w.loads[i].F, w.loads[i].M);
}

void System::flush_all_loads(double* f) {
  const auto& bodies = model_.bodies();
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    Eigen::Map<Vec> fb(f + bodies[b].offset, bodies[b].n());
    fb.noalias() -= bstackT_[b] * bload_[b];
  }
}

void System::time_loads_full(double t) {
  for (auto& l : bload_) l.setZero();
  for (int e : timed_) load_element(e, t);
  ftime_full_.setZero();
  flush_all_loads(ftime_full_.data());
  t_time_full_ = t;
}

void System::body_terms(const double* q, const double* v, const Vec& ftime, double* f) const {
  const auto& bodies = model_.bodies();
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const Body& B = bodies[b];
    const BodyWork& W = bwork_[b];
    Eigen::Map<const Vec> qb(q + B.offset, B.n()), vb(v + B.offset, B.n());
    Eigen::Map<Vec> fb(f + B.offset, B.n());
    fb = W.f0 + ftime.segment(B.offset, B.n()) + B.data->eigenvalues.cwiseProduct(qb) +
         B.data->damping.cwiseProduct(vb);
    if (!W.frame_free) {  // (a fixed frame: KW = G = 0)
      fb.noalias() += W.KW * qb;
      fb.noalias() += W.G * vb;
    }
  }
}

void System::force_impl(double t, const double* q, const double* v, double* f, bool reads_only) {
  if (reads_only) {  // (callers ask for it only without inertial elements)
    force_rows(t, q, v, f);
    return;
  }
  // every marker row; the loads of time alone from every row too, so that a
  // wrong Element::load_parts() of theirs shows against force_rows()
  update_markers(t, q, v, false);
  if (!timed_.empty() && t != t_time_full_) time_loads_full(t);
  body_terms(q, v, ftime_full_, f);
  for (auto& l : bload_) l.setZero();
  for (int e : loaded_) load_element(e, t);
  flush_all_loads(f);
  if (rank_ > 0) solve_inertia(t, f);
}

void System::solve_inertia(double t, double* f) {
  const auto& markers = model_.markers();
  const auto& bodies = model_.bodies();
  const int n = size();
  Eigen::Map<Vec> F(f, n);
  f0_ = F;
  for (int e : inertial_) {
    ElementWork& w = ework_[e];
    const auto& ids = model_.elements()[e]->markers();
    for (std::size_t i = 0; i < ids.size(); ++i) {
      w.motion[i] = motion_[ids[i]];  // linearise first at the accelerations of qdd = 0
      if (!markers[ids[i]].on_ground()) marker_maps(ids[i]);
    }
  }
  constexpr int kMaxPasses = 4;
  for (int pass = 0; pass < kMaxPasses; ++pass) {
    F = f0_;
    U_.setZero();
    W_.setZero();
    for (int e : inertial_) {
      const Element& el = *model_.elements()[e];
      ElementWork& w = ework_[e];
      const auto& ids = el.markers();
      const int r = el.inertia_rank();
      el.evaluate(t, w.motion.data(), w.loads.data());
      el.inertia(t, w.motion.data(), w.P, w.Q);
      // loads at the accelerations of qdd = 0 by the affine model about w.motion
      for (std::size_t i = 0; i < ids.size(); ++i)
        w.dacc.segment<6>(6 * i) << w.motion[i].a - motion_[ids[i]].a,
            w.motion[i].al - motion_[ids[i]].al;
      w.r_1.noalias() = w.Q.transpose() * w.dacc;
      w.dacc.noalias() = w.P * w.r_1;  // now the load correction
      for (std::size_t i = 0; i < ids.size(); ++i) {
        apply_load(ids[i], w.loads[i].F - w.dacc.segment<3>(6 * i),
                   w.loads[i].M - w.dacc.segment<3>(6 * i + 3), f);
        const Marker& m = markers[ids[i]];
        if (m.on_ground()) continue;
        const Body& B = bodies[m.body];
        U_.block(B.offset, w.col, B.n(), r).noalias() +=
            Lm_[ids[i]].transpose() * w.P.middleRows<6>(6 * i);
        W_.block(B.offset, w.col, B.n(), r).noalias() +=
            Lm_[ids[i]].transpose() * w.Q.middleRows<6>(6 * i);
      }
    }
    // M^-1 f_0 = f_0 + U (I - W^T U)^-1 W^T f_0
    Z_.noalias() = -W_.transpose() * U_;
    Z_.diagonal().array() += 1.0;
    lu_.compute(Z_);
    if (!(lu_.rcond() > 1e-14)) {
      std::string names;
      for (int e : inertial_) names += " '" + model_.elements()[e]->name() + "'";
      throw RunError("the mass matrix with the inertial elements" + names + " is singular (rcond " +
                     std::to_string(lu_.rcond()) + ") at t = " + std::to_string(t) + " s");
    }
    y_.noalias() = W_.transpose() * F;
    y_ = lu_.solve(y_);
    F.noalias() += U_ * y_;
    // the solved accelerations become each element's linearisation point
    double change = 0.0;
    for (int e : inertial_) {
      const Element& el = *model_.elements()[e];
      ElementWork& w = ework_[e];
      const auto& ids = el.markers();
      for (std::size_t i = 0; i < ids.size(); ++i) {
        const Marker& m = markers[ids[i]];
        Vec6 acc;
        acc << motion_[ids[i]].a, motion_[ids[i]].al;
        if (!m.on_ground()) {
          const Body& B = bodies[m.body];
          acc.noalias() -= Lm_[ids[i]] * F.segment(B.offset, B.n());  // qdd = -F
        }
        Vec6 old;
        old << w.motion[i].a, w.motion[i].al;
        for (int c = 0; c < w.Q.cols(); ++c) {
          const auto qc = w.Q.col(c).segment<6>(6 * i);
          change = std::max(change, std::abs(qc.dot(acc - old)) / (1.0 + std::abs(qc.dot(acc))));
        }
        w.motion[i].a = acc.head<3>();
        w.motion[i].al = acc.tail<3>();
      }
    }
    // (a branch that still flips after the last pass keeps that pass's result: the
    // loads are continuous across the kink, so both sides nearly agree there)
    if (!piecewise_ || change <= 1e-12) break;
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

void System::observe(double t, const double* q, const double* v, const std::vector<int>& markers) {
  if (rank_ > 0) {
    observe(t, q, v);
    return;
  }
  const auto& all = model_.markers();
  if (oset_.empty() || markers != observed_) {  // (set-up: allocates when the list changes)
    observed_ = markers;
    std::vector<unsigned> parts(all.size(), 0u);
    for (int m : markers)
      parts.at(static_cast<std::size_t>(m)) = Element::kReadsTranslation | Element::kReadsRotation;
    oset_ = row_sets(parts);
  }
  update_lof(t);
  row_products(oset_, q, v);
  for (int m : observed_) {
    const int b = all[m].body;
    if (b < 0) continue;  // ground: constant, set by the constructor
    const RowSet& o = oset_[b];
    const int r = o.tpos[m];
    marker_motion(all[m], lof_[b], axes_[m], o.y.segment<3>(r), o.y.segment<3>(r + 3),
                  o.z.segment<3>(r), o.z.segment<3>(r + 3), motion_[m]);
  }
}

void System::observe(double t, const double* q, const double* v) {
  if (rank_ == 0) {  // no element reads accelerations: the motion is enough
    update_markers(t, q, v);
    return;
  }
  force_impl(t, q, v, scratch_f_.data());  // qdd = -f; leaves the LOF and motion_ current
  const auto& markers = model_.markers();
  const auto& bodies = model_.bodies();
  for (std::size_t m = 0; m < markers.size(); ++m) {
    if (markers[m].on_ground()) continue;
    marker_maps(static_cast<int>(m));
    const Body& B = bodies[markers[m].body];
    const auto fb = scratch_f_.segment(B.offset, B.n());
    motion_[m].a.noalias() -= Lm_[m].topRows<3>() * fb;
    motion_[m].al.noalias() -= Lm_[m].bottomRows<3>() * fb;
  }
}

void System::marker_maps(int mi) {
  const Marker& m = model_.markers()[mi];
  const LofState& L = lof_[m.body];
  Mat& Lm = Lm_[mi];
  Mat& Pq = Pq_[mi];
  Mat& Pv = Pv_[mi];
  Lm.topRows<3>().noalias() = L.R_GL * m.Bu;
  Lm.bottomRows<3>().noalias() = L.R_GL * m.Bt;
  Pq.middleRows<3>(0) = Lm.topRows<3>();
  Pq.middleRows<3>(3).noalias() = skew(L.w_GL_G) * Lm.topRows<3>();
  Pq.middleRows<3>(6) = Lm.bottomRows<3>();
  Pq.middleRows<3>(9).setZero();
  Pv.middleRows<3>(0).setZero();
  Pv.middleRows<3>(3) = Lm.topRows<3>();
  Pv.middleRows<3>(6).setZero();
  Pv.middleRows<3>(9) = Lm.bottomRows<3>();
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
  const auto& markers = model_.markers();
  for (auto& pw : pairs_) {
    if (comb)
      pw.Y.leftCols(pw.Y.cols() / 2).setZero();
    else
      pw.Y.setZero();
  }
  const int nb = static_cast<int>(model_.bodies().size());
  for (std::size_t e = 0; e < ework_.size(); ++e) {
    if (is_timed_[e]) continue;  // loads of time alone: D = 0
    const Element& el = *model_.elements()[e];
    ElementWork& w = ework_[e];
    const auto& ids = el.markers();
    if (el.inertia_rank() == 0)  // inertial ones keep the motion solve_inertia left
      for (std::size_t i = 0; i < ids.size(); ++i) w.motion[i] = motion_[ids[i]];
    if (zoff_[e] >= 0)
      el.derivatives_z(t, w.motion.data(), z_.data() + zoff_[e], w.D);
    else
      el.derivatives(t, w.motion.data(), w.D);
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
  // f = ... - Q  =>  [K C] -= [Bu; Bt]_i^T [YK YC], over the loaded rows
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
  if (rank_ > 0) {  // M^-1 (ck K + cc C) = ck M^-1 K + cc M^-1 C
    apply_inverse_mass(K);
    if (!comb) apply_inverse_mass(*C);
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

double System::next_stop(double t) const {
  double next = std::numeric_limits<double>::infinity();
  for (const auto& b : model_.bodies()) {
    const double tol = 1e-12 * std::max(1.0, std::abs(t));
    if (b.lof.kind() == LofKind::Spin) {
      for (double k : b.lof.knots())
        if (k > t + tol) {
          next = std::min(next, k);
          break;
        }
    } else if (b.lof.kind() == LofKind::Tracking) {
      const double h = b.lof.interval();
      double k = std::floor(t / h) + 1.0;
      if (k * h <= t + tol) k += 1.0;
      next = std::min(next, k * h);
    }
  }
  return next;
}

bool System::at_stop(double t, double* q, double* v) {
  bool changed = false;
  const auto& bodies = model_.bodies();
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    if (bodies[b].lof.kind() != LofKind::Tracking) continue;
    const double h = bodies[b].lof.interval();
    const double k = std::round(t / h);
    if (std::abs(t - k * h) > 1e-9 * h) continue;
    reanchor(static_cast<int>(b), t, q, v);
    changed = true;
  }
  if (changed) t_lof_ = t_time_ = t_time_full_ = std::numeric_limits<double>::quiet_NaN();
  return changed;
}

void System::reanchor(int bi, double t, double* q, double* v) {
  Body& B = model_.bodies()[bi];
  const MassProperties& mp = B.mp;
  double* qb = q + B.offset;
  double* vb = v + B.offset;
  const double sm = std::sqrt(mp.mass);
  Vec3 dc, dcd, th, thd;
  for (int a = 0; a < 3; ++a) {
    dc[a] = qb[B.rigid[a]] / sm;
    dcd[a] = vb[B.rigid[a]] / sm;
  }
  th.setZero();
  thd.setZero();
  for (int k = 0; k < 3; ++k) {
    const double sj = std::sqrt(mp.principal_moments[k]);
    th += mp.principal_axes.col(k) * (qb[B.rigid[3 + k]] / sj);
    thd += mp.principal_axes.col(k) * (vb[B.rigid[3 + k]] / sj);
  }
  const LofState L = B.lof.at(t);
  LofState N;
  N.R_GL = L.R_GL * rotation_from_vector(th);
  const Vec3 rc = L.R_GL * (mp.com + dc);
  N.p_GL = L.p_GL + rc - N.R_GL * mp.com;
  N.w_GL_G = L.w_GL_G + L.R_GL * thd;
  const Vec3 v_com = L.v_GL + L.w_GL_G.cross(rc) + L.R_GL * dcd;
  N.v_GL = v_com - N.w_GL_G.cross(N.R_GL * mp.com);
  N.psi_G = L.psi_G + L.R_GL * th;
  B.lof.reanchor(t, N);
  for (int r : B.rigid) {
    qb[r] = 0.0;
    vb[r] = 0.0;
  }
}

std::string System::describe_coordinate(int i) const {
  for (const auto& b : model_.bodies()) {
    if (i < b.offset || i >= b.offset + b.n()) continue;
    const int k = i - b.offset;
    std::ostringstream os;
    os << "body '" << b.name << "', mode " << k;
    if (b.data->kinds[static_cast<std::size_t>(k)] == ModeKind::Rigid)
      os << " (rigid)";
    else
      os << " (elastic, " << std::sqrt(std::max(0.0, b.data->eigenvalues[k])) / (2.0 * M_PI)
         << " Hz)";
    return os.str();
  }
  return Problem::describe_coordinate(i);
}

std::string System::describe_state(double t, const double* q, const double* v) const {
  std::ostringstream os;
  os << "t = " << t << " s";
  for (const auto& b : model_.bodies()) {
    Eigen::Map<const Vec> qb(q + b.offset, b.n()), vb(v + b.offset, b.n());
    Eigen::Index iq = 0, iv = 0;
    const double mq = b.n() ? qb.cwiseAbs().maxCoeff(&iq) : 0.0;
    const double mv = b.n() ? vb.cwiseAbs().maxCoeff(&iv) : 0.0;
    os << "; body '" << b.name << "': max|q| = " << mq << " (mode " << iq << "), max|v| = " << mv
       << " (mode " << iv << ")";
    if (!qb.allFinite() || !vb.allFinite()) os << " NON-FINITE";
  }
  for (int i = 0; i < nz_; ++i) os << "; " << internal_name(i) << " = " << z_[i];
  return os.str();
}

}  // namespace evas
