// System::force() from the rows the elements read (system.h, "The residual
// from the rows the elements read"): the path every integrator's residual takes
// when the model has no inertial elements.
#include "solver/system.h"

namespace evas {

void System::build_slot_rows() {
  const auto& markers = model_.markers();
  const auto& elements = model_.elements();
  slot_rows_.assign(elements.size(), {});
  for (std::size_t e = 0; e < elements.size(); ++e) {
    const Element& el = *elements[e];
    const std::vector<RowSet>& lsets = is_timed_[e] ? tset_ : lset_;
    auto& slots = slot_rows_[e];
    slots.resize(el.markers().size());
    for (std::size_t i = 0; i < slots.size(); ++i) {
      const int m = el.markers()[i];
      SlotRows& s = slots[i];
      s.body = markers[m].body;
      if (s.body < 0) {  // ground: constant, once here (the other paths copy the same)
        ework_[e].motion[i] = motion_[m];
        continue;
      }
      const RowSet& r = rset_[s.body];
      const RowSet& l = lsets[s.body];
      const unsigned reads = el.motion_reads(i), loads = el.load_parts(i);
      if (reads & Element::kReadsTranslation) s.uq = r.tpos[m];
      if (reads & Element::kReadsRotation) s.tq = r.rpos[m];
      if (loads & Element::kLoadsForce) s.fl = l.tpos[m];
      if (loads & Element::kLoadsMoment) s.ml = l.rpos[m];
    }
  }
}

void System::load_element_rows(int e, double t, std::vector<RowSet>& sets) {
  const auto& markers = model_.markers();
  const auto& ids = model_.elements()[e]->markers();
  const auto& slots = slot_rows_[e];
  ElementWork& w = ework_[e];
  const Vec3 zero = Vec3::Zero();
  for (std::size_t i = 0; i < slots.size(); ++i) {
    const SlotRows& s = slots[i];
    if (s.body < 0) continue;
    if (s.uq < 0 && s.tq < 0) {  // reads only the axes (e.g. the prescribed piston)
      w.motion[i].R = axes_[ids[i]];
      continue;
    }
    const RowSet& r = rset_[s.body];
    // what the element does not read stays at the undeformed marker (not current)
    marker_motion(markers[ids[i]], lof_[s.body], axes_[ids[i]],
                  s.uq >= 0 ? Vec3(r.y.segment<3>(s.uq)) : zero,
                  s.tq >= 0 ? Vec3(r.y.segment<3>(s.tq)) : zero,
                  s.uq >= 0 ? Vec3(r.z.segment<3>(s.uq)) : zero,
                  s.tq >= 0 ? Vec3(r.z.segment<3>(s.tq)) : zero, w.motion[i]);
  }
  evaluate_element(e, t);
  for (std::size_t i = 0; i < slots.size(); ++i) {
    const SlotRows& s = slots[i];
    if (s.body < 0) continue;
    const Mat3& R = lof_[s.body].R_GL;
    Vec& y = sets[static_cast<std::size_t>(s.body)].y;
    if (s.fl >= 0) y.segment<3>(s.fl).noalias() += R.transpose() * w.loads[i].F;
    if (s.ml >= 0) y.segment<3>(s.ml).noalias() += R.transpose() * w.loads[i].M;
  }
}

void System::time_loads(double t) {
  for (RowSet& s : tset_) s.y.setZero();
  for (int e : timed_) load_element_rows(e, t, tset_);
  ftime_.setZero();
  const auto& bodies = model_.bodies();
  for (std::size_t b = 0; b < bodies.size(); ++b)
    ftime_.segment(bodies[b].offset, bodies[b].n()).noalias() -= tset_[b].stackT * tset_[b].y;
  t_time_ = t;
}

void System::row_products(std::vector<RowSet>& sets, const double* q, const double* v) const {
  const auto& bodies = model_.bodies();
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    RowSet& r = sets[b];
    if (r.rows.empty()) continue;
    Eigen::Map<const Vec> qb(q + bodies[b].offset, bodies[b].n()),
        vb(v + bodies[b].offset, bodies[b].n());
    r.y.noalias() = r.stack * qb;
    r.z.noalias() = r.stack * vb;
  }
}

void System::force_rows(double t, const double* q, const double* v, double* f) {
  update_lof(t);
  row_products(rset_, q, v);
  const auto& bodies = model_.bodies();
  if (!timed_.empty() && t != t_time_) time_loads(t);
  body_terms(q, v, ftime_, f);
  for (RowSet& s : lset_) s.y.setZero();
  for (int e : loaded_) load_element_rows(e, t, lset_);
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    Eigen::Map<Vec> fb(f + bodies[b].offset, bodies[b].n());
    fb.noalias() -= lset_[b].stackT * lset_[b].y;
  }
}

}  // namespace evas
