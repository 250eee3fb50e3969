// The tabulated Reynolds film: see film_table.h.
#include "elements/film_table.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include "model/types.h"

namespace evas {

namespace {

using V2 = Eigen::Vector2d;
using M2 = Eigen::Matrix2d;

// Catmull-Rom weights of the nodes -1, 0, 1, 2 at t in [0, 1], and their t-derivatives.
void catmull_rom(double t, double w[4], double dw[4]) {
  const double t2 = t * t, t3 = t2 * t;
  w[0] = 0.5 * (-t3 + 2.0 * t2 - t);
  w[1] = 0.5 * (3.0 * t3 - 5.0 * t2 + 2.0);
  w[2] = 0.5 * (-3.0 * t3 + 4.0 * t2 + t);
  w[3] = 0.5 * (t3 - t2);
  dw[0] = 0.5 * (-3.0 * t2 + 4.0 * t - 1.0);
  dw[1] = 0.5 * (9.0 * t2 - 10.0 * t);
  dw[2] = 0.5 * (-9.0 * t2 + 8.0 * t + 1.0);
  dw[3] = 0.5 * (3.0 * t2 - 2.0 * t);
}

}  // namespace

FilmTable::FilmTable(std::shared_ptr<const ReynoldsFilm> film, double clearance,
                     const FilmTableSize& size)
    : film_(std::move(film)), c_(clearance), size_(size) {
  if (!film_->grid().cavitation)
    throw InputError("a film table needs the Swift-Stieber condition (cavitation: swift-stieber)");
  if (size_.n_eps < 4 || size_.n_psi < 8 || !(size_.eps_top > 0.0 && size_.eps_top < 1.0))
    throw InputError(
        "film table: at least 4 eccentricity intervals, 8 directions and a top "
        "eccentricity ratio in (0, 1)");
  du_ = -std::log(1.0 - size_.eps_top) / size_.n_eps;
  dpsi_ = 2.0 * M_PI / size_.n_psi;
  for (auto& h : h_) h.resize(static_cast<std::size_t>(size_.n_eps + 1) * size_.n_psi);
  for (auto& h : peak_) h.resize(h_[0].size());
  for (int i = 0; i <= size_.n_eps; ++i) {
    const double one_m = std::exp(-i * du_), eps = 1.0 - one_m;
    for (int j = 0; j < size_.n_psi; ++j) {
      const V2 W(std::cos(j * dpsi_), std::sin(j * dpsi_));
      const ReynoldsSolution sol = film_->solve(V2(eps * c_, 0.0), W, false);
      const std::size_t k = static_cast<std::size_t>(i) * size_.n_psi + j;
      for (int c = 0; c < 2; ++c) h_[c][k] = sol.f[c] * one_m * one_m;
      // a unit W always pressurizes some of the film (where W . u > 0)
      peak_[0][k] = std::log(std::max(sol.p_max, 1e-300));
      peak_[1][k] = std::cos(sol.p_max_angle);
      peak_[2][k] = std::sin(sol.p_max_angle);
    }
  }
}

double FilmTable::at(int c, int i, int j) const {
  const int n = size_.n_psi;
  j = ((j % n) + n) % n;
  auto node = [&](int ii) { return h_[c][static_cast<std::size_t>(ii) * n + j]; };
  if (i < 0) return 2.0 * node(0) - node(1);  // linear ghost nodes at both ends
  if (i > size_.n_eps) return 2.0 * node(size_.n_eps) - node(size_.n_eps - 1);
  return node(i);
}

FilmTable::Cell FilmTable::cell(double eps, double psi) const {
  Cell k;
  const double s = -std::log(1.0 - eps) / du_;
  k.i = std::min(static_cast<int>(std::floor(s)), size_.n_eps - 1);
  const double p = psi / dpsi_;
  k.j = static_cast<int>(std::floor(p));
  catmull_rom(s - k.i, k.wu, k.dwu);
  catmull_rom(p - k.j, k.wp, k.dwp);
  return k;
}

double FilmTable::interpolate(const std::vector<double>& v, const Cell& k) const {
  const int n = size_.n_psi;
  auto node = [&](int ii, int jj) {
    jj = ((jj % n) + n) % n;
    auto at_i = [&](int i3) { return v[static_cast<std::size_t>(i3) * n + jj]; };
    if (ii < 0) return 2.0 * at_i(0) - at_i(1);
    if (ii > size_.n_eps) return 2.0 * at_i(size_.n_eps) - at_i(size_.n_eps - 1);
    return at_i(ii);
  };
  double x = 0.0;
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) x += k.wu[a] * k.wp[b] * node(k.i - 1 + a, k.j - 1 + b);
  return x;
}

