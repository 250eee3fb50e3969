// System::force() on the full path (every marker row) and with inertial elements
// (the Woodbury solve of M^-1 f_0), the marker motions it starts from, and the
// motions for outputs (observe). The path from the rows the elements read alone
// is solver/system_rows.cpp.
#include <algorithm>
#include <cmath>
#include <string>

#include "solver/system.h"

namespace evas {

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
    add_inertial_loads(t, f);
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
    const double change = relinearise_inertia(f);
    // (a branch that still flips after the last pass keeps that pass's result: the
    // loads are continuous across the kink, so both sides nearly agree there)
    if (!piecewise_ || change <= 1e-12) break;
  }
}

void System::add_inertial_loads(double t, double* f) {
  const auto& markers = model_.markers();
  const auto& bodies = model_.bodies();
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
}

double System::relinearise_inertia(const double* f) {
  const auto& markers = model_.markers();
  const auto& bodies = model_.bodies();
  Eigen::Map<const Vec> F(f, size());
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
  return change;
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
  observe_accelerations(t, q, v);
}

void System::observe_accelerations(double t, const double* q, const double* v) {
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

}  // namespace evas
