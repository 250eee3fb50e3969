// Body properties for the model (body_properties.h).
#include "model/body_properties.h"

#include <cmath>

namespace evas {

ModalInvariants body_invariants(const ModalBody& body) {
  return body.invariants ? *body.invariants : compute_invariants(body);
}

MassProperties body_mass_properties(const ModalBody& body) {
  if (body.mass_props) return *body.mass_props;
  body.require_full("the mass properties");
  return mass_properties(body.s, body.mass);
}

Mat rigid_participation(const ModalInvariants& inv, const MassProperties& mp) {
  const Eigen::Index n = inv.S.cols();
  Mat P(6, n);
  const double sm = std::sqrt(mp.mass);
  for (Eigen::Index j = 0; j < n; ++j) {
    const Vec3 S = inv.S.col(j);
    const Vec3 h(inv.p[2][1][j] - inv.p[1][2][j], inv.p[0][2][j] - inv.p[2][0][j],
                 inv.p[1][0][j] - inv.p[0][1][j]);
    const Vec3 L = h - mp.com.cross(S);  // sum_i d_i x (M_s Phi)_i, d = s - com
    P.block<3, 1>(0, j) = S / sm;
    for (int k = 0; k < 3; ++k) {
      const double Jk = mp.principal_moments[k];
      P(3 + k, j) = Jk > 0.0 ? mp.principal_axes.col(k).dot(L) / std::sqrt(Jk) : 0.0;
    }
  }
  return P;
}

std::array<int, 6> find_rigid_modes(const ModalBody& b, const ModalInvariants& inv,
                                    const MassProperties& mp) {
  std::array<int, 6> idx = {-1, -1, -1, -1, -1, -1};
  bool any_rigid = false;
  for (auto k : b.kinds) any_rigid = any_rigid || k == ModeKind::Rigid;
  if (!any_rigid) return idx;
  if (!b.invariants || !b.mass_props) {
    // The full node set and mass matrix: compare the shapes with rigid_basis().
    b.require_full("locating the rigid modes");
    const Mat R = rigid_basis(b.s, b.mass);
    const Mat MR = apply_mass(b.mass, R);
    for (int r = 0; r < 6; ++r)
      for (int j = 0; j < b.num_modes(); ++j) {
        if (b.kinds[j] != ModeKind::Rigid) continue;
        if ((b.modes.col(j) - R.col(r)).norm() <= 1e-8 * R.col(r).norm() &&
            std::abs(MR.col(r).dot(b.modes.col(j)) - 1.0) < 1e-8) {
          idx[r] = j;
          break;
        }
      }
    return idx;
  }
  // Stored data of the full body: mode j is rigid basis vector r exactly when
  // its participation is e_r and its mass norm is 1 (then Phi_j - R_r has zero
  // mass norm); the rows at the nodes present must agree as well.
  for (auto Jk : mp.principal_moments)
    if (!(Jk > 0.0)) return idx;  // no rigid rotation basis (rigid_basis() would throw)
  const Mat P = rigid_participation(inv, mp);
  const Mat R = rigid_basis(b.s, mp);
  // Rigid-basis entries are of order 1/sqrt(m) (rotations: |d| / sqrt(J)).
  const double row_scale = std::sqrt(b.num_nodes() / mp.mass);
  for (int r = 0; r < 6; ++r)
    for (int j = 0; j < b.num_modes(); ++j) {
      if (b.kinds[j] != ModeKind::Rigid) continue;
      const double norm2 = (inv.M[0][0](j, j) + inv.M[1][1](j, j) + inv.M[2][2](j, j));
      Vec e = Vec::Zero(6);
      e[r] = 1.0;
      if ((P.col(j) - e).cwiseAbs().maxCoeff() < 1e-8 && std::abs(norm2 - 1.0) < 1e-8 &&
          (b.modes.col(j) - R.col(r)).norm() <= 1e-8 * std::max(R.col(r).norm(), row_scale)) {
        idx[r] = j;
        break;
      }
    }
  return idx;
}

}  // namespace evas
