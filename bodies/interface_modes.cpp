// Interface (static correction) modes, see interface_modes.h.
#include "bodies/interface_modes.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <unordered_map>

namespace evas {

namespace {

/// Relative size below which a principal value of a set's polar tensor counts
/// as zero (the set cannot carry a moment about that axis); as in make_set_marker.
constexpr double kPolarRel = 1e-10;

/// Residual compliance below this fraction of the loads' whole compliance is
/// taken as zero when ranking (the kept modes already carry that load).
constexpr double kResidualFloor = 1e-9;

/// M-inner products x^T M y of the columns (M = Ms (x) I3).
Vec mass_norms2(const SpMat& Ms, const Mat& X) {
  const Mat MX = apply_mass(Ms, X);
  Vec n(X.cols());
  for (int j = 0; j < X.cols(); ++j) n[j] = X.col(j).dot(MX.col(j));
  return n;
}

/// Radius of gyration of a node set about its centroid (equal weights).
double set_radius(const FeModel& fe, const std::vector<long>& set) {
  std::unordered_map<long, int> row;
  for (std::size_t i = 0; i < fe.node_ids.size(); ++i) row[fe.node_ids[i]] = static_cast<int>(i);
  Vec3 c = Vec3::Zero();
  for (long id : set) c += fe.s.row(row.at(id)).transpose();
  c /= static_cast<double>(set.size());
  double r2 = 0.0;
  for (long id : set) r2 += (fe.s.row(row.at(id)).transpose() - c).squaredNorm();
  return std::sqrt(r2 / static_cast<double>(set.size()));
}

/// Columns of G (unit M-norm first) with the components along Q removed (twice,
/// classical Gram-Schmidt), then an M-orthonormal basis of what is left,
/// dropping directions whose squared norm is below tol^2 (already spanned).
Mat orthonormal_remainder(const SpMat& Ms, const Mat& Q, Mat G, double tol,
                          const std::string& who) {
  if (G.cols() == 0) return Mat(G.rows(), 0);
  {
    const Vec n2 = mass_norms2(Ms, G);
    for (int j = 0; j < G.cols(); ++j) {
      if (!(n2[j] > 0.0)) throw InputError(who + "a static shape is zero (no load on the set?)");
      G.col(j) /= std::sqrt(n2[j]);
    }
  }
  for (int pass = 0; pass < 2; ++pass) G -= Q * (Q.transpose() * apply_mass(Ms, G));
  Mat Gram = G.transpose() * apply_mass(Ms, G);
  Gram = (0.5 * (Gram + Gram.transpose())).eval();
  Eigen::SelfAdjointEigenSolver<Mat> gs(Gram);
  std::vector<int> keep;
  for (int k = 0; k < gs.eigenvalues().size(); ++k)
    if (gs.eigenvalues()[k] > tol * tol) keep.push_back(k);
  Mat B(G.rows(), static_cast<int>(keep.size()));
  for (int j = 0; j < static_cast<int>(keep.size()); ++j)
    B.col(j) = G * gs.eigenvectors().col(keep[j]) / std::sqrt(gs.eigenvalues()[keep[j]]);
  B -= Q * (Q.transpose() * apply_mass(Ms, B));
  return B;
}

/// The static shapes of the principal load combinations, ranked by the
/// residual flexibility they carry (see InterfaceOptions::rank_tolerance).
Mat ranked_shapes(const FeModel& fe, const Mat& P, const Mat& F, const Mat& U,
                  const std::vector<double>& scale, const InterfaceOptions& opt,
                  const std::string& who) {
  Mat Ur = U;
  for (int pass = 0; pass < 2; ++pass) Ur -= P * (P.transpose() * apply_mass(fe.Ms, Ur));
  const Vec w = Eigen::Map<const Vec>(scale.data(), static_cast<Eigen::Index>(scale.size()));
  Mat Fr = w.asDiagonal() * (F.transpose() * Ur) * w.asDiagonal();
  Fr = (0.5 * (Fr + Fr.transpose())).eval();
  Eigen::SelfAdjointEigenSolver<Mat> es(Fr);
  const Vec& s = es.eigenvalues();  // ascending
  const double smax = s.size() > 0 ? s[s.size() - 1] : 0.0;
  // What the kept modes miss below this fraction of the loads' whole compliance
  // is round-off (their shapes would be noise): nothing to add.
  Mat Fc = w.asDiagonal() * (F.transpose() * U) * w.asDiagonal();
  Fc = (0.5 * (Fc + Fc.transpose())).eval();
  const double floor =
      kResidualFloor * Eigen::SelfAdjointEigenSolver<Mat>(Fc).eigenvalues().maxCoeff();
  if (!std::isfinite(smax)) throw InputError(who + "the residual flexibility is not finite");
  std::vector<int> keep;
  for (Eigen::Index k = s.size() - 1; k >= 0; --k) {
    if (!(s[k] > floor) || s[k] < opt.rank_tolerance * smax) break;
    if (opt.max_count > 0 && static_cast<int>(keep.size()) >= opt.max_count) break;
    keep.push_back(static_cast<int>(k));
  }
  Mat G(Ur.rows(), static_cast<int>(keep.size()));
  for (std::size_t j = 0; j < keep.size(); ++j)
    G.col(static_cast<int>(j)) = Ur * (w.asDiagonal() * es.eigenvectors().col(keep[j]));
  return G;
}

}  // namespace

Mat interface_loads(const FeModel& fe, const std::vector<long>& set, bool moments) {
  if (set.empty()) throw InputError("interface node set is empty");
  std::unordered_map<long, int> row;
  for (std::size_t i = 0; i < fe.node_ids.size(); ++i) row[fe.node_ids[i]] = static_cast<int>(i);
  std::vector<int> idx;
  for (long id : set) {
    const auto it = row.find(id);
    if (it == row.end())
      throw InputError("interface node set: node id " + std::to_string(id) +
                       " is not in the model");
    idx.push_back(it->second);
  }
  const int N = static_cast<int>(fe.s.rows());
  const double w = 1.0 / static_cast<double>(idx.size());
  Vec3 c = Vec3::Zero();
  for (int i : idx) c += w * fe.s.row(i).transpose();
  Mat3 J = Mat3::Zero();
  for (int i : idx) {
    const Vec3 d = fe.s.row(i).transpose() - c;
    J += w * (d.squaredNorm() * Mat3::Identity() - d * d.transpose());
  }
  std::vector<Vec3> axes;  // moment axes scaled by 1/J_k (the RBE3 spreading J^+ m)
  if (moments) {
    Eigen::SelfAdjointEigenSolver<Mat3> es(J);
    const double jmax = es.eigenvalues().maxCoeff();
    for (int k = 0; k < 3; ++k)
      if (jmax > 0.0 && es.eigenvalues()[k] > kPolarRel * jmax)
        axes.push_back(es.eigenvectors().col(k) / es.eigenvalues()[k]);
  }
  Mat F = Mat::Zero(3 * N, 3 + static_cast<int>(axes.size()));
  for (int i : idx) {
    // Force: f_i = w F. Moment m about the centroid: f_i = w (J^+ m) x d_i, whose
    // resultant is zero and whose moment about the centroid is J J^+ m = m.
    for (int a = 0; a < 3; ++a) F(3 * i + a, a) += w;
    const Vec3 d = fe.s.row(i).transpose() - c;
    for (std::size_t k = 0; k < axes.size(); ++k)
      F.block<3, 1>(3 * i, 3 + static_cast<int>(k)) += w * axes[k].cross(d);
  }
  return F;
}

InertiaReliefSolver::InertiaReliefSolver(const FeModel& fe) : K_(fe.K), Ms_(fe.Ms) {
  const int n = static_cast<int>(K_.rows());
  if (n != 3 * Ms_.rows() || K_.cols() != n)
    throw InputError("inertia relief: K is not 3N x 3N for the N x N mass");
  R_ = rigid_basis(fe.s, fe.Ms);
  // Six DOF whose rows of R form the best-conditioned 6 x 6 block: fixing them
  // removes exactly the rigid motion (a statically determinate support).
  Eigen::ColPivHouseholderQR<Mat> qr(R_.transpose());
  if (qr.rank() < 6) throw InputError("inertia relief: the rigid basis is rank deficient");
  is_fixed_.assign(n, false);
  for (int k = 0; k < 6; ++k) {
    const int dof = qr.colsPermutation().indices()[k];
    fixed_.push_back(dof);
    is_fixed_[dof] = true;
  }
  std::vector<Triplet> t;
  t.reserve(static_cast<std::size_t>(K_.nonZeros()) + 6);
  for (int c = 0; c < K_.outerSize(); ++c)
    for (SpMat::InnerIterator it(K_, c); it; ++it)
      if (!is_fixed_[it.row()] && !is_fixed_[c]) t.emplace_back(it.row(), c, it.value());
  double dmax = 0.0;
  for (int i = 0; i < n; ++i) dmax = std::max(dmax, std::abs(K_.coeff(i, i)));
  for (int dof : fixed_) t.emplace_back(dof, dof, dmax > 0.0 ? dmax : 1.0);
  SpMat Kc(n, n);
  Kc.setFromTriplets(t.begin(), t.end());
  ldlt_.compute(Kc);
  if (ldlt_.info() != Eigen::Success)
    throw InputError(
        "inertia relief: the supported stiffness is singular (mechanism or loose nodes)");
}

Mat InertiaReliefSolver::relieve(const Mat& F) const {
  return F - apply_mass(Ms_, R_ * (R_.transpose() * F));
}

Mat InertiaReliefSolver::solve(const Mat& F) const {
  const Mat Feq = relieve(F);
  auto supported_solve = [&](Mat rhs) {
    for (int dof : fixed_) rhs.row(dof).setZero();
    Mat u = ldlt_.solve(rhs);
    for (int dof : fixed_) u.row(dof).setZero();
    return u;
  };
  Mat U = supported_solve(Feq);
  // One step of iterative refinement against the full K (the reactions at the
  // support are zero for an equilibrated load, so the residual there is round-off).
  U += supported_solve(Feq - K_ * U);
  // Remove the rigid part: K R = 0, so K U is unchanged and R^T M U = 0.
  for (int pass = 0; pass < 2; ++pass) U -= R_ * (R_.transpose() * apply_mass(Ms_, U));
  return U;
}

ModalBody add_interface_modes(const FeModel& fe, const ModalBody& body,
                              const std::vector<std::vector<long>>& interface_sets,
                              const InterfaceOptions& opt) {
  const std::string who = "body '" + body.name + "': interface modes: ";
  const int N = static_cast<int>(fe.s.rows());
  if (body.num_nodes() != N || body.node_ids != fe.node_ids || body.modes.rows() != 3 * N)
    throw InputError(who + "the body was not built from this FE model (nodes differ)");
  if (body.mass.rows() != N || body.mass.cols() != N ||
      SpMat(body.mass - fe.Ms).norm() > 1e-12 * fe.Ms.norm())
    throw InputError(who + "the body's mass matrix differs from the FE model's");
  if (!(opt.damping_ratio >= 0.0)) throw InputError(who + "damping_ratio must be >= 0");
  if (!(opt.independence_tol > 0.0 && opt.independence_tol < 1.0))
    throw InputError(who + "independence_tol must be in (0, 1)");
  if (!(opt.rank_tolerance >= 0.0 && opt.rank_tolerance < 1.0))
    throw InputError(who + "rank_tolerance must be in [0, 1)");
  if (opt.max_count < 0 || opt.krylov_blocks < 0)
    throw InputError(who + "max_count and krylov_blocks must be >= 0");
  if (!opt.loads.empty() && opt.loads.size() != interface_sets.size())
    throw InputError(who + "one load mask per set is needed");
  if (interface_sets.empty()) return body;

  // 1. Loads of all sets (the masked columns), 2. inertia-relief static shapes.
  std::vector<Mat> blocks;
  std::vector<double> scale;  // ranking weight of each column (moments: the set's radius)
  int cols = 0;
  for (std::size_t k = 0; k < interface_sets.size(); ++k) {
    const InterfaceLoadMask mask =
        opt.loads.empty() ? InterfaceLoadMask{{true, true, true}, opt.moments} : opt.loads[k];
    const Mat all = interface_loads(fe, interface_sets[k], mask.moments);
    std::vector<int> pick;
    for (int c = 0; c < all.cols(); ++c)
      if (c >= 3 || mask.force[c]) pick.push_back(c);
    if (pick.empty())
      throw InputError(who + "set " + std::to_string(k + 1) + " of " +
                       std::to_string(interface_sets.size()) + " has no loads selected");
    Mat b(all.rows(), static_cast<int>(pick.size()));
    const double r = pick.back() >= 3 ? set_radius(fe, interface_sets[k]) : 1.0;
    for (std::size_t j = 0; j < pick.size(); ++j) {
      b.col(static_cast<int>(j)) = all.col(pick[j]);
      scale.push_back(pick[j] >= 3 ? r : 1.0);
    }
    blocks.push_back(std::move(b));
    cols += static_cast<int>(blocks.back().cols());
  }
  Mat F(3 * N, cols);
  int c0 = 0;
  for (const auto& b : blocks) {
    F.middleCols(c0, b.cols()) = b;
    c0 += static_cast<int>(b.cols());
  }
  const InertiaReliefSolver irs(fe);
  Mat G = irs.solve(F);
  const Mat& P = body.modes;
  if (opt.rank_tolerance > 0.0 || opt.max_count > 0)
    G = ranked_shapes(fe, P, F, G, scale, opt, who);

  // 3. M-orthonormal remainders after the kept modes; then Wilson's blocks.
  Mat B = orthonormal_remainder(fe.Ms, P, G, opt.independence_tol, who);
  if (B.cols() == 0) return body;
  Mat X = B;
  for (int blk = 0; blk < opt.krylov_blocks && X.cols() > 0; ++blk) {
    Mat Q(P.rows(), P.cols() + B.cols());
    Q << P, B;
    X = orthonormal_remainder(fe.Ms, Q, irs.solve(apply_mass(fe.Ms, X)), opt.independence_tol, who);
    Mat grown(B.rows(), B.cols() + X.cols());
    grown << B, X;
    B = std::move(grown);
  }

  // 4. Rayleigh-Ritz on the new subspace.
  Mat Kr = B.transpose() * (fe.K * B);
  Mat Mr = B.transpose() * apply_mass(fe.Ms, B);
  Kr = (0.5 * (Kr + Kr.transpose())).eval();
  Mr = (0.5 * (Mr + Mr.transpose())).eval();
  Eigen::GeneralizedSelfAdjointEigenSolver<Mat> red(Kr, Mr);
  if (red.info() != Eigen::Success) throw InputError(who + "reduced eigenproblem failed");
  Mat Psi = B * red.eigenvectors();
  const Vec n2 = mass_norms2(fe.Ms, Psi);
  for (int j = 0; j < Psi.cols(); ++j) Psi.col(j) /= std::sqrt(n2[j]);
  const Mat KPsi = fe.K * Psi;

  const int n0 = body.num_modes();
  const int m = static_cast<int>(Psi.cols());
  ModalBody out = body;
  // New modes: invariants stored for the old ones no longer apply (Model::add_body
  // recomputes them from the nodes; store_full_body_data stores them again).
  out.invariants.reset();
  out.modes.conservativeResize(Eigen::NoChange, n0 + m);
  out.modes.rightCols(m) = Psi;
  out.eigenvalues.conservativeResize(n0 + m);
  out.damping.conservativeResize(n0 + m);
  for (int j = 0; j < m; ++j) {
    const double mu = Psi.col(j).dot(KPsi.col(j));
    if (!(mu > 0.0)) {
      std::ostringstream os;
      os << "an interface mode has a non-positive eigenvalue " << mu;
      throw InputError(who + os.str());
    }
    out.eigenvalues[n0 + j] = mu;
    out.damping[n0 + j] = 2.0 * opt.damping_ratio * std::sqrt(mu);
    out.kinds.push_back(ModeKind::Elastic);
  }
  out.validate();
  return out;
}

ModalBody add_interface_modes_by_name(const FeModel& fe, const ModalBody& body,
                                      const std::vector<std::string>& set_names,
                                      const InterfaceOptions& opt) {
  std::vector<std::vector<long>> sets;
  for (const auto& name : set_names) {
    const auto it = fe.node_sets.find(name);
    if (it == fe.node_sets.end())
      throw InputError("body '" + body.name + "': interface modes: no node set '" + name + "'");
    sets.push_back(it->second);
    const std::size_t k = sets.size() - 1;
    if (k < opt.loads.size() && !opt.loads[k].moments &&
        !(opt.loads[k].force[0] || opt.loads[k].force[1] || opt.loads[k].force[2]))
      throw InputError("body '" + body.name + "': interface modes: set '" + name +
                       "' has no loads selected");
  }
  return add_interface_modes(fe, body, sets, opt);
}

}  // namespace evas
