#include "model/surface.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <sstream>

#include "model/lof.h"
#include "model/modal_body.h"

namespace evas {

void SurfaceSet::validate(const std::string& who) const {
  const auto n = static_cast<Eigen::Index>(nodes.size());
  if (n == 0) throw InputError(who + ": the surface set has no nodes");
  if (area.size() != n || normal.rows() != n)
    throw InputError(who + ": the surface set has " + std::to_string(n) + " nodes but " +
                     std::to_string(area.size()) + " areas and " + std::to_string(normal.rows()) +
                     " normals");
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!(std::isfinite(area[i]) && area[i] >= 0.0)) {
      std::ostringstream os;
      os << who << ": node " << nodes[static_cast<std::size_t>(i)] << " has the area " << area[i]
         << " m^2 (must be finite and >= 0)";
      throw InputError(os.str());
    }
    const double len = normal.row(i).norm();
    if (!(std::abs(len - 1.0) < 1e-6)) {
      std::ostringstream os;
      os << who << ": the normal of node " << nodes[static_cast<std::size_t>(i)] << " has length "
         << len << " (must be a unit vector)";
      throw InputError(os.str());
    }
  }
  if (!(area.sum() > 0.0)) throw InputError(who + ": the surface set's areas sum to 0");
}

namespace {

// Rows sqrt(rho c lambda_k) e_k^T of G = B^T diag(area) B = E diag(lambda) E^T,
// the eigenvalues above 1e-12 of the largest (none for G = 0).
Mat components_of(const Mat& B, const Vec& area, double rho_c) {
  const Mat G = B.transpose() * area.asDiagonal() * B;
  Eigen::SelfAdjointEigenSolver<Mat> eig(G);
  const Vec& lambda = eig.eigenvalues();  // ascending
  const double top = lambda.size() ? lambda[lambda.size() - 1] : 0.0;
  std::vector<Eigen::Index> keep;
  for (Eigen::Index k = lambda.size() - 1; k >= 0; --k)
    if (top > 0.0 && lambda[k] > 1e-12 * top) keep.push_back(k);
  Mat W(static_cast<Eigen::Index>(keep.size()), G.cols());
  for (std::size_t j = 0; j < keep.size(); ++j)
    W.row(static_cast<Eigen::Index>(j)) =
        std::sqrt(rho_c * lambda[keep[j]]) * eig.eigenvectors().col(keep[j]).transpose();
  return W;
}

}  // namespace

SurfaceRadiation::SurfaceRadiation(const ModalBody& body, const SurfaceSet& set, double rho_c,
                                   bool per_node, const std::string& who)
    : rho_c_(rho_c), per_node_(per_node) {
  set.validate(who);
  if (!(rho_c > 0.0 && std::isfinite(rho_c)))
    throw InputError(who + ": 'rho_c' must be > 0 kg/(m^2 s)");
  const std::vector<int> rows = body.node_indices(set.nodes);
  const int n = body.num_modes(), K = 6 + n, N = static_cast<int>(rows.size());
  Mat B(N, K);
  for (int i = 0; i < N; ++i) {
    const Vec3 nn = set.normal.row(i).transpose();
    const Vec3 s = body.s.row(rows[static_cast<std::size_t>(i)]).transpose();
    B.block<1, 3>(i, 0) = nn.transpose();
    B.block<1, 3>(i, 3) = s.cross(nn).transpose();
    B.row(i).tail(n) =
        nn.transpose() * body.modes.middleRows(3 * rows[static_cast<std::size_t>(i)], 3);
  }
  area_ = set.total_area();
  a_ = B.transpose() * set.area / area_;
  rigid_.assign(static_cast<std::size_t>(K), 0);
  for (int k = 0; k < 6; ++k) rigid_[static_cast<std::size_t>(k)] = 1;
  for (int k = 0; k < n; ++k)
    if (static_cast<std::size_t>(k) < body.kinds.size() &&
        body.kinds[static_cast<std::size_t>(k)] == ModeKind::Rigid)
      rigid_[static_cast<std::size_t>(6 + k)] = 1;
  W_ = components_of(B, set.area, rho_c);
  Mat Be = B, Br = B;
  for (int k = 0; k < K; ++k) (rigid_[static_cast<std::size_t>(k)] ? Be : Br).col(k).setZero();
  We_ = components_of(Be, set.area, rho_c);
  Wr_ = components_of(Br, set.area, rho_c);
  if (per_node) B_ = std::move(B);
  u_.resize(K);
  c_.resize(W_.rows());
  ce_.resize(We_.rows());
  cr_.resize(Wr_.rows());
}

void SurfaceRadiation::evaluate(const LofState& lof, const double* qdot, double* out) const {
  const Eigen::Index K = u_.size();
  u_.head<3>() = lof.R_GL.transpose() * lof.v_GL;
  u_.segment<3>(3) = lof.R_GL.transpose() * lof.w_GL_G;
  u_.tail(K - 6) = Eigen::Map<const Vec>(qdot, K - 6);
  c_.noalias() = W_ * u_;
  ce_.noalias() = We_ * u_;  // We_, Wr_ have zero columns where the other part is
  cr_.noalias() = Wr_ * u_;
  const double erp = c_.squaredNorm();
  out[0] = a_.dot(u_);
  out[1] = std::sqrt(erp / (rho_c_ * area_));
  out[2] = erp;
  out[3] = ce_.squaredNorm();
  out[4] = cr_.squaredNorm();
  double* o = out + 5;
  for (Eigen::Index k = 0; k < c_.size(); ++k) *o++ = c_[k];
  for (Eigen::Index k = 0; k < ce_.size(); ++k) *o++ = ce_[k];
  if (per_node_) {
    Eigen::Map<Vec> vn(o, B_.rows());
    vn.noalias() = B_ * u_;
  }
}

}  // namespace evas
