// The Reynolds film of a journal bearing of finite width: Reynolds' equation on
// a grid over the whole film (circumference x width), with the Swift-Stieber
// (Reynolds) cavitation condition, p >= 0 and no flow across the film's
// rupture boundary, as Raimondi & Boyd solved it (A. A. Raimondi, J. Boyd, "A
// solution for the finite journal bearing and its application to analysis and
// design", ASLE Transactions 1 (1958) 159-209), or without cavitation
// (Sommerfeld's full film, negative pressures kept). Derivation, grid and
// solver: docs/elements-journal-bearing.md, "Film models".
//
// Bearing-frame components as in elements/journal_bearing.h: e the journal
// centre's offset, W = ed - (om/2) J e, gap h(phi) = c - e . u(phi). Reynolds'
// equation
//   (1/R^2) d/dphi (h^3 dp/dphi) + d/dx (h^3 dp/dx) = -12 eta W . u(phi),
// p = 0 at both ends x = 0, B. With p = (12 eta R^2 / c^3) q and H = h / c,
// xi = x / B:
//   d/dphi (H^3 dq/dphi) + (R/B)^2 d/dxi (H^3 dq/dxi) = -W . u(phi)
// on cell-centred finite volumes, n_phi cells around, n_axial cells on the
// half width (an aligned journal's film is symmetric about the mid-plane). Feed
// (ReynoldsFeed): q fixed at the supply pressure in the axial grooves and oil
// holes and at the inner end of each land of a circumferentially grooved bearing.
// Swift-Stieber: the discrete complementarity problem q >= 0, A q - g >= 0,
// q (A q - g) = 0, solved by the primal-dual active-set method (Hintermueller,
// Ito & Kunisch, SIAM J. Optim. 13 (2003) 865-888), exact in a finite number of
// sets for this M-matrix; each set one sparse Cholesky factorization.
#pragma once

#include <Eigen/Dense>
#include <vector>

namespace evas {

/// How oil reaches the film: axial grooves (through the whole width, at fixed
/// angles of the bearing), oil holes (round, at the mid-plane) and a
/// circumferential groove at the mid-plane (two lands), at the supply pressure.
/// An oil hole is the cells whose centres lie inside it, held at the supply
/// pressure at their centres. A groove's pressure holds at its edges:
/// an axial groove is the whole cells whose centres lie within its arc (its
/// edges on the cells' faces), the circumferential groove the inner end of
/// each land.
struct ReynoldsFeed {
  std::vector<double> groove_angles;  ///< axial grooves' centres, bearing angle [rad]
  double groove_arc = 0.0;            ///< arc of each axial groove [rad]
  double groove_width = 0.0;          ///< circumferential groove's width [m] (0: none)
  std::vector<double> hole_angles;    ///< oil holes' centres at the mid-plane, bearing angle [rad]
  double hole_diameter = 0.0;         ///< diameter of each oil hole [m]
  double supply_pressure = 0.0;       ///< pressure in the grooves [Pa], >= 0
};

struct ReynoldsGrid {
  int n_phi = 72;          ///< cells around the circumference
  int n_axial = 8;         ///< cells on the half width (on one land with a groove)
  bool cavitation = true;  ///< Swift-Stieber (true) or the full Sommerfeld film
  /// Mass-conserving cavitation (Elrod-Adams, film_mass_conserving.cpp) in place
  /// of Swift-Stieber's: solve_mass_conserving only; needs a feed
  bool mass_conserving = false;
  ReynoldsFeed feed;  ///< grooves and supply pressure (none by default)
};

/// One solve of the film: force on the journal and what `evas bearing` reports.
struct ReynoldsSolution {
  Eigen::Vector2d f = Eigen::Vector2d::Zero();      ///< force on the journal [N]
  Eigen::Matrix2d df_dW = Eigen::Matrix2d::Zero();  ///< d f / d W [N s/m]
  Eigen::Matrix2d df_de = Eigen::Matrix2d::Zero();  ///< d f / d e at fixed W [N/m]
  double p_max = 0.0;                               ///< largest cell pressure [Pa]
  double p_max_angle = 0.0;                         ///< its bearing angle phi [rad]
  double side_flow = 0.0;                           ///< flow out of both ends [m^3/s]
  double feed_flow = 0.0;  ///< mass-conserving: flow out of the grooves into the film [m^3/s]
  double theta_min = 1.0;  ///< mass-conserving: smallest film fraction
  Eigen::Vector2d df_dom = Eigen::Vector2d::Zero();  ///< mass-conserving: d f / d om
  int active_sets = 0;                               ///< active-set iterations taken
  int pressurized = 0;                               ///< cells with p > 0
};

/// Reynolds film of radius R, width B, radial clearance c, viscosity eta.
class ReynoldsFilm {
 public:
  ReynoldsFilm(double radius, double width, double clearance, double viscosity,
               const ReynoldsGrid& grid);
  /// The film for eccentricity e and W (bearing components); derivatives when
  /// `derivs`. The caller checks |e| < c.
  ReynoldsSolution solve(const Eigen::Vector2d& e, const Eigen::Vector2d& W, bool derivs) const;
  /// Mass-conserving film (grid.mass_conserving) of a journal at e, moving at
  /// ed, spinning at om relative to the bearing, its film fraction in balance
  /// (quasi-steady; film_mass_conserving.cpp). With `derivs`: df_de at fixed ed
  /// and om, df_dW = d f / d ed, df_dom.
  ReynoldsSolution solve_mass_conserving(const Eigen::Vector2d& e, const Eigen::Vector2d& ed,
                                         double om, bool derivs) const;
  const ReynoldsGrid& grid() const { return grid_; }

 private:
  struct McField {
    Eigen::VectorXd q, theta;  ///< per cell
    double side_flow = 0.0, feed_flow = 0.0;
    int active_sets = 0;
  };
  /// The mass-conserving field for the partition *full (cells with a full
  /// film; empty: the pi-film's), updated to the solution unless `fixed`.
  McField mc_field(const Eigen::Vector2d& e, const Eigen::Vector2d& ed, double om,
                   std::vector<char>* full, bool fixed) const;

  double R_, B_, c_, eta_;
  ReynoldsGrid grid_;
  std::vector<double> cos_c_, sin_c_;  ///< cell-centre angles
  std::vector<double> cos_f_, sin_f_;  ///< face angles (face i between cells i-1 and i)
  std::vector<char> fed_;              ///< ring i lies in an axial groove
  std::vector<char> held_;             ///< cell k at the supply pressure (a groove or a hole)
  std::vector<double> face_scale_;     ///< 2 on a face between a groove and the land, else 1
  double dxi_ = 0.0;                   ///< axial cell size / B
  double q_supply_ = 0.0;              ///< supply pressure in q's units
  bool inner_feed_ = false;            ///< a circumferential groove at the lands' inner ends
  bool fed_any_ = false;               ///< any groove (the right side takes their pressure)
};

}  // namespace evas
