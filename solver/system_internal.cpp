// Element internal states of the System (Problem's "internal states" part).
//
// z = [z_e0; z_e1; ...] for the elements with Element::internal_count() > 0, in
// element order. With the loads L_e(motion, z_e) and rates h_e(motion, z_e):
//   f  = ... - sum Lm^T L_e           =>  Fz = df/dz_e   = -Lm_i^T Dz_i  (marker i's rows)
//   h_e(motion(q, v), z_e)            =>  Hq = dh_e/dq_j = Hm_j Pq_j, Hv = Hm_j Pv_j
//                                         Hz = dh_e/dz_e
// (Lm, Pq, Pv: the marker maps of solver/system.h). With inertial elements f is
// M^-1 f_0, so Fz becomes M^-1 Fz (apply_inverse_mass), which fills the rows of
// the inertial bodies: the pattern of Fz holds them.
#include <algorithm>
#include <sstream>

#include "solver/system.h"

namespace evas {

void System::setup_internal() {
  const auto& elements = model_.elements();
  const auto& markers = model_.markers();
  const auto& bodies = model_.bodies();
  zoff_.assign(elements.size(), -1);
  zelem_.clear();
  nz_ = 0;
  for (std::size_t e = 0; e < elements.size(); ++e) {
    const Element& el = *elements[e];
    const int nze = el.internal_count();
    if (nze <= 0) continue;
    if (el.inertia_rank() > 0)
      throw InputError("element '" + el.name() +
                       "': internal states together with inertial loads are not supported");
    zoff_[e] = nz_;
    nz_ += nze;
    for (int i = 0; i < nze; ++i) zelem_.push_back(static_cast<int>(e));
    const auto k = static_cast<int>(el.markers().size());
    ework_[e].Dz = Mat::Zero(6 * k, nze);
    ework_[e].Hm = Mat::Zero(nze, 12 * k);
    ework_[e].Hz = Mat::Zero(nze, nze);
  }
  z_ = Vec::Zero(nz_);
  const int n = size();
  std::vector<char> inert(bodies.size(), 0);
  for (int e : inertial_)
    for (int mi : elements[e]->markers())
      if (markers[mi].body >= 0) inert[markers[mi].body] = 1;
  std::vector<Triplet> fz, hq, hz;
  for (std::size_t e = 0; e < elements.size(); ++e) {
    if (zoff_[e] < 0) continue;
    const Element& el = *elements[e];
    std::vector<char> touched(bodies.size(), 0);
    for (int mi : el.markers())
      if (markers[mi].body >= 0) touched[markers[mi].body] = 1;
    const int z0 = zoff_[e], nze = el.internal_count();
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      for (int i = 0; i < nze; ++i)
        for (int c = 0; c < bodies[b].n(); ++c) {
          if (touched[b] || (rank_ > 0 && inert[b]))
            fz.emplace_back(bodies[b].offset + c, z0 + i, 0.0);
          if (touched[b]) hq.emplace_back(z0 + i, bodies[b].offset + c, 0.0);
        }
    }
    for (int i = 0; i < nze; ++i)
      for (int j = 0; j < nze; ++j) hz.emplace_back(z0 + i, z0 + j, 0.0);
  }
  auto build = [](SpMat& A, int rows, int cols, const std::vector<Triplet>& t) {
    A.resize(rows, cols);
    A.setFromTriplets(t.begin(), t.end());
    A.makeCompressed();
    A.coeffs().setZero();
  };
  build(fz_pat_, n, nz_, fz);
  build(hq_pat_, nz_, n, hq);
  hv_pat_ = hq_pat_;
  build(hz_pat_, nz_, nz_, hz);
}

const MarkerMotion* System::gather_motion(std::size_t e) {
  ElementWork& w = ework_[e];
  const auto& ids = model_.elements()[e]->markers();
  for (std::size_t i = 0; i < ids.size(); ++i) w.motion[i] = motion_[ids[i]];
  return w.motion.data();
}

void System::evaluate_element(int e, double t) {
  const Element& el = *model_.elements()[e];
  ElementWork& w = ework_[e];
  if (zoff_[e] >= 0)
    el.evaluate_z(t, w.motion.data(), z_.data() + zoff_[e], w.loads.data());
  else
    el.evaluate(t, w.motion.data(), w.loads.data());
}

