// Butenschoen's closed-form finite-width film: see film_finite.h.
#include "elements/film_finite.h"

#include <cmath>
#include <unsupported/Eigen/AutoDiff>

namespace evas {

namespace {

using AD = Eigen::AutoDiffScalar<Eigen::Matrix<double, 5, 1>>;

// The fit's polynomials in b/d (film_finite.h): rotation a1, a2; angle a3..a7;
// squeeze a8, a9.
struct Coefficients {
  double a[10];
};
Coefficients coefficients(double bd) {
  const double x = bd, x2 = x * x, x3 = x2 * x, x4 = x3 * x;
  Coefficients k{};
  k.a[1] = 1.1642 - 1.9456 * x + 7.1161 * x2 - 10.1073 * x3 + 5.0141 * x4;
  k.a[2] = -1.000026 - 0.023634 * x - 0.4215 * x2 - 0.038817 * x3 - 0.090551 * x4;
  k.a[3] = 1.152624 - 0.104565 * x;
  k.a[4] = -2.5905 + 0.798745 * x;
  k.a[5] = 8.73393 - 2.3291 * x;
  k.a[6] = -13.3414 + 3.424337 * x;
  k.a[7] = 6.6294 - 1.591732 * x;
  k.a[8] = 0.70038 + 3.2415 * x - 12.2486 * x2 + 18.895 * x3 - 9.3561 * x4;
  k.a[9] = -0.999935 + 0.0157434 * x - 0.74224 * x2 + 0.42278 * x3 - 0.368928 * x4;
  return k;
}

// So_D / eps and beta for eccentricity ratio eps (T: double or AD).
template <class T>
void rotation(const Coefficients& k, double bd, const T& eps, T& so_d_per_eps, T& beta) {
  using std::atan2;
  using std::sqrt;
  const T s2 = 1.0 - eps * eps;
  so_d_per_eps = bd * bd * sqrt(M_PI * M_PI * s2 + 16.0 * eps * eps) / (2.0 * s2 * s2) * k.a[1] *
                 (eps - 1.0) / (k.a[2] + eps);
  const T poly = k.a[3] + eps * (k.a[4] + eps * (k.a[5] + eps * (k.a[6] + eps * k.a[7])));
  beta = atan2(M_PI * sqrt(s2), 2.0 * eps) * poly;
}

// So_V for the signed eccentricity ratio es (sign of the radial speed).
template <class T>
T squeeze(const Coefficients& k, double bd, const T& es) {
  using std::acos;
  using std::pow;
  using std::sqrt;
  const T s2 = 1.0 - es * es;
  return 4.0 * bd * bd / (s2 * s2 * sqrt(s2)) *
         ((0.5 * M_PI - 0.5 * acos(es)) * (1.0 + 2.0 * es * es) + 1.5 * es * sqrt(s2)) * k.a[8] *
         (1.0 - es) / (-k.a[9] - es);
}

}  // namespace

FilmForce finite_film(double R, double B, double c, double eta, const Eigen::Vector2d& e,
                      const Eigen::Vector2d& ed, double om, bool derivs) {
  const double bd = B / (2.0 * R), psi = c / R;
  const Coefficients k = coefficients(bd);
  const double scale = B * 2.0 * R * eta / (psi * psi);  // F = So * scale * omega
  // inputs: e (0, 1), ed (2, 3), om (4); at the centre the line of centres is x
  const bool centred = e.norm() < 1e-12 * c;
  AD ex(centred ? 1e-12 * c : e.x(), 5, 0), ey(centred ? 0.0 : e.y(), 5, 1);
  AD edx(ed.x(), 5, 2), edy(ed.y(), 5, 3), w(om, 5, 4);
  const AD en = sqrt(ex * ex + ey * ey);
  const AD nx = ex / en, ny = ey / en;  // unit vector along the line of centres
  const AD eps = en / c;
  // eps times the effective speed om - 2 d(delta)/dt, d(delta)/dt = (e x ed) / |e|^2
  const AD eps_wres = eps * w - 2.0 * (nx * edy - ny * edx) / c;
  const double sgn = eps_wres.value() < 0.0 ? -1.0 : 1.0;
  AD per, beta;
  rotation(k, bd, eps, per, beta);
  const AD fd = per * (sgn * eps_wres) * scale;  // |F_D|
  // F_D acts on the bearing at delta - sgn beta, on the journal opposite
  const AD cb = cos(beta), sb = sgn * sin(beta);
  const AD fdx = -fd * (cb * nx + sb * ny), fdy = -fd * (cb * ny - sb * nx);
  // squeeze: eps_dot = n . ed / c, So_V with the sign of eps_dot on eps
  const AD epsd = (nx * edx + ny * edy) / c;
  const AD es = epsd.value() < 0.0 ? AD(-eps) : eps;
  const AD fv = squeeze(k, bd, es) * scale * epsd;
  const AD fx = fdx - fv * nx, fy = fdy - fv * ny;
  FilmForce r;
  r.f = Eigen::Vector2d(fx.value(), fy.value());
  if (derivs) {
    for (int j = 0; j < 2; ++j) {
      r.df_de(0, j) = fx.derivatives()[j];
      r.df_de(1, j) = fy.derivatives()[j];
      r.df_ded(0, j) = fx.derivatives()[2 + j];
      r.df_ded(1, j) = fy.derivatives()[2 + j];
    }
    r.df_dom = Eigen::Vector2d(fx.derivatives()[4], fy.derivatives()[4]);
  }
  return r;
}

}  // namespace evas
