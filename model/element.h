// Force elements: read marker motion, return loads on the markers.
//
// An element with k markers returns one MarkerLoad per marker and, for the
// Jacobian, the 6k x 12k matrix D = d(loads)/d(motion) where the loads of
// marker i are rows [6i, 6i+6) = (F, M) and the motion of marker j columns
// [12j, 12j+12) = (p, v, psi, w). Elements supply D analytically; the base
// class offers a central finite-difference version used as fallback and as the
// reference in tests.
#pragma once

#include <string>
#include <vector>

#include "model/marker.h"
#include "model/speed_profile.h"

namespace evas {

struct Channel {
  std::string name;  ///< e.g. "force_x"
  std::string unit;  ///< e.g. "N"
};

class Element {
 public:
  virtual ~Element() = default;

  const std::string& name() const { return name_; }
  virtual std::string type() const = 0;
  /// Indices of the markers this element attaches to (into the model's marker list).
  const std::vector<int>& markers() const { return markers_; }

  /// Loads on the markers (size k) at time t.
  virtual void evaluate(double t, const MarkerMotion* motion, MarkerLoad* loads) const = 0;
  /// D = d(loads)/d(motion), 6k x 12k, preallocated by the caller.
  virtual void derivatives(double t, const MarkerMotion* motion, Mat& D) const;
  /// True if the loads depend on marker motion (false: explicit in time).
  virtual bool state_dependent() const { return true; }
  /// True if the element reads the rotation (psi, w) of the marker in `slot` or
  /// puts a moment on it: such a marker must carry a rotation (a node set that is
  /// not collinear, or ground). Model::add_element rejects a mismatch, so that no
  /// moment is dropped silently.
  virtual bool needs_rotation(std::size_t slot) const {
    (void)slot;
    return false;
  }

  /// What the loads read of the motion of the marker in `slot`: kReadsTranslation
  /// (p, v, a), kReadsRotation (psi, w, al), both or neither (the marker axes R come
  /// from the body's frame and are always current). System::force() computes only
  /// what some element reads: a field no element declares is not current there.
  /// Default: both.
  static constexpr unsigned kReadsTranslation = 1, kReadsRotation = 2;
  virtual unsigned motion_reads(std::size_t slot) const {
    (void)slot;
    return kReadsTranslation | kReadsRotation;
  }
  /// What the loads put on the marker in `slot`: kLoadsForce (F), kLoadsMoment
  /// (M), both or neither. System::force() maps back only what some element
  /// declares: a part the declaration leaves out is dropped there (the residual
  /// from every row, which tests compare, keeps it). Default: both.
  static constexpr unsigned kLoadsForce = 1, kLoadsMoment = 2;
  virtual unsigned load_parts(std::size_t slot) const {
    (void)slot;
    return kLoadsForce | kLoadsMoment;
  }

  /// Inertial loads (beyond the paper; e.g. the coupled piston's reciprocating
  /// mass). An element of rank r > 0 has loads that are affine in the marker
  /// accelerations (MarkerMotion::a, al) about the values it is evaluated at:
  ///     loads(acc') = loads(acc) + P Q^T (acc' - acc),
  /// P, Q: 6k x r, P's rows (F, M) and Q's rows (a, al) of marker i at 6i.
  /// The System solves these accelerations together with the modal ones
  /// (System::force). derivatives() is then taken at fixed accelerations.
  virtual int inertia_rank() const { return 0; }
  virtual void inertia(double t, const MarkerMotion* m, Mat& P, Mat& Q) const {
    (void)t;
    (void)m;
    P.setZero();
    Q.setZero();
  }
  /// True if P depends on the accelerations (piecewise-affine loads): the System
  /// then re-linearises at the solved accelerations until they settle.
  virtual bool inertia_piecewise() const { return false; }

