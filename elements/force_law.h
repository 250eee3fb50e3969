// One-dimensional nonlinear force-deflection laws for the engine mount and the
// thrust bearing (paper section 3.2: "a nonlinear spring and damper").
//
// ForceLaw f(d), the restoring force at deflection d [m] -> [N]:
//   polynomial  f(d) = k1 d + k2 d^2 + k3 d^3 + ...   (no constant term: f(0) = 0)
//   table       pairs (d_i, f_i), d strictly increasing, at least two pairs;
//               interpolation either
//                 linear: piecewise linear, or
//                 pchip:  monotone piecewise cubic Hermite (Fritsch-Carlson /
//                         Fritsch-Butland): interior slopes are the weighted
//                         harmonic mean of the neighbouring secants (zero where
//                         the secants change sign), end slopes the end secants.
//                         A monotone table gives a monotone, C1 law.
//               Outside the table the law is extended linearly with the end
//               slope (linear: last segment's secant; pchip: end node slope),
//               so value and slope are continuous at the table ends.
// value() and slope() are exact derivatives of each other (the tests check
// this against central differences).
//
// ClearanceLaw g(d): a symmetric dead band of half-width `gap` around d = 0
// with the law applied to the penetration beyond it,
//   e = |d| - gap,   g(d) = sign(d) f(rho(e)),
//   rho(e) = 0                      e <= 0
//          = 2 e^2 / w - e^3 / w^2  0 < e < w        (w = smoothing width)
//          = e                      e >= w
// rho is C1 (rho(0) = rho'(0) = 0, rho(w) = w, rho'(w) = 1) and rho(e) <= e,
// so the force is exactly zero inside the gap, exactly f(e) beyond gap + w and
// the stiffness g'(d) = f'(rho) rho' is continuous: Newton-based integrators
// see no jump in the Jacobian when contact opens or closes. With w = 0 the
// transition is sharp (rho = max(e, 0)); the stiffness then jumps from 0 to
// f'(0) at |d| = gap, and exactly at the edge the gap-side value (0) is used.
// A contact fraction chi(d) in [0, 1] (smoothstep over the same band, a step
// for w = 0) blends contact-only damping in and out.
// The law should satisfy f(0) = 0 (checked by the thrust bearing), otherwise
// the force jumps at contact.
#pragma once

#include <string>
#include <vector>

#include "model/types.h"

namespace evas {

class ForceLaw {
 public:
  enum class Kind { Polynomial, Table };
  enum class Interp { Linear, Pchip };

  ForceLaw() = default;  ///< zero law
  /// f(d) = sum_k coeffs[k] d^(k+1).
  static ForceLaw polynomial(std::vector<double> coeffs);
  /// Table of (d_i, f_i); throws InputError prefixed with `where` if d is not
  /// strictly increasing, fewer than two points or sizes differ.
  static ForceLaw table(std::vector<double> d, std::vector<double> f, Interp interp,
                        const std::string& where = "force law");
  /// Table from flattened pairs d0, f0, d1, f1, ...
  static ForceLaw table_pairs(const std::vector<double>& pairs, Interp interp,
                              const std::string& where = "force law");
  /// "linear" or "pchip" (throws InputError otherwise).
  static Interp interp_from_name(const std::string& name, const std::string& where);

  double value(double d) const;
  double slope(double d) const;
  /// Value and slope at once.
  void eval(double d, double& f, double& df) const;

  Kind kind() const { return kind_; }
  /// Largest |f| over the table points or the polynomial's coefficients (for scaling).
  double scale() const;

 private:
  Kind kind_ = Kind::Polynomial;
  Interp interp_ = Interp::Pchip;
  std::vector<double> c_;      // polynomial coefficients k1, k2, ...
  std::vector<double> x_, y_;  // table
  std::vector<double> m_;      // table node slopes (Hermite tangents)
};

class ClearanceLaw {
 public:
  ClearanceLaw() = default;
  /// Throws InputError prefixed with `where` for gap < 0 or smoothing < 0.
  ClearanceLaw(ForceLaw law, double gap, double smoothing, const std::string& where = "clearance");

  /// g(d) and g'(d).
  void eval(double d, double& g, double& dg) const;
  /// Contact fraction chi(d) in [0, 1] and its derivative.
  void contact(double d, double& chi, double& dchi) const;
  /// Penetration smoothing rho(e) and rho'(e) (exposed for tests).
  void smooth(double e, double& rho, double& drho) const;

  double gap() const { return gap_; }
  double smoothing() const { return w_; }
  const ForceLaw& law() const { return law_; }

 private:
  ForceLaw law_;
  double gap_ = 0.0, w_ = 0.0;
};

/// Builds a law from element parameters: `kind` "polynomial" uses `coeffs`
/// (k1, k2, ...), "table" uses `pairs` (d0, f0, d1, f1, ...) with `interp`
/// "linear" or "pchip". A table given with kind "polynomial" is an error (it
/// would be ignored silently). Errors name `where`.
ForceLaw make_force_law(const std::string& kind, const std::vector<double>& coeffs,
                        const std::vector<double>& pairs, const std::string& interp,
                        const std::string& where);

}  // namespace evas
