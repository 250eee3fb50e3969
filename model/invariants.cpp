#include "model/invariants.h"

namespace evas {

namespace {
using StridedMap = Eigen::Map<const Mat, 0, Eigen::Stride<Eigen::Dynamic, 3>>;

// N x n view of the a-components of all nodes' mode shapes.
StridedMap component(const Mat& modes, int a) {
  const Eigen::Index N = modes.rows() / 3;
  return StridedMap(modes.data() + a, N, modes.cols(),
                    Eigen::Stride<Eigen::Dynamic, 3>(modes.rows(), 3));
}
}  // namespace

ModalInvariants compute_invariants(const ModalBody& body) {
  body.require_full("computing the modal invariants");
  ModalInvariants inv;
  const int n = body.num_modes();
  const SpMat& Ms = body.mass;
  const Vec row_mass = Ms * Vec::Ones(body.num_nodes());
  inv.S.resize(3, n);
  if (n == 0) {  // no modes: empty invariants (no row views of empty matrices)
    for (auto& row : inv.p)
      for (Vec& x : row) x.resize(0);
    for (auto& row : inv.M)
      for (Mat& x : row) x.resize(0, 0);
    return inv;
  }
  std::array<Mat, 3> MsPhi;
  for (int a = 0; a < 3; ++a) {
    const Mat Pa = component(body.modes, a);
    inv.S.row(a) = row_mass.transpose() * Pa;
    MsPhi[a] = Ms * Pa;
  }
  for (int a = 0; a < 3; ++a) {
    const Mat Pa = component(body.modes, a);
    for (int b = 0; b < 3; ++b) {
      inv.p[a][b] = MsPhi[a].transpose() * body.s.col(b);  // Phi_a^T Ms s_b (Ms symmetric)
      inv.M[a][b] = Pa.transpose() * MsPhi[b];
    }
  }
  return inv;
}

void frame_force(const ModalInvariants& inv, const Vec3& a_L, const Mat3& W, Vec& f0) {
  f0.noalias() = inv.S.transpose() * a_L;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      if (W(a, b) != 0.0) f0 += W(a, b) * inv.p[a][b];
}

void frame_matrices(const ModalInvariants& inv, const Mat3& W, const Mat3& Om, Mat& KW, Mat& G) {
  KW.setZero();
  G.setZero();
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      if (W(a, b) != 0.0) KW += W(a, b) * inv.M[a][b];
      if (Om(a, b) != 0.0) G += (2.0 * Om(a, b)) * inv.M[a][b];
    }
}

void frame_terms(const ModalInvariants& inv, const Vec3& a_L, const Vec3& w_L, const Vec3& al_L,
                 Vec& f0, Mat& KW, Mat& G) {
  const Mat3 Om = skew(w_L);
  const Mat3 W = skew(al_L) + Om * Om;
  frame_force(inv, a_L, W, f0);
  frame_matrices(inv, W, Om, KW, G);
}

Mat3 rigid_rotation_correction(const Mat3& J, const Vec3& w, const Vec3& al) {
  const double half_tr = 0.5 * J.trace();
  const Mat3 wt = skew(w), alt = skew(al);
  return J * alt - half_tr * alt - wt * skew(J * w) + half_tr * wt * wt + w.squaredNorm() * J;
}

Vec eq1_literal(const ModalBody& body, const Mat3& A, const Vec3& a_G, const Vec3& w_G,
                const Vec3& al_G, const Vec& q, const Vec& qd, const Vec& qdd,
                const Eigen::Matrix<double, Eigen::Dynamic, 3>& F_G) {
  body.require_full("the literal Eq. 1 (sums over all nodes)");
  const int N = body.num_nodes(), n = body.num_modes();
  const Mat3 w_t = skew(w_G);
  const Mat3 AtWA = A.transpose() * (skew(al_G) + w_t * w_t) * A;
  const Mat3 AtOA = A.transpose() * w_t * A;
  const Vec3 At_a = A.transpose() * a_G;
  Vec r = qdd + body.eigenvalues.cwiseProduct(q) + body.damping.cwiseProduct(qd);
  for (int i = 0; i < N; ++i) {
    const double m_i = body.mass.coeff(i, i);
    const Eigen::Matrix<double, 3, Eigen::Dynamic> Phi_i = body.modes.middleRows(3 * i, 3);
    const Vec3 u = body.s.row(i).transpose() + Phi_i * q;
    const Vec3 acc = At_a + AtWA * u + 2.0 * AtOA * (Phi_i * qd);
    r += Phi_i.transpose() * (m_i * acc - A.transpose() * F_G.row(i).transpose());
  }
  (void)n;
  return r;
}

}  // namespace evas
