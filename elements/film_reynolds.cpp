// Reynolds film of a finite journal bearing: see film_reynolds.h and
// docs/elements-journal-bearing.md ("Film models").
#include "elements/film_reynolds.h"

#include <Eigen/Sparse>
#include <algorithm>
#include <cmath>
#include <string>

#include "model/types.h"

namespace evas {

namespace {

using V2 = Eigen::Vector2d;

// The film's linear system on the pressurized cells (q = 0 on the others),
// factored once per active set. Cells are numbered ring by ring (i around, j
// across: k = i nz + j), so the matrix is banded with half-bandwidth nz but
// for the wrap from the last ring to the first. Where a whole ring is
// cavitated (the usual case: Swift-Stieber leaves the diverging film empty),
// the numbering starts after it and nothing wraps: a band Cholesky
// factorization, n nz^2 / 2 operations. Otherwise (no cavitation, or a film
// pressurized all round) a sparse LDL^T of the pressurized cells.
class FilmSystem {
 public:
  // inner: the cells next to the mid-plane see a fixed pressure across their
  // inner face (a circumferential groove) instead of the symmetry plane
  FilmSystem(int np, int nz, const std::vector<double>& aphi, const std::vector<double>& az,
             bool inner)
      : np_(np), nz_(nz), aphi_(aphi), az_(az), inner_(inner) {}

  void factor(const std::vector<char>& on) {
    on_ = &on;
    start_ = -1;
    for (int i = 0; i < np_ && start_ < 0; ++i) {
      bool empty = true;
      for (int j = 0; j < nz_ && empty; ++j) empty = !on[i * nz_ + j];
      if (empty) start_ = i;
    }
    if (start_ >= 0)
      factor_band();
    else
      factor_sparse();
  }

  /// Solution for the right side g (all cells); zero on the cavitated cells.
  Eigen::VectorXd solve(const Eigen::VectorXd& g) const {
    const int n = np_ * nz_;
    Eigen::VectorXd q = Eigen::VectorXd::Zero(n);
    const std::vector<char>& on = *on_;
    if (start_ >= 0) {
      const int m = (np_ - 1) * nz_, b = nz_, w = b + 1;
      Eigen::VectorXd x(m);
      for (int t = 0; t < m; ++t) x[t] = on[cells_[t]] ? g[cells_[t]] : 0.0;
      for (int t = 0; t < m; ++t) {  // L y = x
        const double* row = &L_[static_cast<std::size_t>(t) * w];
        double v = x[t];
        for (int d = std::min(b, t); d >= 1; --d) v -= row[d] * x[t - d];
        x[t] = v * inv_[t];
      }
      for (int t = m - 1; t >= 0; --t) {  // L^T q = y
        const double v = x[t] * inv_[t];
        x[t] = v;
        const double* row = &L_[static_cast<std::size_t>(t) * w];
        for (int d = 1; d <= std::min(b, t); ++d) x[t - d] -= row[d] * v;
      }
      for (int t = 0; t < m; ++t)
        if (on[cells_[t]]) q[cells_[t]] = x[t];
      return q;
    }
    Eigen::VectorXd gp(m_);
    for (int k = 0; k < n; ++k)
      if (map_[k] >= 0) gp[map_[k]] = g[k];
    const Eigen::VectorXd qp = chol_.solve(gp);
    for (int k = 0; k < n; ++k)
      if (map_[k] >= 0) q[k] = qp[map_[k]];
    return q;
  }

  bool banded() const { return start_ >= 0; }

