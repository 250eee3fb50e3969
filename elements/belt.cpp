#include "elements/belt.h"

#include <cmath>
#include <memory>
#include <sstream>

namespace evas {

Belt::Belt(std::string name, std::vector<int> markers, double tension, std::vector<double> radii,
           const Vec3& normal, std::vector<int> order, int frame_marker, const Vec3& reference)
    : Element(std::move(name), std::move(markers)),
      T_(tension),
      r_(std::move(radii)),
      n_(normal),
      ref_(reference),
      order_(std::move(order)),
      frame_(frame_marker) {
  const std::string where = "element '" + this->name() + "'";
  const int k = static_cast<int>(this->markers().size());
  if (k < 2)
    throw InputError(where + ": a belt needs at least 2 pulley markers, got " + std::to_string(k));
  if (static_cast<int>(r_.size()) != k)
    throw InputError(where + ": 'radii' has " + std::to_string(r_.size()) + " values for " +
                     std::to_string(k) + " pulley markers");
  if (order_.empty())
    for (int i = 0; i < k; ++i) order_.push_back(i);
  if (static_cast<int>(order_.size()) != k)
    throw InputError(where + ": 'order' has " + std::to_string(order_.size()) + " entries for " +
                     std::to_string(k) + " pulley markers");
  std::vector<char> seen(k, 0);
  for (int i : order_) {
    if (i < 0 || i >= k || seen[i])
      throw InputError(where + ": 'order' must list each pulley index 0.." + std::to_string(k - 1) +
                       " once");
    seen[i] = 1;
  }
  if (frame_ < -1 || frame_ >= k)
    throw InputError(where + ": 'frame_marker' must be -1 (ground axes) or 0.." +
                     std::to_string(k - 1));
  if (!(n_.norm() > 0.0)) throw InputError(where + ": 'normal' must not be zero");
  n_.normalize();
  if (ref_.norm() > 0.0 && ref_.cross(n_).norm() < 1e-6 * ref_.norm())
    throw InputError(where + ": 'reference' must not be parallel to 'normal'");
}

void Belt::frame(const MarkerMotion* m, Vec3& n, Vec3& xref) const {
  const Mat3 R = frame_ < 0 ? Mat3::Identity() : m[frame_].R;
  const Vec3 nl = n_;
  Vec3 rl = ref_;
  if (!(rl.norm() > 0.0)) {
    // Automatic: the frame axis most nearly perpendicular to the normal.
    Eigen::Index i = 0;
    nl.cwiseAbs().minCoeff(&i);
    rl = Vec3::Unit(i);
  }
  n = R * nl;
  xref = R * (rl - nl * nl.dot(rl));
  xref.normalize();
}

void Belt::span(const Vec3& n, const Vec3& ci, const Vec3& cj, double ri, double rj, Vec3& u,
                double& L, Mat3* dU) const {
  const Vec3 d = (cj - ci) - n * n.dot(cj - ci);
  const double D = d.norm();
  const double b = D > 0.0 ? (rj - ri) / D : 2.0;
  if (!(std::abs(b) < 1.0)) {
    std::ostringstream os;
    os << "element '" << name() << "': pulleys at (" << ci.transpose() << ") and ("
       << cj.transpose() << ") with radii " << ri << ", " << rj
       << " m have no common tangent (centre distance " << D << " m in the belt plane)";
    throw RangeError(os.str());
  }
  const double a = std::sqrt(1.0 - b * b);
  const Vec3 e = d / D;
  const Vec3 f = e.cross(n);
  u = a * e + b * f;
  L = a * D;
  if (dU) {
    const Mat3 N = skew(n);
    const Mat3 ee = e * e.transpose();
    const Mat3 P = Mat3::Identity() - n * n.transpose();
    *dU = ((b * b / a) * ee + b * N * ee + (a * Mat3::Identity() - b * N) * (P - ee)) / D;
  }
}

void Belt::evaluate(double, const MarkerMotion* m, MarkerLoad* loads) const {
  const int k = static_cast<int>(order_.size());
  Vec3 n, xref;
  frame(m, n, xref);
  for (int i = 0; i < k; ++i) {
    loads[i].F.setZero();
    loads[i].M.setZero();
  }
  for (int s = 0; s < k; ++s) {
    const int i = order_[s], j = order_[(s + 1) % k];
    Vec3 u;
    double L;
    span(n, m[i].p, m[j].p, r_[i], r_[j], u, L, nullptr);
    loads[i].F += T_ * u;
    loads[j].F -= T_ * u;
  }
}

void Belt::derivatives(double, const MarkerMotion* m, Mat& D) const {
  const int k = static_cast<int>(order_.size());
  Vec3 n, xref;
  frame(m, n, xref);
  D.setZero();
  for (int s = 0; s < k; ++s) {
    const int i = order_[s], j = order_[(s + 1) % k];
    Vec3 u;
    double L;
    Mat3 dU;
    span(n, m[i].p, m[j].p, r_[i], r_[j], u, L, &dU);
    const Mat3 G = T_ * dU;  // d(T u)/dc_j = G, d(T u)/dc_i = -G
    D.block<3, 3>(6 * i, 12 * j) += G;
    D.block<3, 3>(6 * i, 12 * i) -= G;
    D.block<3, 3>(6 * j, 12 * j) -= G;
    D.block<3, 3>(6 * j, 12 * i) += G;
  }
}

std::vector<Channel> Belt::channels() const {
  std::vector<Channel> c;
  const int k = static_cast<int>(order_.size());
  for (int p = 0; p < k; ++p) {
    c.push_back({"pulley" + std::to_string(p) + "_fx", "N"});
    c.push_back({"pulley" + std::to_string(p) + "_fy", "N"});
  }
  for (int s = 0; s < k; ++s) {
    c.push_back({"span" + std::to_string(s) + "_angle", "rad"});
    c.push_back({"span" + std::to_string(s) + "_length", "m"});
  }
  return c;
}

void Belt::channel_values(double, const MarkerMotion* m, double* out) const {
  const int k = static_cast<int>(order_.size());
  Vec3 n, xref;
  frame(m, n, xref);
  const Vec3 yref = n.cross(xref);
  for (int p = 0; p < k; ++p) out[2 * p] = out[2 * p + 1] = 0.0;
  for (int s = 0; s < k; ++s) {
    const int i = order_[s], j = order_[(s + 1) % k];
    Vec3 u;
    double L;
    span(n, m[i].p, m[j].p, r_[i], r_[j], u, L, nullptr);
    const double ux = T_ * u.dot(xref), uy = T_ * u.dot(yref);
    out[2 * i] += ux;
    out[2 * i + 1] += uy;
    out[2 * j] -= ux;
    out[2 * j + 1] -= uy;
    out[2 * k + 2 * s] = std::atan2(u.dot(yref), u.dot(xref));
    out[2 * k + 2 * s + 1] = L;
  }
}

ElementType belt_element_type() {
  using K = ParamSpec::Kind;
  ElementType t;
  t.type = "belt";
  t.doc =
      "Belt with constant tension T_B over k >= 2 pulleys (paper 3.2, Fig. 8); markers = pulley "
      "centres in any number (num_markers 0 = variable). Free spans are the common tangents for "
      "signed radii (r > 0: wrapped counter-clockwise about the normal). Force on pulley i: "
      "T_B (u_out + u_in'), the unit span vectors pointing away from it; no moments (constant "
      "tension).";
  t.num_markers = 0;
  t.params = {
      vector_param("tension", K::Scalar, "N", "belt tension T_B", {}, 0.0, true),
      vector_param("radii", K::List, "m",
                   "signed pitch radius per pulley marker (negative: wrapped clockwise about the "
                   "normal, e.g. a back-side idler)",
                   {}, -1e300, true),
      vector_param("normal", K::Vector3, "-", "belt plane normal (frame_marker's axes)", {}, -1e300,
                   true),
      vector_param("order", K::List, "-",
                   "wrap order: pulley indices 0..k-1 into the marker list (empty = marker order)",
                   {}),
      vector_param("frame_marker", K::Scalar, "-",
                   "index of the marker whose axes carry normal and reference (-1 = ground axes)",
                   {-1.0}, -1.0),
      vector_param("reference", K::Vector3, "-",
                   "in-plane x axis for the output components and span angles (0 = automatic)",
                   {0.0, 0.0, 0.0}),
  };
  t.make = [](const std::string& name, const std::vector<int>& markers,
              const ParamValues& v) -> std::unique_ptr<Element> {
    const std::string where = "element '" + name + "'";
    std::vector<int> order;
    for (double x : v.list("order")) {
      if (x != std::floor(x))
        throw InputError(where + ": 'order' entries must be whole pulley indices");
      order.push_back(static_cast<int>(x));
    }
    const double fm = v.scalar("frame_marker");
    if (fm != std::floor(fm))
      throw InputError(where + ": 'frame_marker' must be a whole marker index or -1");
    return std::make_unique<Belt>(name, markers, v.scalar("tension"), v.list("radii"),
                                  v.vec3("normal"), order, static_cast<int>(fm),
                                  v.vec3("reference"));
  };
  return t;
}

}  // namespace evas