bool System::internal_algebraic(int i) const {
  const int e = zelem_.at(static_cast<std::size_t>(i));
  return model_.elements()[e]->internal_algebraic(i - zoff_[e]);
}

std::string System::internal_name(int i) const {
  const int e = zelem_.at(static_cast<std::size_t>(i));
  const Element& el = *model_.elements()[e];
  return "element '" + el.name() + "' state " + el.internal_name(i - zoff_[e]) +
         (el.internal_algebraic(i - zoff_[e]) ? " (algebraic)" : "");
}

void System::set_internal(const double* z) {
  if (nz_ > 0) std::copy(z, z + nz_, z_.data());
}

void System::internal_initial(double t, const Vec& q, const Vec& v, Vec& z) {
  z = Vec::Zero(nz_);
  if (nz_ == 0) return;
  update_markers(t, q.data(), v.data());
  for (std::size_t e = 0; e < ework_.size(); ++e)
    if (zoff_[e] >= 0)
      model_.elements()[e]->internal_initial(t, gather_motion(e), z.data() + zoff_[e]);
}

void System::internal_rate(double t, const double* q, const double* v, double* h) {
  update_markers(t, q, v);
  for (std::size_t e = 0; e < ework_.size(); ++e)
    if (zoff_[e] >= 0)
      model_.elements()[e]->internal_rate(t, gather_motion(e), z_.data() + zoff_[e], h + zoff_[e]);
}

void System::internal_patterns(SpMat& Fz, SpMat& Hq, SpMat& Hv, SpMat& Hz) const {
  Fz = fz_pat_;
  Hq = hq_pat_;
  Hv = hv_pat_;
  Hz = hz_pat_;
}

void System::internal_jacobian(double t, const double* q, const double* v, SpMat& Fz, SpMat& Hq,
                               SpMat& Hv, SpMat& Hz) {
  // inertial elements: U, W and the factorization at this state (apply_inverse_mass)
  if (rank_ > 0)
    force_impl(t, q, v, scratch_f_.data());
  else
    update_markers(t, q, v);
  Fz.coeffs().setZero();
  Hq.coeffs().setZero();
  Hv.coeffs().setZero();
  Hz.coeffs().setZero();
  const auto& markers = model_.markers();
  const auto& bodies = model_.bodies();
  for (std::size_t e = 0; e < ework_.size(); ++e) {
    if (zoff_[e] < 0) continue;
    const Element& el = *model_.elements()[e];
    ElementWork& w = ework_[e];
    const auto& ids = el.markers();
    const int z0 = zoff_[e], nze = el.internal_count();
    for (std::size_t i = 0; i < ids.size(); ++i) {
      w.motion[i] = motion_[ids[i]];
      if (!markers[ids[i]].on_ground()) marker_maps(ids[i]);
    }
    el.internal_derivatives(t, w.motion.data(), z_.data() + z0, w.Dz, w.Hm, w.Hz);
    for (int i = 0; i < nze; ++i)
      for (int j = 0; j < nze; ++j) Hz.coeffRef(z0 + i, z0 + j) += w.Hz(i, j);
    for (std::size_t i = 0; i < ids.size(); ++i) {
      const int b = markers[ids[i]].body;
      if (b < 0) continue;
      const Body& B = bodies[b];
      const Mat fzb = -Lm_[ids[i]].transpose() * w.Dz.middleRows(6 * static_cast<int>(i), 6);
      const Mat hqb = w.Hm.middleCols(12 * static_cast<int>(i), 12) * Pq_[ids[i]];
      const Mat hvb = w.Hm.middleCols(12 * static_cast<int>(i), 12) * Pv_[ids[i]];
      for (int c = 0; c < nze; ++c)
        for (int r = 0; r < B.n(); ++r) {
          Fz.coeffRef(B.offset + r, z0 + c) += fzb(r, c);
          Hq.coeffRef(z0 + c, B.offset + r) += hqb(c, r);
          Hv.coeffRef(z0 + c, B.offset + r) += hvb(c, r);
        }
    }
  }
  if (rank_ > 0 && nz_ > 0) apply_inverse_mass(Fz);
}

}  // namespace evas
