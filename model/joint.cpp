#include "model/joint.h"

#include <array>

#include "model/types.h"

namespace evas {

namespace {

struct TypeInfo {
  JointType type;
  const char* name;
  std::vector<std::string> rows;
};

const std::array<TypeInfo, 6>& types() {
  static const std::array<TypeInfo, 6> t = {{
      {JointType::fixed, "fixed", {"p.x", "p.y", "p.z", "r.x", "r.y", "r.z"}},
      {JointType::spherical, "spherical", {"p.x", "p.y", "p.z"}},
      {JointType::revolute, "revolute", {"p.x", "p.y", "p.z", "r.x", "r.y"}},
      {JointType::cylindrical, "cylindrical", {"r.x", "r.y", "d.x", "d.y"}},
      {JointType::prismatic, "prismatic", {"r.x", "r.y", "r.z", "d.x", "d.y"}},
      {JointType::distance, "distance", {"l"}},
  }};
  return t;
}

// Writes row r of G1/G2 from the derivatives of that row with respect to p1 - p2
// (dp, a row 3-vector) and theta_1, theta_2 (dt1, dt2).
void jac_row(int r, const Vec3& dp, const Vec3& dt1, const Vec3& dt2, const JointSide& s1,
             const JointSide& s2, Mat* G1, Mat* G2) {
  if (G1 && !s1.ground) G1->row(r) = dp.transpose() * s1.Du + dt1.transpose() * s1.Dt;
  if (G2 && !s2.ground) G2->row(r) = -dp.transpose() * s2.Du + dt2.transpose() * s2.Dt;
}

}  // namespace

JointType joint_type(const std::string& name) {
  for (const auto& t : types())
    if (name == t.name) return t.type;
  throw InputError("unknown joint type '" + name + "' (known: fixed, spherical, revolute, " +
                   "cylindrical, prismatic, distance)");
}

std::string joint_type_name(JointType type) {
  for (const auto& t : types())
    if (t.type == type) return t.name;
  return "?";
}

std::vector<std::string> joint_type_names() {
  std::vector<std::string> v;
  for (const auto& t : types()) v.push_back(t.name);
  return v;
}

const std::vector<std::string>& joint_rows(JointType type) {
  for (const auto& t : types())
    if (t.type == type) return t.rows;
  return types()[0].rows;
}

void joint_equations(const Joint& j, const JointSide& s1, const JointSide& s2, double* g,
                     double* gv, double* ga, Mat* G1, Mat* G2) {
  const Vec3 d = s1.p - s2.p, dv = s1.v - s2.v, da = s1.a0 - s2.a0;
  const Vec3 dth = s1.th - s2.th, dthd = s1.thd - s2.thd, dthdd = s1.thdd0 - s2.thdd0;
  const Vec3 zero = Vec3::Zero();
  int r = 0;
  auto point = [&](int k) {
    if (g) g[r] = d(k);
    if (gv) gv[r] = dv(k);
    if (ga) ga[r] = da(k);
    jac_row(r, Vec3::Unit(k), zero, zero, s1, s2, G1, G2);
    ++r;
  };
  // e . (theta_1 - theta_2) with e turning with frame 1: e' = w x e,
  // e'' = al x e + w x (w x e).
  auto rotation = [&](int k) {
    const Vec3 e = s1.E.col(k);
    const Vec3 e1 = s1.w.cross(e), e2 = s1.al.cross(e) + s1.w.cross(e1);
    if (g) g[r] = e.dot(dth);
    if (gv) gv[r] = e1.dot(dth) + e.dot(dthd);
    if (ga) ga[r] = e2.dot(dth) + 2.0 * e1.dot(dthd) + e.dot(dthdd);
    jac_row(r, zero, e, -e, s1, s2, G1, G2);
    ++r;
  };
  // n . (p1 - p2), n = e + theta_1 x e; frames fixed (checked by the System):
  // g' = n . d' + (theta_1' x e) . d,  g'' at qdd = 0 = 2 (theta_1' x e) . d'.
  auto offset = [&](int k) {
    const Vec3 e = s1.E.col(k);
    const Vec3 n = e + s1.th.cross(e), nd = s1.thd.cross(e);
    if (g) g[r] = n.dot(d);
    if (gv) gv[r] = n.dot(dv) + nd.dot(d);
    if (ga) ga[r] = 2.0 * nd.dot(dv) + n.dot(da) + s1.thdd0.cross(e).dot(d);
    jac_row(r, n, e.cross(d), zero, s1, s2, G1, G2);
    ++r;
  };
  switch (j.type) {
    case JointType::fixed:
      for (int k = 0; k < 3; ++k) point(k);
      for (int k = 0; k < 3; ++k) rotation(k);
      break;
    case JointType::spherical:
      for (int k = 0; k < 3; ++k) point(k);
      break;
    case JointType::revolute:
      for (int k = 0; k < 3; ++k) point(k);
      for (int k = 0; k < 2; ++k) rotation(k);
      break;
    case JointType::cylindrical:
      for (int k = 0; k < 2; ++k) rotation(k);
      for (int k = 0; k < 2; ++k) offset(k);
      break;
    case JointType::prismatic:
      for (int k = 0; k < 3; ++k) rotation(k);
      for (int k = 0; k < 2; ++k) offset(k);
      break;
    case JointType::distance: {
      const double L = j.length;
      if (g) g[r] = (d.squaredNorm() - L * L) / (2.0 * L);
      if (gv) gv[r] = d.dot(dv) / L;
      if (ga) ga[r] = (dv.squaredNorm() + d.dot(da)) / L;
      jac_row(r, d / L, zero, zero, s1, s2, G1, G2);
      ++r;
      break;
    }
  }
}

}  // namespace evas
