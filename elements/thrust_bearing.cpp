#include "elements/thrust_bearing.h"

#include <algorithm>
#include <cmath>
#include <memory>

namespace evas {

ThrustBearing::ThrustBearing(std::string name, std::vector<int> markers, ClearanceLaw law,
                             double damping, bool damp_always, const Vec3& axis, double offset)
    : Element(std::move(name), std::move(markers)),
      law_(std::move(law)),
      c_(damping),
      always_(damp_always),
      axis_(axis),
      offset_(offset) {
  if (!(axis_.norm() > 0.0))
    throw InputError("element '" + this->name() + "': axis must not be zero");
  axis_.normalize();
}

void ThrustBearing::axial(double d, double dv, double& F, double& dFdd, double& dFdv) const {
  double g, dg, chi = 1.0, dchi = 0.0;
  law_.eval(d, g, dg);
  if (!always_) law_.contact(d, chi, dchi);
  F = -(g + c_ * chi * dv);
  dFdd = -(dg + c_ * dchi * dv);
  dFdv = -c_ * chi;
}

void ThrustBearing::evaluate(double, const MarkerMotion* m, MarkerLoad* loads) const {
  const Vec3 a = m[0].R * axis_;
  const Vec3 dp = m[1].p - m[0].p;
  double F, dFdd, dFdv;
  axial(a.dot(dp) - offset_, a.dot(m[1].v - m[0].v), F, dFdd, dFdv);
  const Vec3 F1 = F * a;
  loads[1].F = F1;
  loads[1].M.setZero();
  loads[0].F = -F1;
  loads[0].M = -dp.cross(F1);
}

void ThrustBearing::derivatives(double, const MarkerMotion* m, Mat& D) const {
  const Vec3 a = m[0].R * axis_;
  const Vec3 dp = m[1].p - m[0].p;
  double F, dFdd, dFdv;
  axial(a.dot(dp) - offset_, a.dot(m[1].v - m[0].v), F, dFdd, dFdv);
  const Vec3 F1 = F * a;
  const Mat3 aa = a * a.transpose();
  D.setZero();
  for (int j = 0; j < 2; ++j) {
    const double s = j == 1 ? 1.0 : -1.0;
    const int c0 = 12 * j;
    D.block<3, 3>(6, c0) = s * dFdd * aa;      // dF1/dp_j
    D.block<3, 3>(6, c0 + 3) = s * dFdv * aa;  // dF1/dv_j
    D.block<3, 12>(0, c0) = -D.block<3, 12>(6, c0);
    D.block<3, 12>(3, c0) = -skew(dp) * D.block<3, 12>(6, c0);
    D.block<3, 3>(3, c0) += s * skew(F1);
  }
}

std::vector<Channel> ThrustBearing::channels() const {
  return {{"force", "N"}, {"displacement", "m"}, {"clearance", "m"}};
}

void ThrustBearing::channel_values(double, const MarkerMotion* m, double* out) const {
  const Vec3 a = m[0].R * axis_;
  const double d = a.dot(m[1].p - m[0].p) - offset_;
  double F, dFdd, dFdv;
  axial(d, a.dot(m[1].v - m[0].v), F, dFdd, dFdv);
  out[0] = F;
  out[1] = d;
  out[2] = law_.gap() - std::abs(d);
}

ElementType thrust_bearing_element_type() {
  using K = ParamSpec::Kind;
  ElementType t;
  t.type = "thrust-bearing";
  t.doc =
      "Thrust bearing (paper 3.2): axial constraint of the crankshaft (marker 1) in its housing "
      "(marker 0) with axial clearance. d = a.(p1 - p0) - offset along a = marker 0's `axis`; "
      "axial load on the shaft F = -(g(d) + c chi(d) dv), g = 0 for |d| <= gap, "
      "sign(d) f(|d| - gap) beyond (C1-smoothed over `smoothing`); chi = contact fraction "
      "(damping_mode contact) or 1 (always).";
  t.num_markers = 2;
  t.params = {
      vector_param("gap", K::Scalar, "m", "axial clearance on each side of the centred position",
                   {0.0}, 0.0),
      text_param("law", "contact force law", {"polynomial", "table"}, "polynomial"),
      vector_param(
          "stiffness", K::List, "N/m, N/m^2, N/m^3, ...",
          "contact law coefficients k1, k2, ... of the penetration |d| - gap (law: polynomial)",
          {0.0}),
      vector_param("table", K::List, "m, N",
                   "(penetration, force) pairs, penetration increasing, force 0 at penetration 0 "
                   "(law: table)",
                   {}),
      text_param("interpolation", "table interpolation (linear extrapolation beyond the ends)",
                 {"pchip", "linear"}, "pchip"),
      vector_param("smoothing", K::Scalar, "m",
                   "width of the C1 transition of force and damping at contact (0 = sharp edge)",
                   {0.0}, 0.0),
      vector_param("damping", K::Scalar, "N s/m", "axial damping", {0.0}, 0.0),
      text_param("damping_mode", "damping only in contact (blended by chi) or always",
                 {"contact", "always"}, "contact"),
      vector_param("axis", K::Vector3, "-", "bearing axis in marker 0's axes (normalised)",
                   {0.0, 0.0, 1.0}),
      vector_param("offset", K::Scalar, "m",
                   "axial position of marker 1 relative to marker 0 at the centre of the clearance",
                   {0.0}),
  };
  t.make = [](const std::string& name, const std::vector<int>& markers,
              const ParamValues& v) -> std::unique_ptr<Element> {
    const std::string where = "element '" + name + "'";
    ForceLaw law = make_force_law(v.text("law"), v.list("stiffness"), v.list("table"),
                                  v.text("interpolation"), where);
    const double f0 = law.value(0.0);
    if (std::abs(f0) > 1e-9 * std::max(1.0, law.scale()))
      throw InputError(where + ": contact law must give zero force at zero penetration, got " +
                       std::to_string(f0) + " N");
    return std::make_unique<ThrustBearing>(
        name, markers, ClearanceLaw(std::move(law), v.scalar("gap"), v.scalar("smoothing"), where),
        v.scalar("damping"), v.text("damping_mode") == "always", v.vec3("axis"),
        v.scalar("offset"));
  };
  return t;
}

}  // namespace evas
