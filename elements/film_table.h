// The Reynolds film tabulated once and interpolated at run time (film:
// reynolds, solve: table): the idea of the impedance and mobility methods of
// dynamically loaded journal bearings (J. F. Booker, "Dynamically loaded
// journal bearings: mobility method of solution", J. Basic Eng. 87 (1965)
// 537-546; D. W. Childs, H. Moes, H. van Leeuwen, "Journal bearing impedance
// descriptions for rotordynamic applications", J. Lubr. Technol. 99 (1977)
// 198-214). With the Swift-Stieber condition the film force is a function of
// e and W = ed - (om/2) J e only (elements/journal_bearing.h), of degree one
// in W and turning with e:
//   f(e, W) = |W| Q(theta) F(eps, psi),
// Q(theta) the rotation to the line of centres, psi the angle of W from it.
// F is tabulated over eps (nodes uniform in u = -ln(1 - eps), up to eps_top)
// and psi (uniform, periodic) from ReynoldsFilm solves, scaled by (1 - eps)^2,
// and interpolated by bicubic Catmull-Rom splines; the Jacobian is the
// interpolant's, exact for the force returned. Beyond eps_top the film is
// solved directly. Accuracy against direct solves: docs/elements-journal-bearing.md.
#pragma once

#include <memory>
#include <vector>

#include "elements/film_force.h"
#include "elements/film_reynolds.h"

namespace evas {

struct FilmTableSize {
  int n_eps = 48;         ///< intervals in u = -ln(1 - eps) from 0 to eps_top
  int n_psi = 72;         ///< nodes around (the direction of W from e)
  double eps_top = 0.99;  ///< largest tabulated eccentricity ratio
};

class FilmTable {
 public:
  /// Tabulates `film` (which must use the Swift-Stieber condition).
  FilmTable(std::shared_ptr<const ReynoldsFilm> film, double clearance, const FilmTableSize& size);
  /// f(e, W) and, with `derivs`, df/de (at fixed W) and df/dW: in `r`, f,
  /// df_de and df_ded (= df/dW); df_dom is left to the caller.
  FilmForce force(const Eigen::Vector2d& e, const Eigen::Vector2d& W, bool derivs) const;
  /// The peak pressure [Pa] and, in *angle, its bearing angle [rad] in (-pi, pi]:
  /// |W| P(eps, psi) with ln P and the angle from the line of centres (its
  /// cosine and sine) tabulated beside F and interpolated alike.
  double peak_pressure(const Eigen::Vector2d& e, const Eigen::Vector2d& W, double* angle) const;
  /// A table shared by every bearing of the same film and size (built once per process).
  static std::shared_ptr<const FilmTable> shared(std::shared_ptr<const ReynoldsFilm> film,
                                                 double radius, double width, double clearance,
                                                 double viscosity, const FilmTableSize& size);

 private:
  // F (2 components) scaled by (1 - eps)^2 at node (i, j), i over u, j over psi.
  double at(int c, int i, int j) const;

  std::shared_ptr<const ReynoldsFilm> film_;
  double c_;
  FilmTableSize size_;
  double du_, dpsi_;
  std::vector<double> h_[2];  ///< (n_eps + 1) x n_psi, i n_psi + j
  /// ln of the peak pressure per unit |W| and its angle's cosine and sine from
  /// the line of centres, at the same nodes
  std::vector<double> peak_[3];
  /// Interpolation cell of (eps, psi): the first node of each direction, and
  /// the four Catmull-Rom weights of each (and their derivatives)
  struct Cell {
    int i, j;
    double wu[4], dwu[4], wp[4], dwp[4];
  };
  Cell cell(double eps, double psi) const;
  /// Bicubic value of a table v over the nodes (linear ghost nodes in eps, periodic in psi)
  double interpolate(const std::vector<double>& v, const Cell& k) const;
};

}  // namespace evas
