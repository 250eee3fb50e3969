// Belt with constant tension over k pulleys (paper section 3.2, Fig. 8;
// formulation.md section 5).
//
// Markers: the pulley centres c_0 .. c_{k-1} (k >= 2; one of them the crank
// pulley). The belt lies in the plane through the centres with unit normal n
// (`normal`, in the axes of marker `frame_marker`, or ground axes when
// frame_marker = -1). The belt runs through the pulleys in the order `order`
// (a permutation of 0..k-1; default the marker order) and closes back to the
// first. Radii are signed: r > 0 wraps the pulley counter-clockwise about n
// (the belt's inner face on the pulley, the usual case for a loop listed
// counter-clockwise), r < 0 clockwise (e.g. a back-side idler), so the
// tangent between two pulleys of equal sign is the outer common tangent and
// between opposite signs the crossed one.
//
// Span from pulley i to the next pulley j, with d = P (c_j - c_i), P = I - n n^T,
// D = |d|, e = d / D, f = e x n:
//   b = (r_j - r_i) / D = sin(beta),  a = cos(beta) = sqrt(1 - b^2)
//   u = a e + b f                      unit direction of the free span, i -> j
// The tangent points are t_i = c_i + r_i w, t_j = c_j + r_j w with w = u x n,
// and the free span length is L = a D. (Equal radii: u = e, along the centre
// line. Unequal radii: u is turned from the centre line by
// beta = asin((r_j - r_i)/D).) D <= |r_j - r_i| has no tangent: RunError.
// Loads (tension T_B constant):
//   F_i = T_B (u_{i->next} - u_{prev->i}),   M_i = 0.
// The moments of the two span forces about the pulley centre are
// r_i w x (T u) = T r_i n for the outgoing span and -T r_i n for the incoming
// one: with constant tension they cancel exactly, so no moment is applied (the
// belt drive's torque transmission needs a tension difference, which this
// element does not model). Sum F_i = 0 and, for centres in the plane, the
// moments about any point cancel as well.
// Derivatives: with N = skew(n),
//   du/dd = (b^2/(a D)) e e^T + (b/D) N e e^T + (a I - b N)(I - e e^T)/D,
// du/dc_j = (du/dd) P = -du/dc_i; the plane (n) is held fixed.
#pragma once

#include "elements/registry.h"
#include "model/element.h"

namespace evas {

class Belt : public Element {
 public:
  /// order empty = marker order. frame_marker: index into `markers` whose axes carry
  /// normal and reference, or -1 for ground axes. reference zero = automatic.
  Belt(std::string name, std::vector<int> markers, double tension, std::vector<double> radii,
       const Vec3& normal, std::vector<int> order = {}, int frame_marker = -1,
       const Vec3& reference = Vec3::Zero());
  std::string type() const override { return "belt"; }
  /// The span tensions are forces on the pulleys' centres.
  unsigned load_parts(std::size_t) const override { return kLoadsForce; }
  void evaluate(double t, const MarkerMotion* m, MarkerLoad* loads) const override;
  void derivatives(double t, const MarkerMotion* m, Mat& D) const override;
  /// Per pulley p (marker order): pulley<p>_fx, pulley<p>_fy [N] in the belt frame
  /// (x_ref, y_ref = n x x_ref); per span s (order[s] -> order[s+1]): span<s>_angle
  /// [rad] = atan2(u.y_ref, u.x_ref), span<s>_length [m].
  std::vector<Channel> channels() const override;
  void channel_values(double t, const MarkerMotion* m, double* out) const override;

  /// Span geometry from pulley centre ci (radius ri) to cj (rj): unit direction u,
  /// free length L, and dU = du/d(cj - ci) (3x3, includes the projection P).
  /// Throws RunError (naming the element) when the pulleys admit no tangent.
  void span(const Vec3& n, const Vec3& ci, const Vec3& cj, double ri, double rj, Vec3& u, double& L,
            Mat3* dU) const;
  /// Belt plane normal and in-plane reference axis in G.
  void frame(const MarkerMotion* m, Vec3& n, Vec3& xref) const;

 private:
  double T_;
  std::vector<double> r_;
  Vec3 n_, ref_;
  std::vector<int> order_;
  int frame_;
};

/// Declaration of "belt" (num_markers = 0: any number >= 2 of pulley markers).
ElementType belt_element_type();

}  // namespace evas
