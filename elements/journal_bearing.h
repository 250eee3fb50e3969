// Hydrodynamic journal bearing, short-bearing (Ocvirk) theory with the
// pi-film (half-Sommerfeld) condition (the default film; `film: finite |
// reynolds` choose elements/film_finite.h or film_reynolds.h and film_table.h,
// docs/elements-journal-bearing.md "Film models"): paper section 3.2, Eq. 3, Figs. 5-6;
// formulation.md section 5; references.md section 1. Full derivation and the
// sign conventions: docs/elements-journal-bearing.md.
//
// Markers: 0 = bearing (column 2 of its axes R0 is the bearing axis a,
// columns 0/1 span the bearing plane, P = [x y]); 1 = journal centre.
//
// Kinematics (bearing plane, bearing-frame components):
//   e   = P^T d,            d = p1 - p0                       (eccentricity vector)
//   ed  = P^T (dd - w0 x d),  dd = v1 - v0                    (its rate seen by the bearing)
//   om  = (w1 - w0) . a                                       (relative spin)
// Reynolds' equation, short bearing, bearing angle phi, u(phi) = (cos, sin),
// t(phi) = (-sin, cos), film h = c - e . u, surface speed sum om R:
//   d/dx (h^3 dp/dx) = 6 eta om dh/dphi + 12 eta dh/dt = -12 eta g(phi),
//   g(phi) = W . u(phi),   W = ed - (om/2) J e,   J = rotation by +90 deg,
//   p(x, phi) = 6 eta x (B - x) g / h^3           (p = 0 at x = 0, B).
// With delta measured from the line of maximum film in the direction of
// rotation, h = c + e cos(delta) and g = (om/2 - gd) e sin(delta) - ed cos(delta):
// this is Eq. 3 of the paper with the opposite overall sign (Eq. 3 as printed,
// with x (x - B) <= 0, would give suction in the converging film).
// pi-film: p is kept where g > 0, the half circle |phi - atan2(Wy, Wx)| < pi/2.
// Force on the journal: F = -R int int p u dphi dx = -eta R B^3 int_{g>0} g u / h^3 dphi.
//
// Methods: "quadrature" (Gauss-Legendre with n_delta points on the positive
// half circle; the parabolic axial factor is integrated exactly) and "ocvirk"
// (the same integral in closed form via the Sommerfeld substitution; for
// ed = 0 it reduces to references.md s.1).
//
// halves = 2 (paper Fig. 6): two axial stations at s = +-B/(2 sqrt 5) from the
// journal marker, each with half the parabolic weight (the 2-point Gauss rule
// for the weight x (B - x)). An aligned journal gets exactly the full-width
// force; a journal tilted by theta = psi1 - psi0 (in-plane part) gets a moment.
//
// Extreme film: e >= c throws RunError (film closed). eps >= eps_max throws
// RunError unless contact_stiffness > 0; then an asperity contact force
//   F_c = -k_c (e - eps_max c)^n e/|e|      (n = contact_exponent)
// is added on the journal (continuous at the onset; C1 for n > 1).
#pragma once

#include <array>
#include <memory>
#include <string>

#include "elements/film_force.h"
#include "elements/film_reynolds.h"
#include "elements/film_table.h"
#include "elements/registry.h"
#include "model/element.h"

namespace evas {

/// The defaults below are the scene's defaults (the parameter table is bound to
/// these members, journal_bearing_element_type()); the first four are required.
struct JournalBearingParams {
  double radius = 0.0;      ///< journal radius R [m] (required)
  double width = 0.0;       ///< bearing width B [m] (required)
  double clearance = 0.0;   ///< radial clearance c [m] (required)
  double viscosity = 0.0;   ///< dynamic viscosity eta [Pa s] (required)
  bool closed_form = true;  ///< method: ocvirk (true) or quadrature
  int n_delta = 64;         ///< Gauss-Legendre points on the positive half circle
  int halves = 1;           ///< 1 or 2 axial stations
  double eps_max = 0.98;
  double contact_stiffness = 0.0;  ///< k_c [N/m^n]
  double contact_exponent = 1.5;   ///< n [-]
  double journal_speed = 0.0;      ///< added to the relative spin [rad/s]
  /// film model: "short" (the paper's), "finite" (Butenschoen's closed form),
  /// "reynolds" (Reynolds' equation on a grid)
  std::string film = "short";
  /// reynolds: "swift-stieber", "none" (the full Sommerfeld film) or
  /// "mass-conserving" (Elrod-Adams; evas bearing's static answer only)
  std::string cavitation = "swift-stieber";
  int grid_phi = 72;   ///< reynolds: cells around the circumference
  int grid_axial = 8;  ///< reynolds: cells on the half width
  bool table = false;  ///< reynolds: solve at each evaluation (false) or tabulate (true)
  /// reynolds: how oil reaches the film: "none", "axial-grooves" (feed_count
  /// grooves through the width, evenly spaced from feed_angle, each feed_arc
  /// wide), "oil-holes" (feed_count holes feed_diameter across at the mid-plane,
  /// evenly spaced from feed_angle) or "circumferential-groove" (feed_width
  /// wide at the mid-plane)
  std::string feed = "none";
  double feed_angle = 90.0;      ///< first axial groove's centre, bearing angle [deg]
  int feed_count = 2;            ///< axial grooves
  double feed_arc = 20.0;        ///< arc of each axial groove [deg]
  double feed_width = 0.0;       ///< circumferential groove's width [m]
  double feed_diameter = 0.0;    ///< oil holes' diameter [m]
  double supply_pressure = 0.0;  ///< pressure in the grooves [Pa]
};

/// The Reynolds film's grid and feed of a bearing's parameters.
ReynoldsGrid reynolds_grid(const JournalBearingParams& p);

class JournalBearing : public Element {
 public:
  JournalBearing(std::string name, std::vector<int> markers, const JournalBearingParams& p);
  std::string type() const override { return "journal-bearing"; }
  /// Two axial stations read the journal's tilt and load both markers with a moment.
  bool needs_rotation(std::size_t) const override { return p_.halves == 2; }
  void evaluate(double t, const MarkerMotion* m, MarkerLoad* loads) const override;
  void derivatives(double t, const MarkerMotion* m, Mat& D) const override;
  std::vector<Channel> channels() const override;
  void channel_values(double t, const MarkerMotion* m, double* out) const override;

