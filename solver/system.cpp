// The System's construction (solver/system.h): the constructor and the parts it
// builds in turn (body and marker work, the bodies' stacked marker maps, element
// work, the row sets, the inertial work, the pattern), the initial state and the
// descriptions of coordinates and states for messages.
#include "solver/system.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace evas {

System::System(Model& model) : model_(model) {
  const int nb = static_cast<int>(model_.bodies().size());
  const int n = model_.size();
  setup_body_work();
  setup_marker_work();
  setup_body_stacks();

  // Pattern: dense diagonal body blocks plus body-pair blocks of every element.
  std::vector<char> pair(static_cast<std::size_t>(nb) * nb, 0);
  for (int b = 0; b < nb; ++b) pair[b * nb + b] = 1;
  setup_element_work(pair);
  build_row_sets();
  build_pair_rows();
  if (rank_ > 0) setup_inertial_work(pair);
  scratch_f_ = Vec::Zero(n);
  build_pattern(pair);
  setup_joints();
  setup_internal();
  setup_quasi_static();
}

void System::setup_quasi_static() {
  qs_.clear();
  for (const Body& b : model_.bodies()) {
    if (b.quasi_static.empty()) continue;
    for (int k : b.quasi_static) {
      if (k < 0 || k >= b.n() || (!qs_.empty() && b.offset + k <= qs_.back()))
        throw std::logic_error("System: body '" + b.name + "': quasi-static mode " +
                               std::to_string(k) + " out of range or out of order");
      // without damping the mode's velocity is of index 2 (f_k would not depend on it)
      if (!(b.data->damping[k] > 0.0))
        throw InputError(describe_coordinate(b.offset + k) +
                         ": a quasi-static mode needs modal damping (damping_ratio > 0): "
                         "without it its velocity is an index-2 variable");
      qs_.push_back(b.offset + k);
    }
    if (!inertial_.empty())
      throw InputError("body '" + b.name +
                       "' has quasi-static modes, which cannot be combined "
                       "with the inertial element '" +
                       model_.elements()[static_cast<std::size_t>(inertial_.front())]->name() +
                       "' (its mass acts on the modes' accelerations); make it uncoupled or "
                       "keep the body's modes dynamic");
  }
}

void System::setup_body_work() {
  auto& bodies = model_.bodies();
  const int nb = static_cast<int>(bodies.size());
  lof_.resize(nb);
  bwork_.resize(nb);
  for (int b = 0; b < nb; ++b) {
    const int nbm = bodies[b].n();
    bwork_[b].f0 = Vec::Zero(nbm);
    bwork_[b].KW = Mat::Zero(nbm, nbm);
    bwork_[b].G = Mat::Zero(nbm, nbm);
  }
}

void System::setup_marker_work() {
  const auto& bodies = model_.bodies();
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
}

void System::setup_body_stacks() {
  const auto& bodies = model_.bodies();
  const auto& markers = model_.markers();
  const int nb = static_cast<int>(bodies.size());
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
}

void System::setup_element_work(std::vector<char>& pair) {
  const auto& bodies = model_.bodies();
  const auto& markers = model_.markers();
  const int nb = static_cast<int>(bodies.size());
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
}

void System::setup_inertial_work(std::vector<char>& pair) {
  const auto& markers = model_.markers();
  const int nb = static_cast<int>(model_.bodies().size());
  const int n = model_.size();
  // M^-1 K = K + U Z^-1 W^T K fills rows of the inertial bodies in the columns of
  // their neighbours (the bodies their rows of K reach).
  std::vector<char> inert(static_cast<std::size_t>(nb), 0), reach(static_cast<std::size_t>(nb), 0);
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

void System::initial_state(Vec& q, Vec& v) const {
  q.resize(size());
  v.resize(size());
  for (const auto& b : model_.bodies()) {
    q.segment(b.offset, b.n()) = b.q0;
    v.segment(b.offset, b.n()) = b.v0;
  }
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
         << " Hz"
         << (std::binary_search(b.quasi_static.begin(), b.quasi_static.end(), k) ? ", quasi-static"
                                                                                 : "")
         << ")";
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
