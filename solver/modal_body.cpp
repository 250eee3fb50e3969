#include "solver/modal_body.h"

#include <cmath>
#include <sstream>

namespace evas {

int ModalBody::node_index(long id) const {
  for (std::size_t i = 0; i < node_ids.size(); ++i)
    if (node_ids[i] == id) return static_cast<int>(i);
  throw InputError("body '" + name + "': no node with id " + std::to_string(id));
}

void ModalBody::validate() const {
  const int N = num_nodes(), n = num_modes();
  auto fail = [&](const std::string& what) { throw InputError("body '" + name + "': " + what); };
  if (static_cast<int>(node_ids.size()) != N) fail("node id count differs from coordinate rows");
  if (mass.rows() != N || mass.cols() != N) fail("mass matrix is not N x N");
  if (modes.rows() != 3 * N) fail("mode shapes do not have 3N rows");
  if (eigenvalues.size() != n || damping.size() != n || static_cast<int>(kinds.size()) != n)
    fail("eigenvalue, damping and kind counts must equal the mode count");
  if (!s.allFinite() || !modes.allFinite() || !eigenvalues.allFinite() || !damping.allFinite())
    fail("non-finite values in coordinates, modes, eigenvalues or damping");
  for (int k = 0; k < n; ++k) {
    if (kinds[k] == ModeKind::Elastic && eigenvalues[k] <= 0.0)
      fail("elastic mode " + std::to_string(k) + " has eigenvalue <= 0");
    if (damping[k] < 0.0) fail("mode " + std::to_string(k) + " has negative damping");
  }
  for (const auto& [set, ids] : node_sets)
    for (long id : ids) {
      bool found = false;
      for (long nid : node_ids) found = found || nid == id;
      if (!found) fail("node set '" + set + "' names unknown node " + std::to_string(id));
    }
}

ModalBody ModalBody::select_modes(const std::vector<int>& keep) const {
  ModalBody b = *this;
  const int n = static_cast<int>(keep.size());
  b.modes.resize(modes.rows(), n);
  b.eigenvalues.resize(n);
  b.damping.resize(n);
  b.kinds.resize(n);
  for (int j = 0; j < n; ++j) {
    const int k = keep[j];
    if (k < 0 || k >= num_modes())
      throw InputError("body '" + name + "': mode " + std::to_string(k) + " does not exist");
    b.modes.col(j) = modes.col(k);
    b.eigenvalues[j] = eigenvalues[k];
    b.damping[j] = damping[k];
    b.kinds[j] = kinds[k];
  }
  return b;
}

Mat apply_mass(const SpMat& Ms, const Mat& x) {
  const int N = static_cast<int>(Ms.rows());
  Mat y = Mat::Zero(x.rows(), x.cols());
  for (int c = 0; c < Ms.outerSize(); ++c)
    for (SpMat::InnerIterator it(Ms, c); it; ++it) {
      const int i = static_cast<int>(it.row()), j = c;
      y.middleRows(3 * i, 3) += it.value() * x.middleRows(3 * j, 3);
    }
  (void)N;
  return y;
}

MassProperties mass_properties(const Eigen::Matrix<double, Eigen::Dynamic, 3>& s, const SpMat& Ms) {
  MassProperties mp;
  const int N = static_cast<int>(s.rows());
  Vec ones = Vec::Ones(N);
  Vec Mones = Ms * ones;  // row sums
  mp.mass = ones.dot(Mones);
  if (!(mp.mass > 0.0)) throw InputError("body mass must be positive");
  mp.com = (s.transpose() * Mones) / mp.mass;
  // J = sum_ij Ms_ij (d_i . d_j I - d_i d_j^T), d = s - com
  Mat d = s.rowwise() - mp.com.transpose();
  Mat Md = Ms * d;               // N x 3
  Mat3 dd = d.transpose() * Md;  // sum_ij Ms_ij d_i d_j^T
  mp.inertia = dd.trace() * Mat3::Identity() - dd;
  mp.inertia = 0.5 * (mp.inertia + mp.inertia.transpose()).eval();
  Eigen::SelfAdjointEigenSolver<Mat3> es(mp.inertia);
  mp.principal_moments = es.eigenvalues();
  mp.principal_axes = es.eigenvectors();
  if (mp.principal_axes.determinant() < 0) mp.principal_axes.col(2) *= -1.0;
  return mp;
}

Mat rigid_basis(const Eigen::Matrix<double, Eigen::Dynamic, 3>& s, const SpMat& Ms) {
  const MassProperties mp = mass_properties(s, Ms);
  const int N = static_cast<int>(s.rows());
  Mat R = Mat::Zero(3 * N, 6);
  const double sm = std::sqrt(mp.mass);
  for (int i = 0; i < N; ++i) {
    const Vec3 d = s.row(i).transpose() - mp.com;
    for (int a = 0; a < 3; ++a) R(3 * i + a, a) = 1.0 / sm;
    for (int k = 0; k < 3; ++k) {
      const double Jk = mp.principal_moments[k];
      if (!(Jk > 0.0))
        throw InputError("body has zero inertia about a principal axis: no rigid rotation basis");
      const Vec3 phi = mp.principal_axes.col(k).cross(d) / std::sqrt(Jk);
      R.block<3, 1>(3 * i, 3 + k) = phi;
    }
  }
  return R;
}

}  // namespace evas
