// Engine mount (paper section 3.2: "the support force of engine mounts ... a
// nonlinear spring and damper"; formulation.md section 5).
//
// Markers: 0 = the support side (ground or a frame/subframe body), 1 = the
// engine block. The mount axes E are marker 0's axes turned by the rotation
// vector `orientation` (given in marker 0's axes): R_E = R_0 rot(orientation).
//   d  = R_E^T (p1 - p0) - offset        deflection per mount axis [m]
//   dv = R_E^T (v1 - v0)                 deflection rate [m/s]
//   F_E,i = preload_i - f_i(d_i) - c_i dv_i     (i = x, y, z; f_i a ForceLaw)
//   r  = R_E^T (psi1 - psi0),  dw = R_E^T (w1 - w0)
//   M_E = -(kr .* r + cr .* dw)
//   F1 = R_E F_E,  M1 = R_E M_E           load on the block (marker 1)
//   F0 = -F1,      M0 = -M1 - (p1 - p0) x F1   reaction (balances force and moment)
// `preload` is the force the mount exerts on the block at zero deflection (mount
// axes): with the block's weight shared as preload_z = m g / n_mounts the engine
// sits at its reference position under gravity, and f_i(d) describes the
// deflection about that static point. With zero preload the block sags until
// the law carries the weight.
// The rotation terms use the additive rotation vectors psi (small relative
// rotation). R_E is held fixed in the derivatives (it moves only with marker
// 0's LOF, which is prescribed), as in the spring-damper.
#pragma once

#include <array>

#include "elements/element.h"
#include "elements/force_law.h"
#include "elements/registry.h"

namespace evas {

class EngineMount : public Element {
 public:
  bool needs_rotation(std::size_t) const override {
    return (kr_.array() != 0.0).any() || (cr_.array() != 0.0).any();
  }
  EngineMount(std::string name, std::vector<int> markers, std::array<ForceLaw, 3> laws,
              const Vec3& damping, const Vec3& preload, const Vec3& rot_stiffness,
              const Vec3& rot_damping, const Vec3& orientation = Vec3::Zero(),
              const Vec3& offset = Vec3::Zero());
  std::string type() const override { return "engine-mount"; }
  void evaluate(double t, const MarkerMotion* m, MarkerLoad* loads) const override;
  void derivatives(double t, const MarkerMotion* m, Mat& D) const override;
  /// fx, fy, fz [N] (load on the block, mount axes), mx, my, mz [N m], dx, dy, dz [m].
  std::vector<Channel> channels() const override;
  void channel_values(double t, const MarkerMotion* m, double* out) const override;

 private:
  std::array<ForceLaw, 3> laws_;
  Vec3 c_, preload_, kr_, cr_, offset_;
  Mat3 R_ME_;  // mount axes in marker 0's axes
};

/// Declaration of "engine-mount" (2 markers: support, block).
ElementType engine_mount_element_type();

}  // namespace evas
