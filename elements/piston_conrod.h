// Piston-conrod element (paper Fig. 4, Eq. 2; formulation.md section 5).
//
// One cylinder: piston (mass m_p), conrod as two lumped masses (m_1 at the
// piston pin, reciprocating; m_2 at the crankpin, rotating), gas pressure
// from a 720 deg table. Markers (all loads in G components):
//   0  crankpin   on the crankshaft, at the crankpin centre
//   1  liner      on the block, on the cylinder axis at height h_L from the
//                 crank axis (parameter liner_height); should carry rotation
//   2  head       on the block, on the cylinder axis (the gas force acts here)
// Block axes are marker 1's axes (MarkerMotion::R); the cylinder axis e_c
// (crank -> head) and the crank axis e_a are given in block axes; e_s = e_a x e_c.
// Crank angle of this cylinder theta = theta_crank - firing_phase, 0 at its
// firing TDC, increasing in the right-hand sense about e_a; the crankpin sits
// at R (cos theta e_c + sin theta e_s) from the crank axis.
//
// Kinematics (lambda = R/L): sin phi = lambda sin theta,
//   x_p = R cos theta + L cos phi (pin height above the crank axis along e_c).
// Piston (with m_1), equilibrium along e_c and e_s, rod force F_r along the rod
// (compression positive), liner normal force N on the piston along e_s:
//   (m_p + m_1) xdd_p = -F_c + F_r cos phi + F_f,     N = F_r sin phi
//   => F_r = (F_c + m xdd_p - F_f) / cos phi,  N = (F_c + m xdd_p - F_f) tan phi
// Side force on the liner F_s = -N (paper Eq. 2 sign: with the two-term series
// xdd_p = -R w^2 (cos theta + lambda cos 2 theta) and F_f = 0 it is Eq. 2).
// Friction on the piston F_f = -tanh(xd_p / v_s) (F_0 + mu |N|), solved in
// closed form with N.
// Loads:
//   crankpin  F = -F_r u + m_2 R w^2 e_r  (u = cos phi e_c - sin phi e_s: crankpin -> pin)
//   liner     F = -N e_s - F_f e_c,  M = (x_p - h_L) e_c x (-N e_s)  (moves N to the pin)
//   head      F = F_c e_c
// Modes:
//  `prescribed` (the paper's Step 3): theta_crank = w t + theta_0, loads explicit
//     in time, state_dependent() false, D = 0. Without its own `speed` the
//     element follows the crank's speed profile w(t) (model/speed_profile.h):
//     theta_crank = integral_0^t w + theta_0, thd = w(t), thdd = w'(t).
//  `coupled` (beyond the paper): the crank angle is the crankpin marker's rotation
//     relative to the liner marker about e_a,
//       theta_crank = e_a.(psi_pin - psi_liner) + theta_0,  thd = e_a.(w_pin - w_liner),
//       thdd = e_a.(al_pin - al_liner)   (e_a in G; psi includes the LOF spin),
//     so torsion and speed fluctuation reach the piston; xd_p = x' thd,
//     xdd_p = x' thdd + x'' thd^2, and the rotating mass adds m_2 R (thd^2 e_r - thdd e_t).
//     The loads are affine in thdd (piecewise, through the friction's |N|): the
//     element declares rank-1 inertia P Q^T with Q = (e_a on al_pin, -e_a on al_liner)
//     and P = d(loads)/d(thdd), and the System solves the reciprocating inertia
//     implicitly with the modal accelerations (docs/theory.md s.2.6). The block's
//     own acceleration does not act on the piston (as in prescribed mode).
#pragma once

#include <limits>
#include <memory>
#include <string>

#include "elements/gas_pressure.h"
#include "elements/prescribed_speed.h"
#include "elements/pressure_map.h"
#include "elements/registry.h"
#include "model/element.h"

