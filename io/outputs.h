// Output channels and output times of a run (from a scene's OutputSpec).
//
// Channels, in the order the scene lists them:
//   {marker: m}    m.px m.py m.pz [m], m.vx m.vy m.vz [m/s]   (G components)
//   {element: e}   e.<channel> for every channel the element declares
//   {modal: b}     b.q<k> for every mode k of body b (modal coordinate)
//   {torsion: [A, B], name: N}  torsional vibration within one body, about the
//                  twist axis n (in the body's axes; by default its LOF's spin
//                  axis), relative to the LOF: N.angle_a, N.angle_b [rad] =
//                  n . (B_theta q) of marker A and B (the rotation of the
//                  marker's rigid fit), N.twist = angle_b - angle_a [rad], and
//                  N.rate_a, N.rate_b, N.twist_rate [rad/s] the same with v
//   {surface: S, body: B, name: N}  normal velocity and ERP of node set S of
//                  body B (model/surface.h): N.vn_mean, N.vn_rms [m/s], N.erp,
//                  N.erp_elastic, N.erp_rigid [W], components N.c<k> [W^0.5]
//                  (ERP = sum c_k^2) and N.e<k> (ERP_elastic = sum e_k^2), with
//                  per_node
//                  N.vn_<node id> [m/s]
// On the crank-angle grid a first channel "crank_angle" [deg] holds the LOF
// spin angle of the crank body.
// A constrained system (Problem::constraint_count() > 0) adds, after those, per
// constraint equation c (named by Problem::constraint_name): c.g = g(t, q) and
// c.g_dot = G v + g_t (units of the constraint), and with
// add_multiplier_channels() c.lambda, the multiplier.
//
// Output times: uniform in time (start, start + step, ... <= t_end) or the
// times at which the crank body's spin angle reaches multiples of `step`
// degrees (found by bracketing and bisection, so speed profiles work too).
#pragma once

#include <tuple>
#include <vector>

#include "io/scene.h"
#include "model/element.h"
#include "model/surface.h"
#include "solver/system.h"

namespace evas {

class OutputSet {
 public:
  OutputSet(const OutputSpec& spec, System& system, double t_start, double t_end);

  const std::vector<Channel>& channels() const { return channels_; }
  int size() const { return static_cast<int>(channels_.size()); }
  /// Output times, ascending, within [t_start, t_end].
  const std::vector<double>& times() const { return times_; }

  /// Appends a channel c.lambda per constraint equation (call before the
  /// channels are used; no-op without constraints).
  void add_multiplier_channels();
  bool has_multiplier_channels() const { return lambda_first_ >= 0; }

  /// Channel values at (t, q, v) and, with multiplier channels, the multipliers
  /// `lambda` (m values); `out` has size(). Updates the system's markers.
  void values(double t, const double* q, const double* v, double* out,
              const double* lambda = nullptr);
  /// The crank-angle channel alone at time t [deg] (it is kinematic: the crank
  /// body's LOF), without evaluating any element; requires the crank-angle grid.
  double crank_angle(double t) const;
  bool has_crank_angle() const { return crank_body_ >= 0; }

 private:
  struct Source {
    ChannelRequest::Kind kind;
    int index;            // marker, element or body
    int first;            // first channel
    unsigned quantities;  // marker: ChannelRequest::Quantity bits
    bool local;           // marker: components in its own axes
    int torsion = -1;     // torsion: index into torsion_
    int surface = -1;     // surface: index into surfaces_
  };
  std::vector<SurfaceRadiation> surfaces_;
  // A torsion request: the body's coordinates from `offset`, and the rows
  // n^T B_theta of its two markers (angle = row . q).
  struct Torsion {
    int offset = 0;
    Vec a, b;
  };
  std::vector<Torsion> torsion_;
  bool accelerations_ = false;  // a marker's (angular) acceleration is asked for
  System& sys_;
  std::vector<Channel> channels_;
  std::vector<Source> sources_;
  std::vector<int> markers_;  // the markers whose motion the channels read (ascending)
  std::vector<double> times_;
  int crank_body_ = -1;                            // >= 0: channel 0 is the crank angle
  int constraint_first_ = -1, lambda_first_ = -1;  // >= 0: first g / lambda channel
  std::vector<double> gbuf_, gvbuf_;
  std::vector<MarkerMotion> scratch_;
};

/// The quantities of a marker request in channel order: (bit, name prefix, unit):
/// p [m], v [m/s], a [m/s^2], w [rad/s], al [rad/s^2]; channels are
/// MARKER.<prefix><x|y|z>, with the suffix _local in the marker's own axes.
const std::vector<std::tuple<unsigned, const char*, const char*>>& marker_quantities();

/// Most output rows a grid may give (1e8: 8 GB per 10 channels).
constexpr double kMaxOutputRows = 1e8;
/// Throws InputError naming the grid when `rows` (may be huge or not finite)
/// exceeds kMaxOutputRows: checked before any time is computed.
void check_output_rows(double rows, const char* grid);

/// Times in [t0, t1] where the spin angle of `lof` (in degrees) reaches
/// start_deg + k step_deg (start_given) or a multiple of step_deg, in the
/// direction the angle moves. Ascending; the angle is assumed monotonic.
std::vector<double> crank_angle_times(const Lof& lof, double t0, double t1, double step_deg,
                                      double start_deg, bool start_given);

}  // namespace evas
