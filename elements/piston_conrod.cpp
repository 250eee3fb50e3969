#include "elements/piston_conrod.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "elements/param_binding.h"

namespace evas {

namespace {
constexpr double kRad = M_PI / 180.0;
}

// ---------------------------------------------------------------------------
// Slider-crank kinematics.

void SliderCrank::eval(double theta, double& x, double& dx, double& ddx) const {
  eval_sc(std::sin(theta), std::cos(theta), x, dx, ddx);
}

void SliderCrank::eval_sc(double s, double c, double& x, double& dx, double& ddx) const {
  const double Lc = std::sqrt(L * L - R * R * s * s);  // L cos phi
  x = R * c + Lc;
  dx = -R * s - R * R * s * c / Lc;
  ddx = -R * c - R * R * (c * c - s * s) / Lc - std::pow(R * R * s * c, 2) / (Lc * Lc * Lc);
}

double SliderCrank::acceleration(double theta, double w) const {
  const double lam = R / L, s = std::sin(theta);
  const double den = std::pow(1.0 - lam * lam * s * s, 1.5);
  return -R * w * w *
         (std::cos(theta) + (lam * std::cos(2 * theta) + lam * lam * lam * s * s * s * s) / den);
}

double SliderCrank::harmonic(int k) const {
  const double l = R / L, l3 = l * l * l, l5 = l3 * l * l;
  switch (k) {
    case 1:
      return l + l3 / 4 + 15 * l5 / 128;
    case 2:
      return -(l3 / 4 + 3 * l5 / 16);
    case 3:
      return 9 * l5 / 128;
  }
  return 0.0;
}

double SliderCrank::acceleration_series(double theta, double w, int kmax) const {
  double sum = std::cos(theta);
  for (int k = 1; k <= kmax; ++k) sum += harmonic(k) * std::cos(2 * k * theta);
  return -R * w * w * sum;
}

// ---------------------------------------------------------------------------
// Element.

PistonConrod::PistonConrod(std::string name, std::vector<int> markers, const PistonConrodParams& p,
                           std::shared_ptr<const PressureTable> gas)
    : Element(std::move(name), std::move(markers)), p_(p), drive_(p.speed), gas_(std::move(gas)) {
  const std::string where = "piston-conrod '" + this->name() + "'";
  if (this->markers().size() != 3)
    throw InputError(where + ": needs 3 markers (crankpin, liner, head)");
  if (!(p.crank_radius > 0 && p.conrod_length > p.crank_radius))
    throw InputError(where + ": conrod_length must exceed crank_radius (got R = " +
                     std::to_string(p.crank_radius) + " m, L = " + std::to_string(p.conrod_length) +
                     " m)");
  if (!(p.bore > 0)) throw InputError(where + ": bore must be positive");
  if (!(p.piston_mass >= 0 && p.rec_mass >= 0 && p.rot_mass >= 0))
    throw InputError(where + ": masses must not be negative");
  if (!(p.friction_velocity > 0)) throw InputError(where + ": friction_velocity must be positive");
  if (p.cylinder_axis.norm() == 0 || p.crank_axis.norm() == 0)
    throw InputError(where + ": cylinder_axis and crank_axis must be non-zero");
  ec_ = p.cylinder_axis.normalized();
  ea_ = p.crank_axis.normalized();
  if (std::abs(ec_.dot(ea_)) > 1e-3)
    throw InputError(where + ": cylinder_axis must be perpendicular to crank_axis (cos = " +
                     std::to_string(ec_.dot(ea_)) + ")");
  ea_ = (ea_ - ec_.dot(ea_) * ec_).normalized();
  es_ = ea_.cross(ec_);
  sc_.R = p.crank_radius;
  sc_.L = p.conrod_length;
  const double lam = sc_.R / sc_.L;
  // The closed-form friction solution needs mu tan(phi_max) < 1.
  if (p.friction_coefficient * lam / std::sqrt(1 - lam * lam) >= 1.0)
    throw InputError(where + ": friction_coefficient too large for this crank (mu tan phi >= 1)");
  area_ = M_PI / 4 * p.bore * p.bore;
  h_L_ = p.liner_height > 0 ? p.liner_height : p.conrod_length;
}

PistonConrod::State PistonConrod::state(double t) const {
  const SpeedProfile& w = drive_.profile();
  const double theta = w.angle_plus(t, (p_.initial_angle_deg - p_.firing_phase_deg) * kRad);
  return state_at(theta, w.speed(t), w.acceleration(t));
}

void PistonConrod::follow_speed(const SpeedProfile& crank) {
  if (p_.coupled) return;  // the markers carry the crank angle
  if (p_.eq2_side_force && !crank.is_constant())
    throw InputError("piston-conrod '" + name() +
                     "': side_force 'eq2' (the paper's constant-speed series) cannot follow a "
                     "varying crank speed; use side_force 'exact'");
  if (crank.min_speed() < 0.0)
    throw InputError("piston-conrod '" + name() + "': the crank turns at " +
                     format_number(crank.min_speed()) +
                     " rad/s; a prescribed piston's speed must not be negative (as its own "
                     "'speed')");
  if (gas_map_)
    gas_map_->check_covers(crank.min_speed(), crank.max_speed(), "piston-conrod '" + name() + "'");
  drive_.follow(crank);
}

double PistonConrod::peak_gas_pressure() const {
  double peak = gas_ ? gas_->max_pressure() : 0.0;
  if (gas_map_)
    for (const auto& load : gas_map_->loads())
      for (const auto& e : load.entries) peak = std::max(peak, e.table.max_pressure());
  return peak;
}

void PistonConrod::set_pressure_map(std::shared_ptr<const PressureMap> map) {
  const std::string where = "piston-conrod '" + name() + "'";
  if (p_.coupled)
    throw InputError(where +
                     ": a pressure_map needs mode 'prescribed' (the table would depend on the "
                     "crank speed, a state in mode 'coupled')");
  if (gas_) throw InputError(where + ": give pressure_file or pressure_map, not both");
  if (const SpeedProfile* own = drive_.own())
    map->check_covers(own->min_speed(), own->max_speed(), where);
  gas_map_ = std::move(map);
}

std::string PistonConrod::load_source() const {
  return gas_map_ && gas_map_->has_loads() ? "pressure map " + gas_map_->source() : std::string();
}

void PistonConrod::set_operating_load(double load) {
  if (!gas_map_ || !gas_map_->has_loads()) return;
  gas_map_->check_load(load, "piston-conrod '" + name() + "'");
  load_ = load;
}

PistonConrod::State PistonConrod::state(double t, const MarkerMotion* m) const {
  if (!p_.coupled) return state(t);
  double theta, thd, thdd;
  crank_motion(m, theta, thd, thdd);
  return state_at(theta, thd, thdd);
}

void PistonConrod::crank_motion(const MarkerMotion* m, double& theta, double& thd,
                                double& thdd) const {
  const Vec3 ea = m[1].R * ea_;
  theta = ea.dot(m[0].psi - m[1].psi) + (p_.initial_angle_deg - p_.firing_phase_deg) * kRad;
  thd = ea.dot(m[0].w - m[1].w);
  thdd = ea.dot(m[0].al - m[1].al);
}

PistonConrod::State PistonConrod::state_at(double theta, double thd, double thdd) const {
  State s;
  s.theta = theta;
  s.thd = thd;
  s.thdd = thdd;
  double x, dx, ddx;
  const double sn = std::sin(theta), cs = std::cos(theta);  // (once: four uses below)
  sc_.eval_sc(sn, cs, x, dx, ddx);
  s.x = x;
  s.xd = dx * thd;
  const double lam = sc_.R / sc_.L;
  // eq2 (prescribed only): the paper's constant-speed two-term series (A2 ~ lambda), used
  // consistently in the inertia, rod and side forces so that the element stays in equilibrium.
  s.xdd = p_.eq2_side_force ? -sc_.R * thd * thd * (cs + lam * std::cos(2 * theta))
                            : ddx * thd * thd + dx * thdd;
  const double dxdd = p_.eq2_side_force ? 0.0 : dx;  // d xdd / d thdd
  // (a map without loads: the speed interpolation alone, as before loads existed)
  s.p = gas_map_
            ? (gas_map_->has_loads() ? (*gas_map_)(theta, thd, load_) : (*gas_map_)(theta, thd)) -
                  p_.crankcase_pressure
        : gas_ ? (*gas_)(theta)-p_.crankcase_pressure
               : 0.0;
  s.Fc = s.p * area_;
  s.sin_phi = lam * sn;
  s.cos_phi = std::sqrt(1.0 - s.sin_phi * s.sin_phi);
  const double tphi = s.sin_phi / s.cos_phi;
  const double m = p_.piston_mass + p_.rec_mass;
  // Friction on the piston F_f = -sg (F0 + mu |N|), N = (Fc + m xdd - F_f) tan phi:
  // N = B + c |N| with B = (Fc + m xdd + sg F0) tan phi, c = sg mu tan phi, |c| < 1.
  const double sg = std::tanh(s.xd / p_.friction_velocity);
  const double B = (s.Fc + m * s.xdd + sg * p_.friction_force) * tphi;
  const double c = sg * p_.friction_coefficient * tphi;
  const double den = B >= 0 ? 1 - c : 1 + c;
  s.N = B / den;
  s.Ff = -sg * (p_.friction_force + p_.friction_coefficient * std::abs(s.N));
  s.Fr = (s.Fc + m * s.xdd - s.Ff) / s.cos_phi;
  // derivatives with respect to thdd on the current branch (B >= 0 or B < 0)
  s.dN = m * dxdd * tphi / den;
  s.dFf = -sg * p_.friction_coefficient * (B >= 0 ? 1.0 : -1.0) * s.dN;
  s.dFr = (m * dxdd - s.dFf) / s.cos_phi;
  const Vec3 u = s.cos_phi * ec_ - s.sin_phi * es_;
  const Vec3 er = cs * ec_ + sn * es_;
  const Vec3 et = -sn * ec_ + cs * es_;
  s.F_pin_B = -s.Fr * u + p_.rot_mass * sc_.R * (thd * thd * er - thdd * et);
  return s;
}

void PistonConrod::loads_B(const State& s, Vec3& F_pin, Vec3& F_liner, Vec3& M_liner,
                           Vec3& F_head) const {
  F_pin = s.F_pin_B;
  F_liner = -s.N * es_ - s.Ff * ec_;
  M_liner = (s.x - h_L_) * ec_.cross(-s.N * es_);
  F_head = s.Fc * ec_;
}

void PistonConrod::evaluate(double t, const MarkerMotion* m, MarkerLoad* loads) const {
  const State s = state(t, m);
  const Mat3& R = m[1].R;  // block axes in G
  Vec3 Fp, Fl, Ml, Fh;
  loads_B(s, Fp, Fl, Ml, Fh);
  loads[0].F = R * Fp;
  loads[0].M.setZero();
  loads[1].F = R * Fl;
  loads[1].M = R * Ml;
  loads[2].F = R * Fh;
  loads[2].M.setZero();
}

void PistonConrod::inertia(double t, const MarkerMotion* m, Mat& P, Mat& Q) const {
  P.setZero(18, 1);
  Q.setZero(18, 1);
  if (!p_.coupled) return;
  const State s = state(t, m);
  const Mat3& R = m[1].R;
  const Vec3 ea = R * ea_;
  Q.block<3, 1>(3, 0) = ea;   // al of the crankpin marker
  Q.block<3, 1>(9, 0) = -ea;  // al of the liner marker
  const Vec3 u = s.cos_phi * ec_ - s.sin_phi * es_;
  const Vec3 et = -std::sin(s.theta) * ec_ + std::cos(s.theta) * es_;
  P.block<3, 1>(0, 0) = R * (-s.dFr * u - p_.rot_mass * sc_.R * et);
  P.block<3, 1>(6, 0) = R * (-s.dN * es_ - s.dFf * ec_);
  P.block<3, 1>(9, 0) = R * ((s.x - h_L_) * ec_.cross(-s.dN * es_));
}

void PistonConrod::derivatives(double, const MarkerMotion* m, Mat& D) const {
  D.setZero(18, 36);
  if (!p_.coupled) return;  // prescribed mode: loads are explicit in time
  // The loads depend on the motion through theta (psi of crankpin and liner) and thd
  // (their w) only, at fixed thdd and block axes: chain rule with central differences
  // in the two scalars (theta reduced to one 720 deg cycle, so the step is absolute).
  double theta, thd, thdd;
  crank_motion(m, theta, thd, thdd);
  theta = std::fmod(theta, 4 * M_PI);
  const Mat3& R = m[1].R;
  const Vec3 ea = R * ea_;
  auto loads_G = [&](double th, double w) {
    Eigen::Matrix<double, 12, 1> L;
    Vec3 Fp, Fl, Ml, Fh;
    loads_B(state_at(th, w, thdd), Fp, Fl, Ml, Fh);
    L << R * Fp, R * Fl, R * Ml, R * Fh;
    return L;
  };
  const double h_th = 1e-6, h_w = 1e-6 * std::max(1.0, std::abs(thd));
  const Eigen::Matrix<double, 12, 1> d_th =
      (loads_G(theta + h_th, thd) - loads_G(theta - h_th, thd)) / (2 * h_th);
  const Eigen::Matrix<double, 12, 1> d_w =
      (loads_G(theta, thd + h_w) - loads_G(theta, thd - h_w)) / (2 * h_w);
  // rows: pin F (0..2), liner F (6..8), liner M (9..11), head F (12..14)
  const int rows[4] = {0, 6, 9, 12};
  for (int b = 0; b < 4; ++b) {
    const auto dth = d_th.segment<3>(3 * b);
    const auto dw = d_w.segment<3>(3 * b);
    // columns: marker j at 12 j: p 0..2, v 3..5, psi 6..8, w 9..11
    D.block<3, 3>(rows[b], 6) += dth * ea.transpose();
    D.block<3, 3>(rows[b], 12 + 6) -= dth * ea.transpose();
    D.block<3, 3>(rows[b], 9) += dw * ea.transpose();
    D.block<3, 3>(rows[b], 12 + 9) -= dw * ea.transpose();
  }
}

std::vector<Channel> PistonConrod::channels() const {
  return {{"crank_angle", "deg"},    {"piston_position", "m"}, {"piston_acceleration", "m/s^2"},
          {"gas_pressure", "Pa"},    {"gas_force", "N"},       {"side_force", "N"},
          {"conrod_force", "N"},     {"friction_force", "N"},  {"crankpin_force_x", "N"},
          {"crankpin_force_y", "N"}, {"crankpin_force_z", "N"}};
}

void PistonConrod::channel_values(double t, const MarkerMotion* m, double* out) const {
  const State s = state(t, m);
  double a = std::fmod(s.theta / kRad, 720.0);
  if (a < 0) a += 720.0;
  out[0] = a;
  out[1] = s.x;
  out[2] = s.xdd;
  out[3] = s.p;
  out[4] = s.Fc;
  out[5] = -s.N;
  out[6] = s.Fr;
  out[7] = s.Ff;
  for (int i = 0; i < 3; ++i) out[8 + i] = s.F_pin_B[i];
}

// ---------------------------------------------------------------------------
// Declaration.

ElementType piston_conrod_element_type() {
  ParamSpec pressure_file = text_param(
      "pressure_file",
      "cylinder pressure table over 720 deg, relative to the scene file (empty: no gas force)", {},
      "");
  pressure_file.is_path = true;
  ParamSpec pressure_map = text_param(
      "pressure_map",
      "pressure tables at several speeds (and loads): a file of 'speed_rpm table_file' lines, "
      "interpolated linearly in the prescribed crank speed, or of 'speed_rpm load table_file' "
      "lines, also linearly in the scene's operating_point.load (mode prescribed; in place of "
      "pressure_file)",
      {}, "");
  pressure_map.is_path = true;
  ElementType t;
  t.type = "piston-conrod";
  t.doc =
      "Piston and conrod of one cylinder (paper Fig. 4, Eq. 2). Markers: crankpin (crankshaft, "
      "crankpin centre), liner (block, on the cylinder axis at liner_height from the crank axis; "
      "give it rotation), head (block, on the cylinder axis). Block axes = liner marker axes. "
      "Gas force F_c = (p(theta) - crankcase_pressure) A_p on the head; side force on the liner "
      "(moved to the pin height by a moment); crankpin force along the rod plus m_2 R w^2. "
      "theta = speed t + initial_angle - firing_phase (0 = firing TDC; the table's cycle angle); "
      "without its own speed the element follows the crank's speed profile w(t): theta = "
      "integral of w + initial_angle - firing_phase. "
      "Mode prescribed: explicit in time (paper Step 3); mode coupled: crank angle from the "
      "markers, reciprocating inertia implicit. See docs/elements-piston-motor.md.";
  t.num_markers = 3;
  using P = PistonConrodParams;
  static const ParamBinding<P> binding =
      ParamBinding<P>()
          .required(&P::crank_radius, "crank_radius", "m", "crank radius R (half the stroke)", 1e-6)
          .required(&P::conrod_length, "conrod_length", "m",
                    "conrod length L, pin to crankpin centres (> R)", 1e-6)
          .required(&P::bore, "bore", "m", "cylinder bore (piston area pi bore^2 / 4)", 1e-6)
          .required(&P::piston_mass, "piston_mass", "kg", "piston with rings and pin, m_p", 0.0)
          .number(&P::rec_mass, "conrod_reciprocating_mass", "kg",
                  "conrod mass lumped at the pin, m_1", 0.0)
          .number(&P::rot_mass, "conrod_rotating_mass", "kg",
                  "conrod mass lumped at the crankpin, m_2", 0.0)
          .vec3(&P::cylinder_axis, "cylinder_axis", "-",
                "cylinder axis in block axes, from the crank axis towards the head")
          .vec3(&P::crank_axis, "crank_axis", "-",
                "crank axis in block axes; positive crank rotation is right-handed about it")
          .number(&P::firing_phase_deg, "firing_phase", "deg",
                  "crank angle at which this cylinder is at firing TDC (0..720; e.g. 0/180/540/360 "
                  "for an in-line four firing 1-3-4-2)",
                  0.0, 720.0)
          .flag(&P::coupled, "mode",
                "prescribed: theta = speed t (or the integral of the crank's speed) + "
                "initial_angle - "
                "firing_phase (explicit in time); "
                "coupled: theta = rotation of the crankpin marker relative to the liner "
                "marker about crank_axis + initial_angle - firing_phase, reciprocating "
                "inertia solved implicitly",
                {"prescribed", "coupled"}, "coupled")
          .number(&P::speed, "speed", "rad/s",
                  "prescribed crank speed (3000 rpm = 314.159 rad/s) in mode prescribed; "
                  "omitted: the crank's (the body with a spin LOF), constant or a profile; "
                  "not used in mode coupled",
                  0.0)
          .number(&P::initial_angle_deg, "initial_angle", "deg",
                  "prescribed: crank angle at t = 0; coupled: crank angle of the reference "
                  "(undeformed, unrotated) configuration",
                  -1e6, 1e6)
          .unbound(pressure_file)
          .unbound(pressure_map)
          .number(&P::crankcase_pressure, "crankcase_pressure", "Pa",
                  "pressure below the piston, subtracted from the table (1e5 for an absolute table "
                  "with an atmospheric crankcase)",
                  0.0)
          .flag(&P::eq2_side_force, "side_force",
                "exact: exact piston acceleration; eq2: the paper's two-term series "
                "(Eq. 2, constant speed)",
                {"exact", "eq2"}, "eq2")
          .number(&P::friction_coefficient, "friction_coefficient", "-",
                  "piston-liner friction coefficient mu (F_f = mu |N|)", 0.0, 1.0)
          .number(&P::friction_force, "friction_force", "N",
                  "constant piston friction force F_0 (added to mu |N|)", 0.0)
          .number(&P::friction_velocity, "friction_velocity", "m/s",
                  "smoothing speed v_s: friction = -tanh(piston velocity / v_s) (F_0 + mu |N|)",
                  1e-9)
          .number(&P::liner_height, "liner_height", "m",
                  "height of the liner marker above the crank axis along the cylinder axis "
                  "(0: conrod_length, the middle of the pin's travel)",
                  0.0);
  t.params = binding.specs();
  t.make = [](const std::string& name, const std::vector<int>& markers, const ParamValues& v) {
    const std::string where = "piston-conrod '" + name + "'";
    const PistonConrodParams p = binding.read(v, where);
    if (p.coupled && p.eq2_side_force)
      throw InputError(where +
                       ": side_force 'eq2' (the paper's constant-speed series) needs mode "
                       "'prescribed'; mode 'coupled' uses the exact kinematics");
    std::shared_ptr<const PressureTable> gas;
    const std::string& file = v.text("pressure_file");
    if (!file.empty()) {
      try {
        gas = PressureTable::read_cached(file);
      } catch (const InputError& e) {
        throw InputError(where + ": " + e.what());
      }
    }
    auto e = std::make_unique<PistonConrod>(name, markers, p, std::move(gas));
    if (!v.given("speed")) e->leave_speed_to_crank();
    if (const std::string& map = v.text("pressure_map"); !map.empty()) {
      if (p.coupled) throw InputError(where + ": a pressure_map needs mode 'prescribed'");
      if (!file.empty()) throw InputError(where + ": give pressure_file or pressure_map, not both");
      try {
        e->set_pressure_map(std::make_shared<const PressureMap>(PressureMap::read(map)));
      } catch (const InputError& err) {
        const std::string msg = err.what();
        throw InputError(msg.rfind(where, 0) == 0 ? msg : where + ": " + msg);
      }
    }
    return e;
  };
  return t;
}

}  // namespace evas