namespace evas {

/// Slider-crank kinematics (references.md section 2).
struct SliderCrank {
  double R = 0.0;  ///< crank radius [m]
  double L = 0.0;  ///< conrod length [m]
  /// Pin height x_p and its first and second derivatives w.r.t. theta.
  void eval(double theta, double& x, double& dx, double& ddx) const;
  /// The same from sin(theta), cos(theta).
  void eval_sc(double s, double c, double& x, double& dx, double& ddx) const;
  /// Exact piston acceleration at constant speed w (references.md s.2 closed form).
  double acceleration(double theta, double w) const;
  /// Fourier series of the acceleration truncated after cos(2k theta), k <= kmax (1..3):
  /// -R w^2 (cos theta + A2 cos 2theta + A4 cos 4theta + A6 cos 6theta).
  double acceleration_series(double theta, double w, int kmax) const;
  /// Series coefficients A2, A4, A6 (references.md s.2), index 1..3.
  double harmonic(int k) const;
};

/// The defaults below are the scene's defaults (the parameter table is bound to
/// these members, piston_conrod_element_type()); the first four are required.
struct PistonConrodParams {
  double crank_radius = 0.0;           ///< R [m] (required)
  double conrod_length = 0.0;          ///< L [m] (required)
  double bore = 0.0;                   ///< [m] (required)
  double piston_mass = 0.0;            ///< m_p [kg] (required)
  double rec_mass = 0.0;               ///< m_1, conrod share at the pin [kg]
  double rot_mass = 0.0;               ///< m_2, conrod share at the crankpin [kg]
  Vec3 cylinder_axis = Vec3::UnitZ();  ///< block axes, crank -> head
  Vec3 crank_axis = Vec3::UnitX();     ///< block axes, positive rotation sense
  double firing_phase_deg = 0.0;
  double speed = 0.0;              ///< prescribed crank speed w [rad/s]
  double initial_angle_deg = 0.0;  ///< crank angle at t = 0 [deg]
  bool eq2_side_force = false;     ///< use the paper's two-term acceleration series
  double friction_coefficient = 0.0;
  double friction_force = 0.0;      ///< constant part F_0 [N]
  double friction_velocity = 0.05;  ///< smoothing speed v_s of the sign [m/s]
  double crankcase_pressure = 0.0;  ///< subtracted from the table [Pa]
  double liner_height = 0.0;        ///< h_L [m]; <= 0: L (middle of the pin's travel)
  bool coupled = false;             ///< crank angle from the markers (see above)
};

class PistonConrod : public Element {
 public:
  /// The liner marker takes the moment that moves the side force to the pin height.
  bool needs_rotation(std::size_t slot) const override {
    return slot == 1 || (slot == 0 && p_.coupled);
  }
  /// Prescribed: the loads follow from time alone (and the liner's axes). Coupled:
  /// the crank angle is the pin's rotation against the liner's.
  unsigned motion_reads(std::size_t slot) const override {
    return p_.coupled && slot < 2 ? kReadsRotation : 0u;
  }
  /// Forces on the crankpin and the head; force and moment on the liner.
  unsigned load_parts(std::size_t slot) const override {
    return slot == 1 ? kLoadsForce | kLoadsMoment : kLoadsForce;
  }
  /// `gas` may be null (no gas force). Throws InputError on inconsistent geometry.
  PistonConrod(std::string name, std::vector<int> markers, const PistonConrodParams& p,
               std::shared_ptr<const PressureTable> gas);
  std::string type() const override { return "piston-conrod"; }
  void evaluate(double t, const MarkerMotion* m, MarkerLoad* loads) const override;
  void derivatives(double t, const MarkerMotion* m, Mat& D) const override;
  bool state_dependent() const override { return p_.coupled; }
  int inertia_rank() const override { return p_.coupled ? 1 : 0; }
  void inertia(double t, const MarkerMotion* m, Mat& P, Mat& Q) const override;
  bool inertia_piecewise() const override { return p_.coupled && p_.friction_coefficient > 0; }
  std::vector<Channel> channels() const override;
  void channel_values(double t, const MarkerMotion* m, double* out) const override;