 private:
  // The operator on the rings after start_, cavitated cells as q = 0 rows.
  void factor_band() {
    const int m = (np_ - 1) * nz_, b = nz_, w = b + 1;
    const std::vector<char>& on = *on_;
    cells_.resize(m);
    for (int t = 0; t < m; ++t) cells_[t] = ((start_ + 1 + t / nz_) % np_) * nz_ + t % nz_;
    // A in band storage, row by row: L_[t w + d] = A(t, t - d), d = 0..b
    L_.assign(static_cast<std::size_t>(m) * w, 0.0);
    inv_.resize(m);
    for (int t = 0; t < m; ++t) {
      double* row = &L_[static_cast<std::size_t>(t) * w];
      const int k = cells_[t], i = k / nz_, j = k % nz_;
      if (!on[k]) {
        row[0] = 1.0;  // q = 0
        continue;
      }
      const int in = (i + 1) % np_;
      row[0] = aphi_[in] + aphi_[i] + (j + 1 < nz_ ? az_[i] : 0.0) + (j > 0 ? az_[i] : 0.0) +
               (j == 0 ? 2.0 * az_[i] : 0.0) + (inner_ && j + 1 == nz_ ? 2.0 * az_[i] : 0.0);
      if (j > 0 && on[k - 1]) row[1] = -az_[i];             // (i, j - 1)
      if (t >= b && on[cells_[t - b]]) row[b] = -aphi_[i];  // the ring before, same j
    }
    for (int t = 0; t < m; ++t) {  // band Cholesky in place: L(t, k) = row_t[t - k]
      double* rt = &L_[static_cast<std::size_t>(t) * w];
      for (int d = std::min(b, t); d >= 1; --d) {
        const int k = t - d;
        const double* rk = &L_[static_cast<std::size_t>(k) * w];
        double v = rt[d];
        // sum over l = t - b .. k - 1 of L(t, l) L(k, l)
        for (int dl = d + 1; dl <= std::min(b, t); ++dl) v -= rt[dl] * rk[dl - d];
        rt[d] = v * inv_[k];
      }
      double v = rt[0];
      for (int d = 1; d <= std::min(b, t); ++d) v -= rt[d] * rt[d];
      if (!(v > 0.0)) throw RunError("Reynolds film: the film matrix is not positive definite");
      rt[0] = std::sqrt(v);
      inv_[t] = 1.0 / rt[0];
    }
  }

  void factor_sparse() {
    const int n = np_ * nz_;
    const std::vector<char>& on = *on_;
    map_.assign(n, -1);
    m_ = 0;
    for (int k = 0; k < n; ++k)
      if (on[k]) map_[k] = m_++;
    if (m_ == 0) return;
    std::vector<Eigen::Triplet<double>> trip;
    trip.reserve(5 * m_);
    for (int i = 0; i < np_; ++i) {
      const int in = (i + 1) % np_, ip = (i + np_ - 1) % np_;
      for (int j = 0; j < nz_; ++j) {
        const int r = map_[i * nz_ + j];
        if (r < 0) continue;
        double diag = aphi_[in] + aphi_[i];
        auto off = [&](int k, double a) {
          if (map_[k] >= 0) trip.emplace_back(r, map_[k], -a);
        };
        off(in * nz_ + j, aphi_[in]);
        off(ip * nz_ + j, aphi_[i]);
        if (j + 1 < nz_) diag += az_[i], off(i * nz_ + j + 1, az_[i]);
        if (j > 0) diag += az_[i], off(i * nz_ + j - 1, az_[i]);
        if (j == 0) diag += 2.0 * az_[i];
        if (inner_ && j + 1 == nz_) diag += 2.0 * az_[i];
        trip.emplace_back(r, r, diag);
      }
    }
    Eigen::SparseMatrix<double> A(m_, m_);
    A.setFromTriplets(trip.begin(), trip.end());
    chol_.compute(A);
    if (chol_.info() != Eigen::Success) throw RunError("Reynolds film: factorization failed");
  }