double FilmTable::peak_pressure(const V2& e_in, const V2& W, double* angle) const {
  const V2 e = e_in.norm() < 1e-12 * c_ ? V2(1e-12 * c_, 0.0) : e_in;
  const double en = e.norm(), eps = en / c_;
  if (angle) *angle = 0.0;
  if (eps > size_.eps_top) {  // beyond the table: the film itself
    const ReynoldsSolution s = film_->solve(e_in, W, false);
    if (angle) *angle = s.p_max_angle;
    return s.p_max;
  }
  const double wn = W.norm();
  if (wn == 0.0) return 0.0;  // a journal at rest in its film
  const double theta = std::atan2(e.y(), e.x());
  double psi = std::atan2(W.y(), W.x()) - theta;
  psi -= 2.0 * M_PI * std::floor(psi / (2.0 * M_PI));
  const Cell k = cell(eps, psi);
  if (angle)
    *angle = std::remainder(theta + std::atan2(interpolate(peak_[2], k), interpolate(peak_[1], k)),
                            2.0 * M_PI);
  return wn * std::exp(interpolate(peak_[0], k));
}

FilmForce FilmTable::force(const V2& e_in, const V2& W, bool derivs) const {
  // at the centre the line of centres is x (the film there does not depend on it)
  const V2 e = e_in.norm() < 1e-12 * c_ ? V2(1e-12 * c_, 0.0) : e_in;
  const double en = e.norm(), eps = en / c_;
  FilmForce r;
  if (eps > size_.eps_top) {  // beyond the table: the film itself
    const ReynoldsSolution s = film_->solve(e_in, W, derivs);
    r.f = s.f;
    r.df_de = s.df_de;
    r.df_ded = s.df_dW;
    return r;
  }
  const V2 n = e / en, t(-n.y(), n.x());
  M2 Q;
  Q.col(0) = n;
  Q.col(1) = t;
  const V2 wl(W.dot(n), W.dot(t));
  const double wn = wl.norm();
  double psi = wn > 0.0 ? std::atan2(wl.y(), wl.x()) : 0.0;
  if (psi < 0.0) psi += 2.0 * M_PI;
  // interpolation cell and weights
  const double one_m = 1.0 - eps, u = -std::log(one_m);
  const double s = u / du_;
  int i = static_cast<int>(std::floor(s));
  if (i > size_.n_eps - 1) i = size_.n_eps - 1;
  const double tu = s - i;
  const double p = psi / dpsi_;
  const int j = static_cast<int>(std::floor(p));
  const double tp = p - j;
  double wu[4], dwu[4], wp[4], dwp[4];
  catmull_rom(tu, wu, dwu);
  catmull_rom(tp, wp, dwp);
  V2 H = V2::Zero(), Hu = V2::Zero(), Hp = V2::Zero();
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) {
      const V2 h(at(0, i - 1 + a, j - 1 + b), at(1, i - 1 + a, j - 1 + b));
      H += wu[a] * wp[b] * h;
      if (derivs) {
        Hu += dwu[a] * wp[b] * h;
        Hp += wu[a] * dwp[b] * h;
      }
    }
  const double sc = 1.0 / (one_m * one_m);
  const V2 F = sc * H;  // the unit-W force in the line-of-centres frame
  const V2 fl = wn * F;
  r.f = Q * fl;
  if (!derivs) return r;
  // d F / d eps = (H_u / du + 2 H) / (1 - eps)^3 (u = -ln(1 - eps)); d F / d psi = H_psi / (...)^2
  const V2 Fe = (Hu / du_ + 2.0 * H) * (sc / one_m);
  const V2 Fp = Hp * (sc / dpsi_);
  const V2 wh(std::cos(psi), std::sin(psi)), wt(-wh.y(), wh.x());
  // f = |W| Q F(eps, psi): in W through |W| and psi; in e through eps and the
  // turning of Q and of psi (psi = angle of W - theta)
  const M2 dfl_dwl = F * wh.transpose() + Fp * wt.transpose();
  r.df_ded = Q * dfl_dwl * Q.transpose();
  M2 J;
  J << 0.0, -1.0, 1.0, 0.0;
  const V2 df_dtheta = J * r.f - wn * (Q * Fp);
  r.df_de = (wn / c_) * (Q * Fe) * n.transpose() + df_dtheta * t.transpose() / en;
  return r;
}

std::shared_ptr<const FilmTable> FilmTable::shared(std::shared_ptr<const ReynoldsFilm> film,
                                                   double radius, double width, double clearance,
                                                   double viscosity, const FilmTableSize& size) {
  using Key = std::tuple<double, double, double, double, int, int, int, int, double>;
  static std::map<Key, std::shared_ptr<const FilmTable>> tables;  // (evas runs one thread)
  const ReynoldsGrid& g = film->grid();
  const Key k{radius,    width,      clearance,  viscosity,   g.n_phi,
              g.n_axial, size.n_eps, size.n_psi, size.eps_top};
  auto it = tables.find(k);
  if (it != tables.end()) return it->second;
  auto t = std::make_shared<const FilmTable>(std::move(film), clearance, size);
  tables.emplace(k, t);
  return t;
}

}  // namespace evas
