#include "elements/engine_mount.h"

#include <memory>

namespace evas {

EngineMount::EngineMount(std::string name, std::vector<int> markers, std::array<ForceLaw, 3> laws,
                         const Vec3& damping, const Vec3& preload, const Vec3& rot_stiffness,
                         const Vec3& rot_damping, const Vec3& orientation, const Vec3& offset,
                         const Vec3& maxwell_stiffness, const Vec3& maxwell_damping)
    : Element(std::move(name), std::move(markers)),
      laws_(std::move(laws)),
      c_(damping),
      preload_(preload),
      kr_(rot_stiffness),
      cr_(rot_damping),
      offset_(offset),
      k2_(maxwell_stiffness),
      c2_(maxwell_damping),
      R_ME_(rotation_from_vector(orientation)) {
  const char* axes = "xyz";
  for (int i = 0; i < 3; ++i) {
    const std::string where = std::string("axis ") + axes[i] + ": ";
    if (!(k2_[i] >= 0.0) || !(c2_[i] >= 0.0))
      throw InputError(where + "maxwell_stiffness and maxwell_damping must not be negative");
    if (k2_[i] > 0.0 && c2_[i] == 0.0)
      throw InputError(where +
                       "a Maxwell branch (maxwell_stiffness > 0) needs maxwell_damping > 0");
    if (c2_[i] > 0.0 && k2_[i] == 0.0)
      throw InputError(where + "maxwell_damping is given without maxwell_stiffness");
    if (k2_[i] > 0.0) branch_.push_back(i);
  }
}

Vec3 EngineMount::deflection(const MarkerMotion* m, Mat3& R) const {
  R = m[0].R * R_ME_;
  return R.transpose() * (m[1].p - m[0].p) - offset_;
}

void EngineMount::states_or_unloaded(const MarkerMotion* m, const double* z, double* out) const {
  Mat3 R;
  const Vec3 d = z ? Vec3::Zero() : deflection(m, R);
  for (std::size_t j = 0; j < branch_.size(); ++j) out[j] = z ? z[j] : d[branch_[j]];
}

std::string EngineMount::internal_name(int i) const {
  return std::string("z_") + "xyz"[branch_.at(static_cast<std::size_t>(i))];
}

void EngineMount::internal_initial(double, const MarkerMotion* m, double* z) const {
  states_or_unloaded(m, nullptr, z);
}

void EngineMount::evaluate(double t, const MarkerMotion* m, MarkerLoad* loads) const {
  double z[3];
  states_or_unloaded(m, nullptr, z);
  evaluate_z(t, m, z, loads);
}

void EngineMount::internal_rate(double, const MarkerMotion* m, const double* z, double* h) const {
  Mat3 R;
  const Vec3 d = deflection(m, R);
  for (std::size_t j = 0; j < branch_.size(); ++j) {
    const int i = branch_[j];
    h[j] = k2_[i] / c2_[i] * (d[i] - z[j]);
  }
}

void EngineMount::internal_derivatives(double, const MarkerMotion* m, const double* z, Mat& Dz,
                                       Mat& Hm, Mat& Hz) const {
  (void)z;
  const Mat3 R = m[0].R * R_ME_;
  const Vec3 dp = m[1].p - m[0].p;
  Dz.setZero();
  Hm.setZero();
  Hz.setZero();
  for (std::size_t j = 0; j < branch_.size(); ++j) {
    const int i = branch_[j], c = static_cast<int>(j);
    const Vec3 dF1 = k2_[i] * R.col(i);  // dF1/dz_j
    Dz.block<3, 1>(6, c) = dF1;
    Dz.block<3, 1>(0, c) = -dF1;
    Dz.block<3, 1>(3, c) = -dp.cross(dF1);
    const double rate = k2_[i] / c2_[i];
    Hm.block<1, 3>(c, 12) = rate * R.col(i).transpose();  // dd_i/dp1 = e_i^T R^T
    Hm.block<1, 3>(c, 0) = -rate * R.col(i).transpose();
    Hz(c, c) = -rate;
  }
}

void EngineMount::evaluate_z(double, const MarkerMotion* m, const double* z,
                             MarkerLoad* loads) const {
  const Mat3 R = m[0].R * R_ME_;
  const Vec3 dp = m[1].p - m[0].p;
  const Vec3 d = R.transpose() * dp - offset_;
  const Vec3 dv = R.transpose() * (m[1].v - m[0].v);
  const Vec3 r = R.transpose() * (m[1].psi - m[0].psi);
  const Vec3 dw = R.transpose() * (m[1].w - m[0].w);
  Vec3 FE;
  for (int i = 0; i < 3; ++i) FE[i] = preload_[i] - laws_[i].value(d[i]) - c_[i] * dv[i];
  for (std::size_t j = 0; j < branch_.size(); ++j)
    FE[branch_[j]] -= k2_[branch_[j]] * (d[branch_[j]] - z[j]);
  const Vec3 F1 = R * FE;
  const Vec3 M1 = R * (-(kr_.cwiseProduct(r) + cr_.cwiseProduct(dw)));
  loads[1].F = F1;
  loads[1].M = M1;
  loads[0].F = -F1;
  loads[0].M = -M1 - dp.cross(F1);
}

void EngineMount::derivatives(double t, const MarkerMotion* m, Mat& D) const {
  double z[3];
  states_or_unloaded(m, nullptr, z);
  derivatives_z(t, m, z, D);
  if (branch_.empty()) return;
  // the unloaded branch (z = d) adds no force: take its stiffness out again
  Mat Dz(12, static_cast<Eigen::Index>(branch_.size())), Hm, Hz;
  Hm.setZero(static_cast<Eigen::Index>(branch_.size()), 24);
  Hz.setZero(static_cast<Eigen::Index>(branch_.size()), static_cast<Eigen::Index>(branch_.size()));
  internal_derivatives(t, m, z, Dz, Hm, Hz);
  for (std::size_t j = 0; j < branch_.size(); ++j) {
    const int i = branch_[j];
    // dz_j/d(motion) = dd_i/d(motion) = Hm row j * c2 / k2
    D.noalias() += Dz.col(static_cast<Eigen::Index>(j)) *
                   (c2_[i] / k2_[i] * Hm.row(static_cast<Eigen::Index>(j)));
  }
}

void EngineMount::derivatives_z(double, const MarkerMotion* m, const double* z, Mat& D) const {
  const Mat3 R = m[0].R * R_ME_;
  const Vec3 dp = m[1].p - m[0].p;
  const Vec3 d = R.transpose() * dp - offset_;
  const Vec3 dv = R.transpose() * (m[1].v - m[0].v);
  Vec3 FE, kt;
  for (int i = 0; i < 3; ++i) {
    double f, df;
    laws_[i].eval(d[i], f, df);
    FE[i] = preload_[i] - f - c_[i] * dv[i];
    kt[i] = df;  // tangent stiffness of axis i
  }
  for (std::size_t j = 0; j < branch_.size(); ++j) {
    const int i = branch_[j];
    FE[i] -= k2_[i] * (d[i] - z[j]);
    kt[i] += k2_[i];
  }
  const Vec3 F1 = R * FE;
  const Mat3 Kg = R * kt.asDiagonal() * R.transpose();
  const Mat3 Cg = R * c_.asDiagonal() * R.transpose();
  const Mat3 Krg = R * kr_.asDiagonal() * R.transpose();
  const Mat3 Crg = R * cr_.asDiagonal() * R.transpose();
  D.setZero();
  // Rows: F0, M0, F1, M1; columns of marker j at 12 j: p, v, psi, w.
  for (int j = 0; j < 2; ++j) {
    const double s = j == 1 ? 1.0 : -1.0;  // d(p1 - p0)/dp_j = s I
    const int c0 = 12 * j;
    D.block<3, 3>(6, c0) = -s * Kg;
    D.block<3, 3>(6, c0 + 3) = -s * Cg;
    D.block<3, 3>(9, c0 + 6) = -s * Krg;
    D.block<3, 3>(9, c0 + 9) = -s * Crg;
    D.block<3, 12>(0, c0) = -D.block<3, 12>(6, c0);
    D.block<3, 12>(3, c0) = -D.block<3, 12>(9, c0) - skew(dp) * D.block<3, 12>(6, c0);
    D.block<3, 3>(3, c0) += s * skew(F1);  // from -(p1 - p0) x F1 = F1 x (p1 - p0)
  }
}

std::vector<Channel> EngineMount::channels() const {
  std::vector<Channel> c = {{"fx", "N"},   {"fy", "N"}, {"fz", "N"}, {"mx", "N m"}, {"my", "N m"},
                            {"mz", "N m"}, {"dx", "m"}, {"dy", "m"}, {"dz", "m"}};
  for (int i : branch_) c.push_back({std::string("maxwell_f") + "xyz"[i], "N"});
  for (int i : branch_) c.push_back({std::string("z_") + "xyz"[i], "m"});
  return c;
}

void EngineMount::channel_values(double t, const MarkerMotion* m, double* out) const {
  double z[3];
  states_or_unloaded(m, nullptr, z);
  channel_values_z(t, m, z, out);
}

void EngineMount::channel_values_z(double t, const MarkerMotion* m, const double* z,
                                   double* out) const {
  MarkerLoad loads[2];
  evaluate_z(t, m, z, loads);
  const Mat3 R = m[0].R * R_ME_;
  const Vec3 F = R.transpose() * loads[1].F, M = R.transpose() * loads[1].M;
  const Vec3 d = R.transpose() * (m[1].p - m[0].p) - offset_;
  for (int i = 0; i < 3; ++i) {
    out[i] = F[i];
    out[3 + i] = M[i];
    out[6 + i] = d[i];
  }
  const std::size_t nb = branch_.size();
  for (std::size_t j = 0; j < nb; ++j) {
    const int i = branch_[j];
    out[9 + j] = -k2_[i] * (d[i] - z[j]);
    out[9 + nb + j] = z[j];
  }
}

ElementType engine_mount_element_type() {
  using K = ParamSpec::Kind;
  ElementType t;
  t.type = "engine-mount";
  t.doc =
      "Engine mount (paper 3.2): nonlinear spring and linear damper per mount axis between "
      "marker 1 (engine block) and marker 0 (ground or support body). Mount axes E = marker 0's "
      "axes turned by `orientation`. Load on marker 1: F_E,i = preload_i - f_i(d_i) - c_i dv_i, "
      "d = R_E^T (p1 - p0) - offset; M_E = -(kr r + cr dw), r = R_E^T (psi1 - psi0). f_i is the "
      "polynomial k1 d + k2 d^2 + ... or a (deflection, force) table. Marker 0 gets the reaction.";
  t.num_markers = 2;
  t.params = {
      text_param("law", "force-deflection law of all three axes", {"polynomial", "table"},
                 "polynomial"),
      vector_param("k_x", K::List, "N/m, N/m^2, N/m^3, ...",
                   "polynomial coefficients k1, k2, k3, ... of mount axis x (law: polynomial)",
                   {0.0}),
      vector_param("k_y", K::List, "N/m, N/m^2, N/m^3, ...",
                   "polynomial coefficients of mount axis y", {0.0}),
      vector_param("k_z", K::List, "N/m, N/m^2, N/m^3, ...",
                   "polynomial coefficients of mount axis z", {0.0}),
      vector_param("table_x", K::List, "m, N",
                   "(deflection, force) pairs of axis x, deflection increasing (law: table)", {}),
      vector_param("table_y", K::List, "m, N", "(deflection, force) pairs of axis y", {}),
      vector_param("table_z", K::List, "m, N", "(deflection, force) pairs of axis z", {}),
      text_param("interpolation",
                 "table interpolation: monotone cubic Hermite (pchip) or linear; both extrapolate "
                 "linearly with the end slope",
                 {"pchip", "linear"}, "pchip"),
      vector_param("damping", K::Vector3, "N s/m", "linear damping per mount axis", {0.0, 0.0, 0.0},
                   0.0),
      vector_param(
          "preload", K::Vector3, "N",
          "force on the block at zero deflection (mount axes), e.g. (0, 0, m g / n) to hold the "
          "engine at its reference position",
          {0.0, 0.0, 0.0}),
      vector_param("rot_stiffness", K::Vector3, "N m/rad", "rotational stiffness per mount axis",
                   {0.0, 0.0, 0.0}, 0.0),
      vector_param("rot_damping", K::Vector3, "N m s/rad", "rotational damping per mount axis",
                   {0.0, 0.0, 0.0}, 0.0),
      vector_param("orientation", K::Vector3, "rad",
                   "rotation vector of the mount axes relative to marker 0's axes",
                   {0.0, 0.0, 0.0}),
      vector_param("offset", K::Vector3, "m",
                   "position of marker 1 relative to marker 0 at zero deflection (mount axes)",
                   {0.0, 0.0, 0.0}),
      vector_param("maxwell_stiffness", K::Vector3, "N/m",
                   "Maxwell branch per mount axis: spring k2 in series with a dashpot, parallel "
                   "to the law (0: no branch); each branch is an internal state, z' = (k2 / c2) "
                   "(d - z), force -k2 (d - z)",
                   {0.0, 0.0, 0.0}, 0.0),
      vector_param("maxwell_damping", K::Vector3, "N s/m",
                   "dashpot c2 of each Maxwell branch (> 0 where maxwell_stiffness > 0)",
                   {0.0, 0.0, 0.0}, 0.0),
  };
  t.make = [](const std::string& name, const std::vector<int>& markers,
              const ParamValues& v) -> std::unique_ptr<Element> {
    const std::string where = "element '" + name + "'";
    const std::string law = v.text("law"), interp = v.text("interpolation");
    const char* axes[3] = {"x", "y", "z"};
    std::array<ForceLaw, 3> laws;
    for (int i = 0; i < 3; ++i) {
      const std::string a = axes[i];
      laws[i] = make_force_law(
          law, v.list("k_" + a), v.list("table_" + a), interp,
          where + ", axis " + a + " (" + (law == "table" ? "table_" : "k_") + a + ")");
    }
    return std::make_unique<EngineMount>(name, markers, laws, v.vec3("damping"), v.vec3("preload"),
                                         v.vec3("rot_stiffness"), v.vec3("rot_damping"),
                                         v.vec3("orientation"), v.vec3("offset"),
                                         v.vec3("maxwell_stiffness"), v.vec3("maxwell_damping"));
  };
  return t;
}

}  // namespace evas
