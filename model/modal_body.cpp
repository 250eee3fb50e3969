#include "model/modal_body.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <unordered_map>
#include <unordered_set>

#include "model/invariants.h"

namespace evas {

std::string ModalBody::label() const {
  return "body '" + name + "'" + (source.empty() ? "" : " (" + source + ")");
}

int ModalBody::node_index(long id) const {
  for (std::size_t i = 0; i < node_ids.size(); ++i)
    if (node_ids[i] == id) return static_cast<int>(i);
  missing_node(id);
}

std::vector<int> ModalBody::node_indices(const std::vector<long>& ids) const {
  std::vector<int> out;
  out.reserve(ids.size());
  // FE bodies list their nodes in increasing id: a binary search per node,
  // without building a table of every node for each set
  if (std::is_sorted(node_ids.begin(), node_ids.end())) {
    for (long id : ids) {
      const auto it = std::lower_bound(node_ids.begin(), node_ids.end(), id);
      if (it == node_ids.end() || *it != id) missing_node(id);
      out.push_back(static_cast<int>(it - node_ids.begin()));
    }
    return out;
  }
  std::unordered_map<long, int> row;
  row.reserve(node_ids.size());
  for (std::size_t i = 0; i < node_ids.size(); ++i)
    row.emplace(node_ids[i], static_cast<int>(i));  // the first of a repeated id, as node_index
  for (long id : ids) {
    const auto it = row.find(id);
    if (it == row.end()) missing_node(id);
    out.push_back(it->second);
  }
  return out;
}

void ModalBody::missing_node(long id) const {
  if (reduced())
    throw InputError(label() + ": no node with id " + std::to_string(id) +
                     "; the body is reduced (" + std::to_string(num_nodes()) + " of " +
                     std::to_string(full_num_nodes) +
                     " nodes kept: those of its node sets and extra nodes), regenerate it with "
                     "the node in 'reduce: extra_nodes' or in a kept set");
  throw InputError("body '" + name + "': no node with id " + std::to_string(id));
}

void ModalBody::require_full(const std::string& what) const {
  if (!reduced()) return;
  throw InputError(label() + ": " + what + " needs the full node set and mass matrix, but the " +
                   "body is reduced (" + std::to_string(num_nodes()) + " of " +
                   std::to_string(full_num_nodes) +
                   " nodes kept, no mass matrix); use the full body file");
}

void ModalBody::validate() const {
  const int N = num_nodes(), n = num_modes();
  auto fail = [&](const std::string& what) { throw InputError("body '" + name + "': " + what); };
  if (static_cast<int>(node_ids.size()) != N) fail("node id count differs from coordinate rows");
  if (reduced()) {
    if (mass.rows() != 0 || mass.cols() != 0) fail("a reduced body carries no mass matrix");
    if (!invariants || !mass_props)
      fail("a reduced body needs the stored invariants and mass properties of the full body");
    if (full_num_nodes < N) fail("a reduced body has more nodes than the full body");
  } else if (mass.rows() != N || mass.cols() != N) {
    fail("mass matrix is not N x N");
  }
  if (invariants) {
    const ModalInvariants& v = *invariants;
    bool ok = v.S.rows() == 3 && v.S.cols() == n && v.S.allFinite();
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        ok = ok && v.p[a][b].size() == n && v.M[a][b].rows() == n && v.M[a][b].cols() == n &&
             v.p[a][b].allFinite() && v.M[a][b].allFinite();
    if (!ok)
      fail("stored invariants do not match the " + std::to_string(n) +
           " modes (wrong sizes or non-finite values)");
  }
  if (mass_props) {
    const MassProperties& mp = *mass_props;
    if (!(mp.mass > 0.0) || !std::isfinite(mp.mass) || !mp.com.allFinite() ||
        !mp.inertia.allFinite() || !mp.principal_moments.allFinite() ||
        !mp.principal_axes.allFinite())
      fail("stored mass properties are not finite or the mass is not positive");
  }
  if (modes.rows() != 3 * N) fail("mode shapes do not have 3N rows");
  if (eigenvalues.size() != n || damping.size() != n || static_cast<int>(kinds.size()) != n)
    fail("eigenvalue, damping and kind counts must equal the mode count");
  if (!s.allFinite() || !modes.allFinite() || !eigenvalues.allFinite() || !damping.allFinite())
    fail("non-finite values in coordinates, modes, eigenvalues or damping");
  for (int k = 0; k < n; ++k) {
    if (kinds[k] == ModeKind::Elastic && eigenvalues[k] <= 0.0) {
      std::ostringstream os;
      os << "elastic mode " << k << " has eigenvalue " << std::setprecision(6) << eigenvalues[k]
         << " <= 0 (a negative eigenvalue, or a rigid mode marked elastic: kind 0 is rigid)";
      fail(os.str());
    }
    if (damping[k] < 0.0) {
      std::ostringstream os;
      os << "mode " << k << " has negative damping " << std::setprecision(6) << damping[k];
      fail(os.str());
    }
  }
  const std::unordered_set<long> known(node_ids.begin(), node_ids.end());
  for (const auto& [set, ids] : node_sets)
    for (long id : ids)
      if (!known.count(id)) fail("node set '" + set + "' names unknown node " + std::to_string(id));
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
  if (invariants) {
    const ModalInvariants& v = *invariants;
    if (v.S.cols() != num_modes())
      throw InputError(label() + ": stored invariants do not match the mode count");
    auto w = std::make_shared<ModalInvariants>();
    w->S.resize(3, n);
    for (int j = 0; j < n; ++j) w->S.col(j) = v.S.col(keep[j]);
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c) {
        w->p[a][c].resize(n);
        w->M[a][c].resize(n, n);
        for (int j = 0; j < n; ++j) {
          w->p[a][c][j] = v.p[a][c][keep[j]];
          for (int l = 0; l < n; ++l) w->M[a][c](j, l) = v.M[a][c](keep[j], keep[l]);
        }
      }
    b.invariants = std::move(w);
  }
  return b;
}

Mat apply_mass(const SpMat& Ms, const Mat& x) {
  const int N = static_cast<int>(Ms.rows());
  if (Ms.cols() != N || x.rows() != 3 * N)
    throw InputError("apply_mass: a " + std::to_string(Ms.rows()) + " x " +
                     std::to_string(Ms.cols()) + " mass matrix does not fit " +
                     std::to_string(x.rows()) + " rows (3 per node)");
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
  if (Ms.rows() != N || Ms.cols() != N)
    throw InputError("mass properties: the mass matrix (" + std::to_string(Ms.rows()) + " x " +
                     std::to_string(Ms.cols()) + ") does not match the " + std::to_string(N) +
                     " nodes (a reduced body has no mass matrix)");
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
  return rigid_basis(s, mass_properties(s, Ms));
}

Mat rigid_basis(const Eigen::Matrix<double, Eigen::Dynamic, 3>& s, const MassProperties& mp) {
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