  /// Everything the element computes at one instant (block axes where noted).
  struct State {
    double theta = 0.0;                            ///< cylinder crank angle [rad], 0 = firing TDC
    double x = 0.0, xd = 0.0, xdd = 0.0;           ///< pin height, velocity, acceleration (used)
    double p = 0.0;                                ///< gas pressure minus crankcase [Pa]
    double Fc = 0.0, Fr = 0.0, N = 0.0, Ff = 0.0;  ///< gas, rod, liner normal, friction [N]
    double sin_phi = 0.0, cos_phi = 1.0;
    Vec3 F_pin_B = Vec3::Zero();            ///< crankpin load, block axes [N]
    double thd = 0.0, thdd = 0.0;           ///< crank speed and acceleration used [rad/s, rad/s^2]
    double dN = 0.0, dFf = 0.0, dFr = 0.0;  ///< d/d(thdd) of N, F_f, F_r (coupled mode)
  };
  /// Prescribed mode: the state at time t.
  State state(double t) const;
  /// Either mode: the state at the given marker motion (prescribed: motion ignored).
  State state(double t, const MarkerMotion* m) const;
  /// Exact kinematics at crank angle theta (cylinder), speed and acceleration.
  State state_at(double theta, double thd, double thdd) const;
  const PistonConrodParams& params() const { return p_; }

  /// Mode prescribed: the crank's speed profile replaces `speed` (the scene
  /// reader's follow_speed); until then the element reports wants_speed().
  void leave_speed_to_crank() {
    if (!p_.coupled) drive_.leave_to_crank();
  }
  const SpeedProfile* own_speed() const override { return p_.coupled ? nullptr : drive_.own(); }
  bool wants_speed() const override { return drive_.waiting(); }
  void follow_speed(const SpeedProfile& crank) override;
  /// Gas pressure from tables at several speeds (in place of one table), read
  /// at the prescribed crank speed. Mode prescribed only; the speed (its own,
  /// or the crank's when it follows) must stay inside the map's speeds.
  void set_pressure_map(std::shared_ptr<const PressureMap> map);
  /// A map with a load column reads the scene's operating_point.load.
  std::string load_source() const override;
  /// The load at which a map with loads is read, constant over the run; throws
  /// InputError naming the element, the map and its loads when outside them.
  /// Without such a map: nothing to read it (the scene reader refuses the load).
  void set_operating_load(double load) override;
  /// The highest pressure of its table, or of every table of its map [Pa]; 0
  /// when it does not fire (for the plausibility check of the scene reader).
  double peak_gas_pressure() const;

 private:
  PistonConrodParams p_;
  PrescribedSpeed drive_;  // mode prescribed: crank angle since t = 0, speed, acceleration
  std::shared_ptr<const PressureTable> gas_;
  std::shared_ptr<const PressureMap> gas_map_;  // in place of gas_ (set_pressure_map)
  // operating_point.load [the map's unit] for a map with loads; NaN until set
  // (the scene reader refuses such a map without a load)
  double load_ = std::numeric_limits<double>::quiet_NaN();
  SliderCrank sc_;
  Vec3 ec_, ea_, es_;  // block axes
  double area_, h_L_;
  /// Loads in block axes (pin F, liner F, liner M, head F) from a state.
  void loads_B(const State& s, Vec3& F_pin, Vec3& F_liner, Vec3& M_liner, Vec3& F_head) const;
  /// Coupled mode: cylinder crank angle, speed, acceleration from the markers.
  void crank_motion(const MarkerMotion* m, double& theta, double& thd, double& thdd) const;
};

/// Declaration for the registry ("piston-conrod").
ElementType piston_conrod_element_type();

}  // namespace evas
