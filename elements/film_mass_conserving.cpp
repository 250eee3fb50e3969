// Mass-conserving cavitation of the Reynolds film (Jakobsson-Floberg-Olsson):
// ReynoldsFilm::solve_mass_conserving, see film_reynolds.h and
// docs/elements-journal-bearing.md ("Mass-conserving cavitation").
//
// Elrod & Adams' p-theta form: in every cell either the film is full (theta = 1,
// p >= 0) or it has ruptured (p = 0, 0 <= theta < 1, theta the fraction of the
// gap the oil fills). One equation for both, the flow balance of the cell,
//   A q + (om c / 2) D(theta H) - theta (ed . u) = 0,
// A the pressure-flow operator of the Swift-Stieber film (film_reynolds.cpp),
// D the circumferential difference of the Couette flow theta H carried from the
// upstream cell (upwind), the squeeze term with the film fraction held (quasi-
// steady). The unknown of a cell is q where it is full, theta where it has
// ruptured: for a given partition a linear system (not symmetric: the Couette
// flow is one-way), and the partition is found by the semismooth Newton
// (active-set) iteration of the complementarity problem q >= 0, 1 - theta >= 0,
// q (1 - theta) = 0 (as in Woloszynski, Podsiadlo, Stachowiak, "Efficient
// solution to the cavitation problem in hydrodynamic lubrication", Tribology
// Letters 58 (2015) 18): a cell whose q turns negative ruptures, one whose
// theta exceeds 1 fills.
#include <Eigen/Sparse>
#include <algorithm>
#include <cmath>
#include <string>

#include "elements/film_reynolds.h"
#include "model/types.h"