  int np_, nz_;
  const std::vector<double>& aphi_;
  const std::vector<double>& az_;
  bool inner_;
  const std::vector<char>* on_ = nullptr;
  int start_ = -1;
  std::vector<int> cells_;   // band position t (rings after start_, in order) -> cell
  std::vector<double> L_;    // band factor, row by row: L_[t (nz + 1) + d] = L(t, t - d)
  std::vector<double> inv_;  // 1 / L(t, t)
  std::vector<int> map_;
  int m_ = 0;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> chol_;
};

}  // namespace

ReynoldsFilm::ReynoldsFilm(double radius, double width, double clearance, double viscosity,
                           const ReynoldsGrid& grid)
    : R_(radius), B_(width), c_(clearance), eta_(viscosity), grid_(grid) {
  if (grid_.n_phi < 8 || grid_.n_axial < 1)
    throw InputError(
        "Reynolds film: the grid needs at least 8 cells around and 1 on the half "
        "width (got " +
        std::to_string(grid_.n_phi) + " x " + std::to_string(grid_.n_axial) + ")");
  const int n = grid_.n_phi;
  const double dphi = 2.0 * M_PI / n;
  cos_c_.resize(n);
  sin_c_.resize(n);
  cos_f_.resize(n);
  sin_f_.resize(n);
  for (int i = 0; i < n; ++i) {
    cos_c_[i] = std::cos((i + 0.5) * dphi);
    sin_c_[i] = std::sin((i + 0.5) * dphi);
    cos_f_[i] = std::cos(i * dphi);
    sin_f_[i] = std::sin(i * dphi);
  }
  const ReynoldsFeed& feed = grid_.feed;
  auto deg = [](double a) { return format_number(a * 180.0 / M_PI); };
  if (!(feed.supply_pressure >= 0.0))
    throw InputError("Reynolds film: the supply pressure " + format_number(feed.supply_pressure) +
                     " Pa is below 0");
  if (!(feed.groove_width >= 0.0) || feed.groove_width >= B_)
    throw InputError("Reynolds film: a circumferential groove " + format_number(feed.groove_width) +
                     " m wide leaves no land of the " + format_number(B_) + " m bearing width");
  inner_feed_ = feed.groove_width > 0.0;
  dxi_ = 0.5 * (1.0 - feed.groove_width / B_) / grid_.n_axial;
  q_supply_ = feed.supply_pressure * c_ * c_ * c_ / (12.0 * eta_ * R_ * R_);
  fed_.assign(n, 0);
  for (double a : feed.groove_angles) {
    if (!(feed.groove_arc > 0.0 && feed.groove_arc < 2.0 * M_PI))
      throw InputError("Reynolds film: an axial groove's arc of " + deg(feed.groove_arc) +
                       " deg must lie between 0 and 360 deg");
    int cells = 0;
    for (int i = 0; i < n; ++i) {
      const double d = std::remainder((i + 0.5) * dphi - a, 2.0 * M_PI);
      if (std::abs(d) < 0.5 * feed.groove_arc) fed_[i] = 1, ++cells;
    }
    if (cells == 0)
      throw InputError("Reynolds film: the axial groove at " + deg(a) + " deg, " +
                       deg(feed.groove_arc) + " deg wide, is narrower than a cell of the grid (" +
                       deg(dphi) + " deg): raise grid_phi");
  }
  if (std::count(fed_.begin(), fed_.end(), 1) == n)
    throw InputError("Reynolds film: the axial grooves cover the whole circumference");
  const int nz = grid_.n_axial;
  held_.assign(static_cast<std::size_t>(n) * nz, 0);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < nz; ++j) held_[i * nz + j] = fed_[i];
  for (double a : feed.hole_angles) {
    if (!(feed.hole_diameter > 0.0 && feed.hole_diameter < B_ - feed.groove_width))
      throw InputError("Reynolds film: an oil hole " + format_number(feed.hole_diameter) +
                       " m across must lie between 0 and the bearing width " + format_number(B_) +
                       " m");
    int cells = 0;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < nz; ++j) {  // from the cell centre to the hole's, in metres
        const double s = R_ * std::remainder((i + 0.5) * dphi - a, 2.0 * M_PI);
        const double x = (nz - j - 0.5) * dxi_ * B_;  // from the mid-plane
        if (s * s + x * x < 0.25 * feed.hole_diameter * feed.hole_diameter)
          held_[i * nz + j] = 1, ++cells;
      }
    if (cells == 0)
      throw InputError("Reynolds film: the oil hole at " + deg(a) + " deg, " +
                       format_number(feed.hole_diameter) +
                       " m across, holds no cell centre of the grid (cells of " +
                       format_number(R_ * dphi) + " x " + format_number(dxi_ * B_) +
                       " m): raise grid_phi and grid_axial");
  }
  const bool held_any = std::count(held_.begin(), held_.end(), 1) > 0;
  fed_any_ = inner_feed_ || held_any;
  if (grid_.mass_conserving && !held_any && !(inner_feed_ && q_supply_ > 0.0))
    throw InputError(
        "Reynolds film: mass-conserving cavitation needs a feed that brings oil into the film "
        "(axial grooves or oil holes, or a circumferential groove with a supply pressure above "
        "0): without one the side leakage empties it");
  face_scale_.assign(n, 1.0);
  for (int i = 0; i < n; ++i)
    if (fed_[i] != fed_[(i + n - 1) % n]) face_scale_[i] = 2.0;  // half a cell to the edge
}

