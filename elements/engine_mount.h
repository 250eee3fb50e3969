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
//
// Maxwell branch (optional, beyond the paper): per mount axis i with
// maxwell_stiffness k2_i > 0, a spring k2_i in series with a dashpot c2_i, in
// parallel with the law: the standard linear solid (Zener) of viscoelastic
// mounts (Lakes, Viscoelastic Materials, Cambridge 2009, ch. 2), whose dynamic
// stiffness k + k2 i w tau / (1 + i w tau), tau = c2 / k2, rises with frequency
// as that of rubber and hydraulic mounts does (Yu, Naganathan & Dukkipati,
// Mech. Mach. Theory 36 (2001) 123-142). Its state z_i (the dashpot's end,
// mount axes) is an element internal state:
//   F_E,i += -k2_i (d_i - z_i),     z_i' = (k2_i / c2_i) (d_i - z_i).
// It starts unloaded (z = d). The z-free evaluate() and channel_values() take
// the branch unloaded (z = d).
#pragma once

#include <array>

#include "elements/force_law.h"
#include "elements/registry.h"
#include "model/element.h"

namespace evas {

class EngineMount : public Element {
 public:
  bool needs_rotation(std::size_t) const override {
    return (kr_.array() != 0.0).any() || (cr_.array() != 0.0).any();
  }
  /// Rotations only with rotational stiffness or damping (kr, cr).
  unsigned motion_reads(std::size_t slot) const override {
    return kReadsTranslation | (needs_rotation(slot) ? kReadsRotation : 0u);
  }
  /// The block (marker 1) takes a moment only with kr, cr; the support always
  /// (the force's lever arm p1 - p0).
  unsigned load_parts(std::size_t slot) const override {
    return kLoadsForce | (slot == 0 || needs_rotation(slot) ? kLoadsMoment : 0u);
  }
  EngineMount(std::string name, std::vector<int> markers, std::array<ForceLaw, 3> laws,
              const Vec3& damping, const Vec3& preload, const Vec3& rot_stiffness,
              const Vec3& rot_damping, const Vec3& orientation = Vec3::Zero(),
              const Vec3& offset = Vec3::Zero(), const Vec3& maxwell_stiffness = Vec3::Zero(),
              const Vec3& maxwell_damping = Vec3::Zero());
  std::string type() const override { return "engine-mount"; }
  void evaluate(double t, const MarkerMotion* m, MarkerLoad* loads) const override;
  void derivatives(double t, const MarkerMotion* m, Mat& D) const override;
  /// fx, fy, fz [N] (load on the block, mount axes), mx, my, mz [N m], dx, dy, dz [m].
  std::vector<Channel> channels() const override;
  void channel_values(double t, const MarkerMotion* m, double* out) const override;

  // Maxwell branches: one differential state per branched axis.
  int internal_count() const override { return static_cast<int>(branch_.size()); }
  std::string internal_name(int i) const override;
  void internal_initial(double t, const MarkerMotion* m, double* z) const override;
  void evaluate_z(double t, const MarkerMotion* m, const double* z,
                  MarkerLoad* loads) const override;
  void derivatives_z(double t, const MarkerMotion* m, const double* z, Mat& D) const override;
  /// ... plus maxwell_f<axis> [N] (branch force on the block) and z_<axis> [m] per branch.
  void channel_values_z(double t, const MarkerMotion* m, const double* z,
                        double* out) const override;
  void internal_rate(double t, const MarkerMotion* m, const double* z, double* h) const override;
  void internal_derivatives(double t, const MarkerMotion* m, const double* z, Mat& Dz, Mat& Hm,
                            Mat& Hz) const override;

 private:
  std::array<ForceLaw, 3> laws_;
  Vec3 c_, preload_, kr_, cr_, offset_, k2_, c2_;
  Mat3 R_ME_;                // mount axes in marker 0's axes
  std::vector<int> branch_;  // mount axis of each Maxwell state
  /// Deflection d (mount axes) and R_E.
  Vec3 deflection(const MarkerMotion* m, Mat3& R) const;
  /// z, or d on the branched axes when z is null (branch unloaded).
  void states_or_unloaded(const MarkerMotion* m, const double* z, double* out) const;
};

/// Declaration of "engine-mount" (2 markers: support, block).
ElementType engine_mount_element_type();

}  // namespace evas