namespace evas {

namespace {

using V2 = Eigen::Vector2d;

}  // namespace

ReynoldsFilm::McField ReynoldsFilm::mc_field(const V2& e, const V2& ed, double om,
                                             std::vector<char>* full, bool fixed) const {
  const int np = grid_.n_phi, nz = grid_.n_axial, n = np * nz;
  const double dphi = 2.0 * M_PI / np, dxi = dxi_;
  const double rb2 = (R_ / B_) * (R_ / B_);
  std::vector<double> Hc(np), Hf(np), aphi(np), az(np), sq(np);
  for (int i = 0; i < np; ++i) {
    Hc[i] = 1.0 - (e.x() * cos_c_[i] + e.y() * sin_c_[i]) / c_;
    Hf[i] = 1.0 - (e.x() * cos_f_[i] + e.y() * sin_f_[i]) / c_;
    aphi[i] = face_scale_[i] * Hf[i] * Hf[i] * Hf[i] / (dphi * dphi);
    az[i] = rb2 * Hc[i] * Hc[i] * Hc[i] / (dxi * dxi);
    sq[i] = ed.x() * cos_c_[i] + ed.y() * sin_c_[i];
  }
  const double s = 0.5 * om * c_ / dphi;  // Couette flow per unit theta H, over the cell
  std::vector<char>& on = *full;
  if (on.empty()) {  // first partition: the pi-film's full half (W . u > 0)
    on.assign(n, 0);
    for (int i = 0; i < np; ++i) {
      const double g =
          sq[i] - 0.5 * om * (-e.y() * cos_c_[i] + e.x() * sin_c_[i]);  // W . u at the centre
      for (int j = 0; j < nz; ++j) on[i * nz + j] = !held_[i * nz + j] && g > 0.0;
    }
  }
  McField out;
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  std::vector<Eigen::Triplet<double>> trip;
  Eigen::VectorXd rhs(n), x(n);
  for (int it = 0;; ++it) {
    if (it > 200)
      throw RunError(
          "Reynolds film (mass-conserving): the cavitation zone did not settle in 200 "
          "partitions");
    ++out.active_sets;
    trip.clear();
    rhs.setZero();
    for (int i = 0; i < np; ++i) {
      const int in = (i + 1) % np, ip = (i + np - 1) % np;
      for (int j = 0; j < nz; ++j) {
        const int k = i * nz + j;
        if (held_[k]) {  // a groove or a hole: q at the supply pressure, full
          trip.emplace_back(k, k, 1.0);
          rhs[k] = q_supply_;
          continue;
        }
        // pressure flow: sum over neighbours a (q_k - q_nb), ends at q = 0
        double diag = 0.0;
        auto nb = [&](int m, double a) {
          diag += a;
          if (held_[m])
            rhs[k] += a * q_supply_;
          else if (on[m])
            trip.emplace_back(k, m, -a);
        };
        nb(in * nz + j, aphi[in]);
        nb(ip * nz + j, aphi[i]);
        if (j + 1 < nz) nb(k + 1, az[i]);
        if (j > 0) nb(k - 1, az[i]);
        if (j == 0) diag += 2.0 * az[i];
        if (inner_feed_ && j + 1 == nz) diag += 2.0 * az[i], rhs[k] += 2.0 * az[i] * q_supply_;
        if (on[k]) trip.emplace_back(k, k, diag);
        // Couette flow s (theta H)_upwind out of the downstream face, in at the
        // upstream one; the squeeze term -theta (ed . u) of the cell
        auto theta = [&](int m, double a) {  // a theta_m on row k
          if (!held_[m] && !on[m])
            trip.emplace_back(k, m, a);
          else
            rhs[k] -= a;
        };
        if (s >= 0.0) {
          theta(k, s * Hf[in] - sq[i]);
          theta(ip * nz + j, -s * Hf[i]);
        } else {
          theta(in * nz + j, s * Hf[in]);
          theta(k, -s * Hf[i] - sq[i]);
        }
      }
    }
    Eigen::SparseMatrix<double> M(n, n);
    M.setFromTriplets(trip.begin(), trip.end());
    lu.compute(M);
    if (lu.info() != Eigen::Success)
      throw RunError(
          "Reynolds film (mass-conserving): the film's system is singular (no oil "
          "reaches the ruptured zone?)");
    x = lu.solve(rhs);
    if (fixed) break;
    bool changed = false;
    for (int k = 0; k < n; ++k) {
      if (held_[k]) continue;
      const char now = on[k] ? x[k] >= 0.0 : x[k] > 1.0;
      changed |= now != on[k];
      on[k] = now;
    }
    if (!changed) break;
  }
  out.q = Eigen::VectorXd::Zero(n);
  out.theta = Eigen::VectorXd::Ones(n);
  for (int k = 0; k < n; ++k) {
    if (held_[k])
      out.q[k] = q_supply_;
    else if (on[k])
      out.q[k] = std::max(x[k], 0.0);
    else
      out.theta[k] = std::min(x[k], 1.0);
  }
  // Flows [m^3/s], both halves: out of the ends, and out of the held cells (grooves,
  // holes) into the others and out of the ends, and in from a circumferential groove
  const double kq = R_ * R_ * R_ * dphi / B_;  // axial flow per unit H^3 dq/dxi
  const double kc = 2.0 * R_ * B_ * dxi;       // circumferential flow per unit (...) dphi
  auto around = [&](int i, int j) {            // flow across face i+1 towards +phi
    const int in = (i + 1) % np, up = s >= 0.0 ? i : in;
    return kc * (s * dphi * out.theta[up * nz + j] * Hf[in] -
                 aphi[in] * dphi * (out.q[in * nz + j] - out.q[i * nz + j]));
  };
  for (int i = 0; i < np; ++i) {
    const double h3 = Hc[i] * Hc[i] * Hc[i];
    const int in = (i + 1) % np;
    for (int j = 0; j < nz; ++j) {
      const int k = i * nz + j;
      if (j == 0) {  // the end
        out.side_flow += 2.0 * kq * h3 * out.q[k] / (0.5 * dxi);
        if (held_[k]) out.feed_flow += 2.0 * kq * h3 * out.q[k] / (0.5 * dxi);
      }
      if (inner_feed_ && j + 1 == nz)
        out.feed_flow += 2.0 * kq * h3 * (q_supply_ - out.q[k]) / (0.5 * dxi);
      if (held_[k] != held_[in * nz + j])  // face i+1 between a held cell and another
        out.feed_flow += held_[k] ? around(i, j) : -around(i, j);
      if (j + 1 < nz && held_[k] != held_[k + 1]) {  // towards the mid-plane
        const double f = 2.0 * kq * h3 * (out.q[k] - out.q[k + 1]) / dxi;
        out.feed_flow += held_[k] ? f : -f;
      }
    }
  }
  return out;
}

ReynoldsSolution ReynoldsFilm::solve_mass_conserving(const V2& e, const V2& ed, double om,
                                                     bool derivs) const {
  if (!grid_.mass_conserving)
    throw InputError("Reynolds film: solve_mass_conserving on a film without mass conservation");
  const int np = grid_.n_phi, nz = grid_.n_axial;
  const double dphi = 2.0 * M_PI / np;
  const double kp = 12.0 * eta_ * R_ * R_ / (c_ * c_ * c_);
  const double kf = -2.0 * R_ * B_ * dphi * dxi_ * kp;  // force per unit q u (both lands)
  std::vector<char> full;
  const McField m = mc_field(e, ed, om, &full, false);
  ReynoldsSolution sol;
  auto force_of = [&](const Eigen::VectorXd& q) {
    V2 f = V2::Zero();
    for (int i = 0; i < np; ++i)
      for (int j = 0; j < nz; ++j) f += kf * q[i * nz + j] * V2(cos_c_[i], sin_c_[i]);
    return f;
  };
  sol.f = force_of(m.q);
  sol.active_sets = m.active_sets;
  sol.side_flow = m.side_flow;
  sol.feed_flow = m.feed_flow;
  sol.theta_min = m.theta.minCoeff();
  for (int i = 0; i < np; ++i)
    for (int j = 0; j < nz; ++j) {
      const double p = kp * m.q[i * nz + j];
      if (p > 0.0) sol.pressurized += 2;
      if (p > sol.p_max) sol.p_max = p, sol.p_max_angle = (i + 0.5) * dphi;
    }
  if (sol.p_max_angle > M_PI) sol.p_max_angle -= 2.0 * M_PI;
  if (sol.theta_min < -1e-9)
    throw RunError("Reynolds film (mass-conserving): the ruptured film runs dry (film fraction " +
                   format_number(sol.theta_min) + "): the feed supplies too little oil");
  if (!derivs) return sol;
  // Derivatives at the final partition by central differences (the system is
  // smooth in e, ed and om while the partition holds): df_de (ed, om held),
  // df_dW = df/d(ed), df_dom.
  auto at = [&](const V2& e1, const V2& ed1, double om1) {
    std::vector<char> set = full;
    return force_of(mc_field(e1, ed1, om1, &set, true).q);
  };
  const double he = 1e-6 * c_, hd = 1e-6 * (std::abs(om) * c_ + ed.norm()),
               ho = 1e-6 * std::max(std::abs(om), 1.0);
  for (int c = 0; c < 2; ++c) {
    const V2 d = V2::Unit(c);
    sol.df_de.col(c) = (at(e + he * d, ed, om) - at(e - he * d, ed, om)) / (2.0 * he);
    sol.df_dW.col(c) = (at(e, ed + hd * d, om) - at(e, ed - hd * d, om)) / (2.0 * hd);
  }
  sol.df_dom = (at(e, ed, om + ho) - at(e, ed, om - ho)) / (2.0 * ho);
  return sol;
}

}  // namespace evas