ReynoldsSolution ReynoldsFilm::solve(const V2& e, const V2& W, bool derivs) const {
  if (grid_.mass_conserving)  // its Couette and squeeze parts do not combine into W
    throw InputError("Reynolds film: the mass-conserving film is solved by solve_mass_conserving");
  const int np = grid_.n_phi, nz = grid_.n_axial, n = np * nz;
  const double dphi = 2.0 * M_PI / np, dxi = dxi_;
  const double rb2 = (R_ / B_) * (R_ / B_);
  // Coefficients: around, face i (angle i dphi) between cells i-1 and i; across,
  // between neighbouring axial cells of ring i; at the end x = 0 (half a cell away).
  std::vector<double> Hc(np), Hf(np), aphi(np), az(np);
  for (int i = 0; i < np; ++i) {
    Hc[i] = 1.0 - (e.x() * cos_c_[i] + e.y() * sin_c_[i]) / c_;
    Hf[i] = 1.0 - (e.x() * cos_f_[i] + e.y() * sin_f_[i]) / c_;
    aphi[i] = face_scale_[i] * Hf[i] * Hf[i] * Hf[i] / (dphi * dphi);
    az[i] = rb2 * Hc[i] * Hc[i] * Hc[i] / (dxi * dxi);
  }
  auto idx = [nz](int i, int j) { return i * nz + j; };
  // A q for the full grid, with coefficient arrays ap (faces around) and ac (across)
  auto apply = [&](const std::vector<double>& ap, const std::vector<double>& ac,
                   const Eigen::VectorXd& q) {
    Eigen::VectorXd r = Eigen::VectorXd::Zero(n);
    for (int i = 0; i < np; ++i) {
      const int in = (i + 1) % np;  // face i+1 between cells i and in
      for (int j = 0; j < nz; ++j) {
        const double d = ap[in] * (q[idx(i, j)] - q[idx(in, j)]);
        r[idx(i, j)] += d;
        r[idx(in, j)] -= d;
        if (j + 1 < nz) {
          const double dz = ac[i] * (q[idx(i, j)] - q[idx(i, j + 1)]);
          r[idx(i, j)] += dz;
          r[idx(i, j + 1)] -= dz;
        }
      }
      r[idx(i, 0)] += 2.0 * ac[i] * q[idx(i, 0)];  // the end, p = 0
      if (inner_feed_)                             // the land's inner end, at the groove's pressure
        r[idx(i, nz - 1)] += 2.0 * ac[i] * (q[idx(i, nz - 1)] - q_supply_);
    }
    return r;
  };
  Eigen::VectorXd g(n);
  for (int i = 0; i < np; ++i)
    for (int j = 0; j < nz; ++j) g[idx(i, j)] = W.x() * cos_c_[i] + W.y() * sin_c_[i];
  // The grooves' pressure: q_fix on the axial grooves' cells (0 elsewhere); the
  // system on the other cells has the right side g - A q_fix (the circumferential
  // groove's part inside apply)
  Eigen::VectorXd q_fix;
  if (fed_any_) {
    q_fix = Eigen::VectorXd::Zero(n);
    for (int k = 0; k < n; ++k)
      if (held_[k]) q_fix[k] = q_supply_;
  }
  const Eigen::VectorXd rhs = fed_any_ ? Eigen::VectorXd(g - apply(aphi, az, q_fix)) : g;

  // Active set: pressurized cells get the equation, the others q = 0. The
  // first set is the pi-film's (g > 0). (A start from the last call's final
  // set took more sets on the engine, 3.9 against 3.3 per solve: consecutive
  // calls come from the other axial station and from the corrector's trials.)
  std::vector<char> on(n);
  for (int k = 0; k < n; ++k) on[k] = !held_[k] && (!grid_.cavitation || rhs[k] > 0.0);
  // W = 0 (a journal at rest in its film): no pressure, and f, of degree one in
  // W, has a kink there; the set and the derivatives are the one-sided ones for
  // W along e (along x at the centre), as the table's (film_table.h)
  const bool at_rest = grid_.cavitation && W.squaredNorm() == 0.0 && q_supply_ == 0.0;
  if (at_rest) {
    const double en = e.norm();
    const V2 dir = en > 0.0 ? V2(e / en) : V2(1.0, 0.0);
    for (int i = 0; i < np; ++i)
      for (int j = 0; j < nz; ++j) g[idx(i, j)] = dir.x() * cos_c_[i] + dir.y() * sin_c_[i];
    for (int k = 0; k < n; ++k) on[k] = !held_[k] && g[k] > 0.0;
  }
  Eigen::VectorXd q = Eigen::VectorXd::Zero(n);
  FilmSystem sys(np, nz, aphi, az, inner_feed_);
  ReynoldsSolution s;
  for (int it = 0;; ++it) {
    if (it > 100)
      throw RunError("Reynolds film: the cavitation boundary did not settle in 100 active sets");
    ++s.active_sets;
    sys.factor(on);
    q = sys.solve(at_rest ? g : rhs);
    if (fed_any_) q += q_fix;
    if (!grid_.cavitation) break;
    const Eigen::VectorXd lambda = apply(aphi, az, q) - g;
    bool changed = false;
    for (int k = 0; k < n; ++k) {
      if (held_[k]) continue;
      const char now = on[k] ? (q[k] >= 0.0) : !(lambda[k] > 0.0);
      changed |= now != on[k];
      on[k] = now;
    }
    if (!changed) break;
  }
  if (at_rest) q.setZero();  // the set was found for W along e; the film itself is empty
  // Cells cut from the set with q < 0 in the last solve are zero.
  const double kp = 12.0 * eta_ * R_ * R_ / (c_ * c_ * c_);
  const double kf = -2.0 * R_ * B_ * dphi * dxi * kp;  // force per unit q u (both lands)
  for (int i = 0; i < np; ++i)
    for (int j = 0; j < nz; ++j) {
      // (without cavitation the film's negative pressures count too)
      const double p = kp * q[idx(i, j)];
      s.f += kf * q[idx(i, j)] * V2(cos_c_[i], sin_c_[i]);
      if (p > 0.0) ++s.pressurized;
      if (p > s.p_max) s.p_max = p, s.p_max_angle = (i + 0.5) * dphi;
    }
  if (s.p_max_angle > M_PI) s.p_max_angle -= 2.0 * M_PI;
  for (int i = 0; i < np; ++i) {
    const double h = c_ * Hc[i];
    s.side_flow +=
        2.0 * h * h * h / (12.0 * eta_) * kp * q[idx(i, 0)] / (0.5 * B_ * dxi) * R_ * dphi;
  }
  s.pressurized *= 2;  // both halves
  if (!derivs || (s.pressurized == 0 && !at_rest)) return s;
  // With the final set: q = A^-1 g on it, linear in W; d/de through the H^3 coefficients.
  auto force_of = [&](const Eigen::VectorXd& x) {
    V2 f = V2::Zero();
    for (int i = 0; i < np; ++i)
      for (int j = 0; j < nz; ++j) f += kf * x[idx(i, j)] * V2(cos_c_[i], sin_c_[i]);
    return f;
  };
  for (int c = 0; c < 2; ++c) {
    Eigen::VectorXd gu(n);
    for (int i = 0; i < np; ++i)
      for (int j = 0; j < nz; ++j) gu[idx(i, j)] = c == 0 ? cos_c_[i] : sin_c_[i];
    s.df_dW.col(c) = force_of(sys.solve(gu));
    // d(A q)/d e_c at fixed q: the coefficients' 3 H^2 dH/de_c, dH/de_c = -u_c / c
    std::vector<double> dap(np), daz(np);
    for (int i = 0; i < np; ++i) {
      const double uf = c == 0 ? cos_f_[i] : sin_f_[i], uc = c == 0 ? cos_c_[i] : sin_c_[i];
      dap[i] = -3.0 * face_scale_[i] * Hf[i] * Hf[i] * uf / (c_ * dphi * dphi);
      daz[i] = -3.0 * rb2 * Hc[i] * Hc[i] * uc / (c_ * dxi * dxi);
    }
    s.df_de.col(c) = force_of(sys.solve(-apply(dap, daz, q)));
  }
  return s;
}

}  // namespace evas
