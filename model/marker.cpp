#include "model/marker.h"

#include <cmath>

namespace evas {

Marker make_node_marker(const std::string& name, int body, const ModalBody& b, long node_id) {
  Marker m;
  m.name = name;
  m.body = body;
  const int i = b.node_index(node_id);
  m.c = b.s.row(i).transpose();
  m.Bu = b.modes.middleRows(3 * i, 3);
  m.Bt = Mat3X::Zero(3, b.num_modes());
  m.has_rotation = false;
  return m;
}

Marker make_set_marker(const std::string& name, int body, const ModalBody& b,
                       const std::vector<long>& node_ids, const std::vector<double>& weights,
                       const Vec3* centre) {
  if (node_ids.empty()) throw InputError("marker '" + name + "': empty node set");
  if (!weights.empty() && weights.size() != node_ids.size())
    throw InputError("marker '" + name + "': " + std::to_string(weights.size()) + " weights for " +
                     std::to_string(node_ids.size()) + " nodes");
  const int n = b.num_modes();
  std::vector<int> idx;
  std::vector<double> w;
  double wsum = 0.0;
  Vec3 centroid = Vec3::Zero();
  const std::vector<int> rows = b.node_indices(node_ids);
  for (std::size_t k = 0; k < node_ids.size(); ++k) {
    idx.push_back(rows[k]);
    w.push_back(weights.empty() ? 1.0 : weights[k]);
    if (!(w.back() >= 0.0)) throw InputError("marker '" + name + "': negative weight");
    wsum += w.back();
    centroid += w.back() * b.s.row(idx.back()).transpose();
  }
  if (!(wsum > 0.0)) throw InputError("marker '" + name + "': weights sum to zero");
  Marker m;
  m.name = name;
  m.body = body;
  centroid /= wsum;
  // Least-squares fit of a rigid motion (u, theta) about the weighted centroid:
  // u = sum w u_i / sum w, theta = J^+ sum w d_i x (u_i - u), d_i = s_i - centroid.
  std::vector<Vec3> d(idx.size());
  Mat3 J = Mat3::Zero();
  for (std::size_t k = 0; k < idx.size(); ++k) {
    d[k] = b.s.row(idx[k]).transpose() - centroid;
    J += w[k] * (d[k].squaredNorm() * Mat3::Identity() - d[k] * d[k].transpose());
  }
  // Bu = sum (w/wsum) u_i and T = sum w d_i x (u_i - Bu), one mode at a time:
  // the shapes are stored by mode (column), so each sum reads one column in
  // node order instead of striding across all columns per node.
  Mat3X Bu(3, n), T(3, n);
  for (int j = 0; j < n; ++j) {
    const double* col = b.modes.col(j).data();
    Vec3 bu = Vec3::Zero();
    for (std::size_t k = 0; k < idx.size(); ++k)
      bu += (w[k] / wsum) * Eigen::Map<const Vec3>(col + 3 * static_cast<long>(idx[k]));
    Vec3 t = Vec3::Zero();
    for (std::size_t k = 0; k < idx.size(); ++k)
      t += w[k] * d[k].cross(Eigen::Map<const Vec3>(col + 3 * static_cast<long>(idx[k])) - bu);
    Bu.col(j) = bu;
    T.col(j) = t;
  }
  Eigen::SelfAdjointEigenSolver<Mat3> es(J);
  const double lmax = es.eigenvalues().maxCoeff();
  Mat3 Jinv = Mat3::Zero();
  int rank = 0;
  for (int k = 0; k < 3; ++k)
    if (lmax > 0.0 && es.eigenvalues()[k] > 1e-10 * lmax) {
      Jinv += es.eigenvectors().col(k) * es.eigenvectors().col(k).transpose() / es.eigenvalues()[k];
      ++rank;
    }
  m.Bt = Jinv * T;
  m.has_rotation = rank == 3;
  // The marker point: the centroid, or a given centre carried rigidly by the fit
  // (u_c = u + theta x (c - centroid)).
  m.c = centre ? *centre : centroid;
  m.Bu = Bu - skew(m.c - centroid) * m.Bt;
  return m;
}

Marker make_ground_marker(const std::string& name, const Vec3& p_G, const Mat3& R_GM) {
  Marker m;
  m.name = name;
  m.body = -1;
  m.c = p_G;
  m.R_LM = R_GM;
  m.has_rotation = true;
  return m;
}

void marker_motion(const Marker& m, const LofState& L, const double* q, const double* v,
                   MarkerMotion& out) {
  if (m.on_ground()) {
    marker_motion(m, L, Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), out);
    return;
  }
  const Eigen::Index n = m.Bu.cols();
  Eigen::Map<const Vec> qm(q, n), vm(v, n);
  marker_motion(m, L, m.Bu * qm, m.Bt * qm, m.Bu * vm, m.Bt * vm, out);
}

void marker_motion(const Marker& m, const LofState& L, const Vec3& uq, const Vec3& tq,
                   const Vec3& uv, const Vec3& tv, MarkerMotion& out) {
  if (m.on_ground()) {
    out.p = m.c;
    out.v.setZero();
    out.psi.setZero();
    out.w.setZero();
    out.R = m.R_LM;
    out.a.setZero();
    out.al.setZero();
    return;
  }
  marker_motion(m, L, L.R_GL * m.R_LM, uq, tq, uv, tv, out);
}

void marker_motion(const Marker& m, const LofState& L, const Mat3& R_GM, const Vec3& uq,
                   const Vec3& tq, const Vec3& uv, const Vec3& tv, MarkerMotion& out) {
  out.R = R_GM;
  if (L.w_GL_G.isZero(0.0) && L.al_GL_G.isZero(0.0)) {  // a frame that does not turn
    out.p = L.p_GL + L.R_GL * (m.c + uq);
    out.v = L.v_GL + L.R_GL * uv;
    out.psi = L.psi_G + L.R_GL * tq;
    out.w = L.R_GL * tv;
    out.a = L.a_GL;
    out.al.setZero();
    return;
  }
  const Vec3 r_G = L.R_GL * (m.c + uq);
  out.p = L.p_GL + r_G;
  const Vec3 u_G = L.R_GL * uv;
  const Vec3 t_G = L.R_GL * tv;
  const Vec3 wr = L.w_GL_G.cross(r_G);
  out.v = L.v_GL + wr + u_G;
  out.psi = L.psi_G + L.R_GL * tq;
  out.w = L.w_GL_G + t_G;
  out.a = L.a_GL + L.al_GL_G.cross(r_G) + L.w_GL_G.cross(wr) + 2.0 * L.w_GL_G.cross(u_G);
  out.al = L.al_GL_G + L.w_GL_G.cross(t_G);
}

}  // namespace evas