  const JournalBearingParams& params() const { return p_; }

  /// Why the film cannot run (cavitation mass-conserving: a static answer only,
  /// its film fraction has no history yet); empty when it can.
  std::string run_refusal() const override;
  /// The Reynolds film's grid solver (film = reynolds), else null.
  const ReynoldsFilm* reynolds_film() const { return reynolds_.get(); }
  /// Film force (hydrodynamic + contact) of a bearing of weight `weight` (1 =
  /// full width) for eccentricity e, its rate ed, relative spin om, with
  /// derivatives when `derivs`. Throws RunError for eps >= eps_max (no
  /// contact) or e >= c. Public for tests.
  FilmForce film(double t, const Eigen::Vector2d& e, const Eigen::Vector2d& ed, double om,
                 double weight, bool derivs) const;
  /// Hydrodynamic part only by the chosen film model (and, for the short
  /// film, method): no checks, no contact.
  FilmForce hydro(const Eigen::Vector2d& e, const Eigen::Vector2d& ed, double om, double weight,
                  bool derivs, bool closed_form) const;
  /// Peak film pressure at the mid-plane for the state (e, ed, om) [Pa]; with
  /// `angle`, its bearing angle phi (from the bearing marker's x axis towards
  /// its y axis, in (-pi, pi]) [rad].
  double peak_pressure(const Eigen::Vector2d& e, const Eigen::Vector2d& ed, double om,
                       double* angle = nullptr) const;
  /// Viscous friction torque on the journal about the bearing axis [N m] of a
  /// station of weight `weight` (share of the width) with eccentricity e,
  /// relative spin om and hydrodynamic film force f on the journal:
  ///   T = -2 pi eta R^3 (weight B) om / (c sqrt(1 - eps^2)) - (e x f)_z / 2,
  /// the Couette shear over the whole circumference (Petroff's law, with the
  /// eccentric film) plus the pressure-driven part, which by parts is half the
  /// moment of the film force about the bearing centre (Hamrock, Schmid,
  /// Jacobson, Fundamentals of Fluid Film Lubrication, 2nd ed., Dekker 2004,
  /// journal friction of the short bearing). Asperity contact is not included.
  double friction_torque(const Eigen::Vector2d& e, double om, const Eigen::Vector2d& f,
                         double weight) const;

 private:
  struct Station {
    double s;       ///< axial offset from the journal marker [m]
    double weight;  ///< share of the full-width parabolic weight
  };
  /// Kinematics of one station: e, ed, om (bearing components).
  void station_state(const MarkerMotion* m, double s, Eigen::Vector2d& e, Eigen::Vector2d& ed,
                     double& om) const;
  void fail_if_closed(double t, double e) const;
  /// Short film: hydro() and peak_pressure() of the paper's film.
  FilmForce short_hydro(const Eigen::Vector2d& e, const Eigen::Vector2d& ed, double om,
                        double weight, bool derivs, bool closed_form) const;
  double short_peak_pressure(const Eigen::Vector2d& e, const Eigen::Vector2d& ed, double om,
                             double* angle) const;

  JournalBearingParams p_;
  enum class Film { Short, Finite, Reynolds } film_ = Film::Short;
  std::shared_ptr<const ReynoldsFilm> reynolds_;  ///< film = reynolds
  std::shared_ptr<const FilmTable> table_;        ///< film = reynolds, solve = table
  std::vector<Station> stations_;
  std::vector<double> gl_x_, gl_w_;  ///< Gauss-Legendre nodes/weights on [-1, 1]
};

/// Declaration of the "journal-bearing" element type (wired into registry.cpp).
ElementType journal_bearing_element_type();

/// Gauss-Legendre nodes and weights on [-1, 1] (n >= 1).
void gauss_legendre(int n, std::vector<double>& x, std::vector<double>& w);

}  // namespace evas
