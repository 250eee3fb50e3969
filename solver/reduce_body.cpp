#include "solver/reduce_body.h"

#include <cmath>
#include <set>
#include <unordered_map>

namespace evas {

void store_full_body_data(ModalBody& body) {
  body.require_full("computing the invariants to store");
  body.validate();
  body.invariants = std::make_shared<ModalInvariants>(compute_invariants(body));
  body.mass_props = mass_properties(body.s, body.mass);
}

ModalBody reduce_body(const ModalBody& body, const ReduceOptions& opt) {
  body.validate();
  const std::string who = body.label() + ": reduce: ";
  ModalBody out;
  out.name = body.name;
  out.source = body.source;
  if (body.invariants && body.mass_props) {
    out.invariants = body.invariants;
    out.mass_props = body.mass_props;
  } else {
    out.invariants = std::make_shared<ModalInvariants>(body_invariants(body));
    out.mass_props = body_mass_properties(body);
  }
  out.full_num_nodes = body.reduced() ? body.full_num_nodes : body.num_nodes();

  // Kept sets and nodes.
  std::unordered_map<long, int> row;
  for (int i = 0; i < body.num_nodes(); ++i) row[body.node_ids[i]] = i;
  std::set<int> keep;
  auto keep_set = [&](const std::string& name, const std::vector<long>& ids) {
    out.node_sets[name] = ids;
    for (long id : ids) keep.insert(row.at(id));  // validate(): set members are nodes
  };
  if (opt.all_sets) {
    if (!opt.keep_sets.empty())
      throw InputError(who + "give either all sets or a list of sets to keep, not both");
    for (const auto& [name, ids] : body.node_sets) keep_set(name, ids);
  } else {
    for (const std::string& name : opt.keep_sets) {
      const auto it = body.node_sets.find(name);
      if (it == body.node_sets.end()) {
        std::string known;
        for (const auto& s : body.node_sets) known += (known.empty() ? "" : ", ") + s.first;
        throw InputError(who + "no node set '" + name +
                         "' (known: " + (known.empty() ? "none" : known) + ")");
      }
      keep_set(name, it->second);
    }
  }
  for (long id : opt.extra_nodes) {
    const auto it = row.find(id);
    if (it == row.end())
      throw InputError(who + "extra node " + std::to_string(id) + " is not a node of the body");
    keep.insert(it->second);
  }

  const int Nr = static_cast<int>(keep.size()), n = body.num_modes();
  out.node_ids.reserve(Nr);
  out.s.resize(Nr, 3);
  out.modes.resize(3 * Nr, n);
  int r = 0;
  for (int i : keep) {
    out.node_ids.push_back(body.node_ids[i]);
    out.s.row(r) = body.s.row(i);
    out.modes.middleRows(3 * r, 3) = body.modes.middleRows(3 * i, 3);
    ++r;
  }
  out.mass.resize(0, 0);
  out.eigenvalues = body.eigenvalues;
  out.damping = body.damping;
  out.kinds = body.kinds;
  out.validate();
  return out;
}

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
