// Linear spring-damper between two markers (translation and rotation).
//
// Loads on marker 2 (marker 1 gets the reaction), in the element frame E whose
// axes are marker 1's axes (R_E = R_1):
//   d = R_E^T (p2 - p1 - R_E l0),   dv = R_E^T (v2 - v1)
//   F_E = -(k .* d + c .* dv) - preload,          F2 = R_E F_E,  F1 = -F2
//   r = R_E^T (psi2 - psi1),        dw = R_E^T (w2 - w1)
//   M_E = -(kr .* r + cr .* dw),                  M2 = R_E M_E,  M1 = -M2 - (p2-p1) x F2
// Rotations use the additive rotation vectors psi of the markers (LOF rotation
// plus small modal rotation), valid for small relative rotation off the spin
// axis. The element frame R_E is held at its reference orientation for the
// derivatives (R_E varies only with the LOF spin, which is prescribed).
#pragma once

#include "model/element.h"

namespace evas {

class SpringDamper : public Element {
 public:
  SpringDamper(std::string name, std::vector<int> markers, const Vec3& k, const Vec3& c,
               const Vec3& kr, const Vec3& cr, const Vec3& l0, const Vec3& preload);
  std::string type() const override { return "spring-damper"; }
  bool needs_rotation(std::size_t) const override {
    return (kr_.array() != 0.0).any() || (cr_.array() != 0.0).any();
  }
  void evaluate(double t, const MarkerMotion* m, MarkerLoad* loads) const override;
  void derivatives(double t, const MarkerMotion* m, Mat& D) const override;
  std::vector<Channel> channels() const override;
  void channel_values(double t, const MarkerMotion* m, double* out) const override;

 private:
  Vec3 k_, c_, kr_, cr_, l0_, preload_;
};

}  // namespace evas