  /// Internal states (beyond the paper; issue: element states as DAE variables).
  /// An element may carry nz = internal_count() first-order states z of its own,
  /// each differential (z_i' = h_i) or algebraic (0 = h_i, e.g. the speed of a
  /// massless disk, whose torque balance replaces Newton's law). The System
  /// places them after the modal coordinates (Problem::internal_count()); only
  /// integrators that declare Integrator::takes_internal_states() run them.
  /// An element without states keeps the z-free functions above; the *_z
  /// versions below default to them, so such an element needs nothing new.
  virtual int internal_count() const { return 0; }
  virtual bool internal_algebraic(int i) const {
    (void)i;
    return false;
  }
  /// Short name of state i for messages and outputs, e.g. "z_x" (default "z<i>").
  virtual std::string internal_name(int i) const;
  /// Initial states at the initial motion; algebraic ones consistent (h = 0).
  virtual void internal_initial(double t, const MarkerMotion* m, double* z) const {
    (void)t;
    (void)m;
    (void)z;
  }
  /// Loads, derivatives and channels at states z (internal_count() values).
  virtual void evaluate_z(double t, const MarkerMotion* m, const double* z,
                          MarkerLoad* loads) const {
    (void)z;
    evaluate(t, m, loads);
  }
  virtual void derivatives_z(double t, const MarkerMotion* m, const double* z, Mat& D) const {
    (void)z;
    derivatives(t, m, D);
  }
  virtual void channel_values_z(double t, const MarkerMotion* m, const double* z,
                                double* out) const {
    (void)z;
    channel_values(t, m, out);
  }
  /// h(t, motion, z) (nz values): z' = h for differential, 0 = h for algebraic states.
  virtual void internal_rate(double t, const MarkerMotion* m, const double* z, double* h) const {
    (void)t;
    (void)m;
    (void)z;
    (void)h;
  }
  /// Analytic derivatives, preallocated by the caller: Dz = d(loads)/dz (6k x nz),
  /// Hm = dh/d(motion) (nz x 12k, columns as in D), Hz = dh/dz (nz x nz).
  virtual void internal_derivatives(double t, const MarkerMotion* m, const double* z, Mat& Dz,
                                    Mat& Hm, Mat& Hz) const {
    (void)t;
    (void)m;
    (void)z;
    Dz.setZero();
    Hm.setZero();
    Hz.setZero();
  }
  /// Central finite differences of the same three (reference in tests).
  void internal_derivatives_fd(double t, const MarkerMotion* m, const double* z, Mat& Dz, Mat& Hm,
                               Mat& Hz) const;

  /// Output channels and their values at the given motion.
  virtual std::vector<Channel> channels() const = 0;
  virtual void channel_values(double t, const MarkerMotion* motion, double* out) const = 0;

  /// Finite-difference D (central differences, step scaled by the motion).
  void derivatives_fd(double t, const MarkerMotion* motion, Mat& D) const;

  /// Why the element, as configured, cannot take part in a run (a model meant
  /// for a static answer only), or empty when it can. The scene reader refuses
  /// such an element with this text.
  virtual std::string run_refusal() const { return {}; }

  // --- The crank's speed (an operating point stated once) ---
  // An element that prescribes a crank speed (a piston in mode prescribed, the
  // motor's driver) either gives its own `speed` or follows the crank: the
  // scene reader hands it the speed profile of the one body with a spin LOF,
  // and refuses a scene whose own speeds disagree with the crank's.
  /// The speed the element prescribes by itself (its `speed` parameter), or
  /// null when it prescribes none or follows the crank.
  virtual const SpeedProfile* own_speed() const { return nullptr; }
  /// True when the element needs a crank speed and was given none.
  virtual bool wants_speed() const { return false; }
  /// Follow `crank` (angle turned since t = 0, speed, acceleration). Throws
  /// InputError when the element cannot (e.g. a constant-speed approximation
  /// under a varying speed).
  virtual void follow_speed(const SpeedProfile& crank) { (void)crank; }

  // --- The engine's load (operating_point.load, stated once in the scene) ---
  // An element whose data depend on the engine load (a prescribed piston whose
  // pressure map has a load column) says what reads it; the scene reader hands
  // it the scene's load, refuses a scene that gives none, and refuses a load
  // that no element reads (it would be ignored without a word).
  /// What reads the load (e.g. "pressure map FILE"), empty when nothing does.
  virtual std::string load_source() const { return {}; }
  /// The scene's load, constant over the run. Throws InputError when the
  /// element's data do not reach it.
  virtual void set_operating_load(double load) { (void)load; }

 protected:
  Element(std::string name, std::vector<int> markers)
      : name_(std::move(name)), markers_(std::move(markers)) {}

 private:
  std::string name_;
  std::vector<int> markers_;
};

}  // namespace evas
