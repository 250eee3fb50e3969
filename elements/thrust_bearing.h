// Thrust bearing (paper section 3.2: "the constraint of the crankshaft in the
// axial direction ... a nonlinear spring and damper"; formulation.md section 5).
//
// Markers: 0 = the bearing housing (block side), 1 = the crankshaft. The axis
// is a = R_0 axis / |axis| (`axis` in marker 0's axes, default its z).
//   d  = a . (p1 - p0) - offset    axial position of the shaft in the clearance [m]
//   dv = a . (v1 - v0)              axial rate [m/s]
//   F  = -( g(d) + c chi(d) dv )    axial load on the shaft [N]
// with g the ClearanceLaw (elements/force_law.h): zero for |d| <= gap, the
// contact law f(rho(|d| - gap)) sign(d) beyond, C1-smoothed over the band
// `smoothing` (0 = sharp edge). Damping mode "contact" multiplies c by the
// contact fraction chi (smoothstep over the same band: 0 in the gap, 1 beyond
// gap + smoothing); mode "always" uses chi = 1 (an oil film damps everywhere).
// The damping force is not clamped, so in contact the total force can briefly
// pull (kept for a smooth Jacobian).
//   F1 = F a,  F0 = -F1,  M1 = 0,  M0 = -(p1 - p0) x F1  (balance of moments)
// The axis is held fixed in the derivatives (it moves only with marker 0's
// prescribed LOF). Derivatives: dF/dd = -(g'(d) + c chi'(d) dv), exact on both
// sides of the gap edges and continuous across them when smoothing > 0.
#pragma once

#include "elements/force_law.h"
#include "elements/registry.h"
#include "model/element.h"

namespace evas {

class ThrustBearing : public Element {
 public:
  ThrustBearing(std::string name, std::vector<int> markers, ClearanceLaw law, double damping,
                bool damp_always, const Vec3& axis = Vec3::UnitZ(), double offset = 0.0);
  std::string type() const override { return "thrust-bearing"; }
  /// Translations only; the collar (marker 0) takes the force's moment, the shaft none.
  unsigned motion_reads(std::size_t) const override { return kReadsTranslation; }
  unsigned load_parts(std::size_t slot) const override {
    return slot == 0 ? kLoadsForce | kLoadsMoment : kLoadsForce;
  }
  void evaluate(double t, const MarkerMotion* m, MarkerLoad* loads) const override;
  void derivatives(double t, const MarkerMotion* m, Mat& D) const override;
  /// force [N] (axial load on the shaft), displacement d [m], clearance gap - |d| [m]
  /// (positive: free play left, negative: penetration).
  std::vector<Channel> channels() const override;
  void channel_values(double t, const MarkerMotion* m, double* out) const override;

  /// Axial load on the shaft and dF/dd, dF/ddv at axial position d and rate dv.
  void axial(double d, double dv, double& F, double& dFdd, double& dFdv) const;

 private:
  ClearanceLaw law_;
  double c_;
  bool always_;
  Vec3 axis_;  // unit, marker 0's axes
  double offset_;
};

/// Declaration of "thrust-bearing" (2 markers: housing, shaft).
ElementType thrust_bearing_element_type();

}  // namespace evas
