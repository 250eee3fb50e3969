// Modal-body builder (see body_builder.h and formulation.md section 2).
//
// Steps
//   1. Check the FE data (sizes, symmetry, finite values).
//   2. Lowest eigenpairs of K phi = lambda M phi, M = Ms (x) I3. The mass of a
//      coarse quadratic-tet mesh integrated with a reduced rule (ccx: 4 points for
//      C3D10) is only positive semi-definite, and the free-free K is singular, so
//      neither K nor M may be factored. Both solvers therefore work on the shifted
//      pencil
//          M x = nu B x,   B = K + s M,   lambda = 1/nu - s,
//      whose B is positive definite for s > 0 on a connected free body (K is
//      positive definite on the null space of M unless a massless part is loose,
//      and s M covers the rigid motions). Null mass directions give nu = 0
//      (infinite lambda) and are discarded (nu <= kNullNu / s); rigid modes give
//      nu = 1/s, the largest.
//        dense   : Cholesky B = L L^T, Eigen::SelfAdjointEigenSolver of L^-1 M L^-T;
//        spectra : Spectra::SymGEigsSolver in Cholesky mode (sparse LLT of B),
//                  largest nu. Its Krylov operator L^-1 M L^-T has the spectrum of
//                  the shift-invert operator (K + s M)^-1 M, so convergence is
//                  that of shift-invert at sigma = -s, but the inner product is
//                  the Euclidean one of the Cholesky-transformed problem instead
//                  of the M inner product of SymGEigsShiftSolver. When M is
//                  singular that inner product is only a semi-norm, blind to
//                  null-mass components of the Lanczos vectors: on the ccx block
//                  fixture shift-invert reported convergence while its Ritz vectors
//                  had residuals |K x - lambda M x| / |K x| up to 0.15, eigenvalues
//                  off by up to 3 % (4e-3 after the Rayleigh-Ritz step 4). nev
//                  grows until the count and the frequency cut-off are covered.
//      Choice of s: the computed nu have an absolute error ~ eps / s, so the
//      relative error of lambda is ~ eps (lambda + s)^2 / (s lambda): smallest
//      (4 eps) at lambda = s and growing only linearly with lambda / s or
//      s / lambda. The lowest elastic eigenvalue is not known beforehand; FE
//      models of engine parts have lambda_1 / lambda_max between ~1e-10 and
//      ~1e-2, so s = kShiftRel * d with kShiftRel = 1e-6 and d = max_i K_ii / M_ii
//      (a Rayleigh quotient, lambda_max >= d) sits in the middle of that range on
//      a log scale: the wanted eigenvalues then carry relative errors below
//      ~1e4 eps before the Rayleigh-Ritz step 4 (which refines them further).
//   3. Rigid eigenvectors: the returned eigenvectors with the 6 largest rigid
//      content |R^T M phi|^2 (R = rigid_basis(), M-orthonormal) are the rigid
//      ones; no threshold on lambda is used, so a very slender body whose
//      softest elastic modes are tiny compared with lambda_max keeps them. A free
//      body has content ~1 on 6 eigenvectors; if the sixth largest is below 1/2,
//      K does not have the rigid-body null space of a free body (supported model).
//   4. The remaining (elastic) eigenvectors E are projected twice against R:
//      E <- E - R (R^T M E). The small projected problem is solved again in the
//      shifted form (E^T M E) y = nu (E^T K E + s E^T M E) y, Phi = E y
//      M-normalised, lambda = phi^T K phi (Rayleigh-Ritz). An elastic eigenvalue
//      below kMechanismRel * s (numerically zero or negative) means a mechanism,
//      loose nodes or an indefinite K; a clearly negative rigid-mode eigenvalue
//      (below -kNegativeRel * s) means K is not positive semi-definite.
//   5. Truncation by count and cut-off frequency, modes = [R | elastic] or
//      [elastic], damping c_k = 2 zeta omega_k for elastic modes.
#include "bodies/body_builder.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>
#include <vector>

#ifdef EVAS_HAVE_SPECTRA
#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymGEigsSolver.h>

#include <Eigen/SparseCholesky>
#endif

namespace evas {

namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;
/// Shift s = kShiftRel * max_i K_ii / M_ii of the pencil M x = nu (K + s M) x (see step 2).
constexpr double kShiftRel = 1e-6;
/// Eigenvalues nu <= kNullNu / s of the shifted pencil belong to null mass
/// directions (nu = 0, lambda = infinity) and are discarded. Their computed nu
/// are round-off, ~ eps / s; the kept modes have lambda < 1e11 s.
constexpr double kNullNu = 1e-11;
/// An elastic eigenvalue below kMechanismRel * s is numerically zero (a mechanism).
constexpr double kMechanismRel = 1e-6;
/// A rigid eigenvalue below -kNegativeRel * s means K is not positive semi-definite.
constexpr double kNegativeRel = 1e-4;
/// Models with fewer DOF than this use the dense solver under solver = "auto"
/// when a truncation is given (measured: dense 20 s vs Spectra 0.02 s at 2000 DOF);
/// without a truncation all modes are wanted and only the dense solver gives them.
constexpr int kDenseLimit = 600;
/// Extra eigenpairs asked from Spectra beyond what is kept, so that clusters at
/// the truncation boundary are resolved.
constexpr int kSpectraMargin = 10;

struct EigenPairs {
  Vec values;   ///< lambda, ascending
  Mat vectors;  ///< 3N x m, M-normalised
};

[[noreturn]] void fail(const std::string& body, const std::string& what) {
  throw InputError("body '" + body + "': " + what);
}

/// Full 3N x 3N mass M = Ms (x) I3 (DOF 3i+a).
SpMat expand_mass(const SpMat& Ms) {
  std::vector<Triplet> t;
  t.reserve(static_cast<std::size_t>(Ms.nonZeros()) * 3);
  for (int c = 0; c < Ms.outerSize(); ++c)
    for (SpMat::InnerIterator it(Ms, c); it; ++it)
      for (int a = 0; a < 3; ++a)
        t.emplace_back(3 * static_cast<int>(it.row()) + a, 3 * c + a, it.value());
  SpMat M(3 * Ms.rows(), 3 * Ms.cols());
  M.setFromTriplets(t.begin(), t.end());
  M.makeCompressed();
  return M;
}

/// Relative asymmetry ||A - A^T||_F / ||A||_F of a sparse matrix.
double asymmetry(const SpMat& A) {
  const double n = A.norm();
  if (n == 0.0) return 0.0;
  const SpMat At = A.transpose();
  return SpMat(A - At).norm() / n;
}

void check_input(const std::string& name, const FeModel& fe) {
  const long N = static_cast<long>(fe.s.rows());
  std::ostringstream os;
  if (N < 1) fail(name, "the FE model has no nodes");
  if (static_cast<long>(fe.node_ids.size()) != N) {
    os << "node_ids has " << fe.node_ids.size() << " entries but there are " << N
       << " coordinate rows";
    fail(name, os.str());
  }
  if (fe.K.rows() != 3 * N || fe.K.cols() != 3 * N) {
    os << "stiffness K is " << fe.K.rows() << " x " << fe.K.cols()
       << ", expected 3N x 3N = " << 3 * N << " x " << 3 * N;
    fail(name, os.str());
  }
  if (fe.Ms.rows() != N || fe.Ms.cols() != N) {
    os << "scalar mass Ms is " << fe.Ms.rows() << " x " << fe.Ms.cols()
       << ", expected N x N = " << N << " x " << N;
    fail(name, os.str());
  }
  if (!fe.s.allFinite()) fail(name, "node coordinates are not finite");
  for (const SpMat* A : {&fe.K, &fe.Ms})
    for (int c = 0; c < A->outerSize(); ++c)
      for (SpMat::InnerIterator it(*A, c); it; ++it)
        if (!std::isfinite(it.value()))
          fail(name, std::string(A == &fe.K ? "K" : "Ms") + " has non-finite entries");
  if (asymmetry(fe.K) > 1e-10) fail(name, "stiffness K is not symmetric");
  if (asymmetry(fe.Ms) > 1e-10) fail(name, "scalar mass Ms is not symmetric");
  for (long i = 0; i < N; ++i)
    if (!(fe.Ms.coeff(i, i) > 0.0)) {
      os << "scalar mass Ms has a non-positive diagonal entry at node id " << fe.node_ids[i];
      fail(name, os.str());
    }
}

/// Largest K_ii / M_ii: a Rayleigh quotient, so a lower estimate of lambda_max.
double diagonal_ratio(const SpMat& K, const SpMat& M) {
  double r = 0.0;
  for (int i = 0; i < K.rows(); ++i) {
    const double m = M.coeff(i, i);
    if (m > 0.0) r = std::max(r, K.coeff(i, i) / m);
  }
  return r;
}

/// Eigenpairs of the shifted pencil (values nu, vectors B-normalised, any order)
/// to ascending lambda = 1/nu - s with M-normalised vectors (x^T M x = nu x^T B x
/// = nu), dropping the null-mass directions nu <= kNullNu / s.
EigenPairs from_shifted(const Vec& nu, const Mat& X, double s) {
  std::vector<int> idx;
  for (int j = 0; j < static_cast<int>(nu.size()); ++j)
    if (nu[j] > kNullNu / s) idx.push_back(j);
  // ascending lambda = descending nu
  std::sort(idx.begin(), idx.end(), [&](int a, int b) { return nu[a] > nu[b]; });
  EigenPairs ep;
  ep.values.resize(static_cast<long>(idx.size()));
  ep.vectors.resize(X.rows(), static_cast<long>(idx.size()));
  for (int j = 0; j < static_cast<int>(idx.size()); ++j) {
    ep.values[j] = 1.0 / nu[idx[j]] - s;
    ep.vectors.col(j) = X.col(idx[j]) / std::sqrt(nu[idx[j]]);
  }
  return ep;
}

/// True when the Cholesky pivots l_ii^2 of B = K + s M (l: the factor's
/// diagonal) show B numerically definite. A loose part without mass makes B
/// singular; its Cholesky then meets a zero pivot, or one of round-off size
/// (about n eps max B_ii; rank-revealing Cholesky: Higham, Accuracy and
/// Stability of Numerical Algorithms, 2nd ed., section 10.3), depending on how
/// the build rounds, and the pencil's eigenvalues are arbitrary. A sound
/// model's pivots are at least B's smallest eigenvalue, which K + s M keeps
/// far above that unless a part is both without mass and without stiffness.
bool definite_pivots(const Vec& l, const Vec& b_diag) {
  const double tiny = static_cast<double>(b_diag.size()) * std::numeric_limits<double>::epsilon() *
                      b_diag.maxCoeff();
  return l.size() > 0 && l.cwiseAbs2().minCoeff() > tiny;
}

EigenPairs solve_dense(const std::string& name, const SpMat& K, const SpMat& M, double s) {
  const Mat Md = Mat(M);
  const Mat Bd = Mat(K) + s * Md;
  const std::string failed =
      "dense generalized eigen-solver failed: K + s M is not positive definite (K is "
      "indefinite, or a part of the model without mass is loose)";
  const Eigen::LLT<Mat> llt(Bd);
  if (llt.info() != Eigen::Success || !definite_pivots(llt.matrixLLT().diagonal(), Bd.diagonal()))
    fail(name, failed);
  // M x = nu B x with B = L L^T as the standard problem C y = nu y, C = L^-1 M
  // L^-T, x = L^-T y (B-normalised); the steps of Eigen's
  // GeneralizedSelfAdjointEigenSolver, on the factor checked above
  Mat C = Md.selfadjointView<Eigen::Lower>();
  llt.matrixL().solveInPlace<Eigen::OnTheLeft>(C);
  llt.matrixU().solveInPlace<Eigen::OnTheRight>(C);
  const Eigen::SelfAdjointEigenSolver<Mat> es(C);
  if (es.info() != Eigen::Success) fail(name, failed);
  Mat X = es.eigenvectors();
  llt.matrixU().solveInPlace(X);
  return from_shifted(es.eigenvalues(), X, s);
}

#ifdef EVAS_HAVE_SPECTRA
/// Sparse Cholesky of B = K + s M with the interface Spectra's Cholesky mode
/// asks of it (as Spectra::SparseCholesky), which also tells whether B is
/// numerically definite (definite_pivots).
class BCholesky {
 public:
  using Scalar = double;
  explicit BCholesky(const SpMat& B) : n_(B.rows()) {
    llt_.compute(B);
    definite_ =
        llt_.info() == Eigen::Success &&
        definite_pivots(Vec(llt_.matrixL().nestedExpression().diagonal()), Vec(B.diagonal()));
  }
  bool definite() const { return definite_; }
  Eigen::Index rows() const { return n_; }
  Eigen::Index cols() const { return n_; }
  void lower_triangular_solve(const double* x_in, double* y_out) const {
    Eigen::Map<Vec> y(y_out, n_);
    y.noalias() = llt_.permutationP() * Eigen::Map<const Vec>(x_in, n_);
    llt_.matrixL().solveInPlace(y);
  }
  void upper_triangular_solve(const double* x_in, double* y_out) const {
    Eigen::Map<Vec> y(y_out, n_);
    y.noalias() = llt_.matrixU().solve(Eigen::Map<const Vec>(x_in, n_));
    y = llt_.permutationPinv() * y;
  }

 private:
  Eigen::Index n_;
  Eigen::SimplicialLLT<SpMat> llt_;
  bool definite_ = false;
};
#endif

#ifdef EVAS_HAVE_SPECTRA
EigenPairs solve_spectra_once(const std::string& name, const SpMat& M, BCholesky& chol, double s,
                              int nev) {
  using OpType = Spectra::SparseSymMatProd<double>;
  using BOpType = BCholesky;
  const int n = static_cast<int>(M.rows());
  const int ncv = std::min(n, std::max(2 * nev + 1, nev + 20));
  OpType op(M);
  try {
    Spectra::SymGEigsSolver<OpType, BOpType, Spectra::GEigsMode::Cholesky> eig(op, chol, nev, ncv);
    eig.init();
    eig.compute(Spectra::SortRule::LargestAlge, 2000, 1e-12, Spectra::SortRule::LargestAlge);
    if (eig.info() != Spectra::CompInfo::Successful) {
      std::ostringstream os;
      os << "Spectra eigen-solver did not converge (" << nev << " eigenpairs, ncv " << ncv
         << ", shift " << s << ")";
      fail(name, os.str());
    }
    return from_shifted(eig.eigenvalues(), eig.eigenvectors(), s);
  } catch (const std::invalid_argument& e) {
    fail(name, std::string("Spectra eigen-solver: ") + e.what());
  }
}
#endif

/// Indices that sort `v` ascending.
std::vector<int> ascending(const Vec& v) {
  std::vector<int> idx(v.size());
  for (int i = 0; i < static_cast<int>(idx.size()); ++i) idx[i] = i;
  std::sort(idx.begin(), idx.end(), [&](int a, int b) { return v[a] < v[b]; });
  return idx;
}

}  // namespace

ModalBody build_modal_body(const std::string& name, const FeModel& fe, const BuildOptions& opt) {
  check_input(name, fe);
  if (opt.num_elastic < 0) fail(name, "num_elastic must be >= 0");
  if (!(opt.max_frequency >= 0.0)) fail(name, "max_frequency must be >= 0");
  if (!(opt.damping_ratio >= 0.0)) fail(name, "damping_ratio must be >= 0");

  const int N = static_cast<int>(fe.s.rows());
  const int n = 3 * N;
  const SpMat M = expand_mass(fe.Ms);
  const double lambda_cut = opt.max_frequency > 0.0 ? std::pow(kTwoPi * opt.max_frequency, 2) : 0.0;

  std::string solver = opt.solver;
  if (solver == "auto") {
#ifdef EVAS_HAVE_SPECTRA
    const bool truncated = opt.num_elastic > 0 || opt.max_frequency > 0.0;
    solver = (n < kDenseLimit || !truncated) ? "dense" : "spectra";
#else
    solver = "dense";
#endif
  }
  if (solver != "dense" && solver != "spectra")
    fail(name, "unknown eigen-solver '" + opt.solver + "' (use dense, spectra or auto)");

  const double dratio = diagonal_ratio(fe.K, M);
  if (!(dratio > 0.0)) fail(name, "stiffness K has no positive diagonal entry");
  const double shift = kShiftRel * dratio;

  EigenPairs ep;
  if (solver == "dense") {
    ep = solve_dense(name, fe.K, M, shift);
  } else {
#ifdef EVAS_HAVE_SPECTRA
    if (opt.num_elastic == 0 && opt.max_frequency == 0.0)
      fail(name, "the spectra eigen-solver needs num_elastic or max_frequency to be set");
    const SpMat B = SpMat(fe.K + shift * M);
    BCholesky chol(B);
    if (!chol.definite())
      fail(name,
           "sparse Cholesky of K + s M failed: K is indefinite, or a part of the model "
           "without mass is loose");
    const Mat R0 = rigid_basis(fe.s, fe.Ms);
    // sixth (and fifth) largest rigid content of the eigenvectors found
    auto rigid_content_56 = [&](const EigenPairs& e) {
      if (e.values.size() < 6) return Eigen::Vector2d(0.0, 0.0);
      Vec c = (R0.transpose() * apply_mass(fe.Ms, e.vectors)).colwise().squaredNorm().transpose();
      std::sort(c.data(), c.data() + c.size(), std::greater<double>());
      return Eigen::Vector2d(c[4], c[5]);
    };
    int rigid_retries = 0;
    int nev = 6 + (opt.num_elastic > 0 ? opt.num_elastic : 20) + kSpectraMargin;
    for (;;) {
      if (nev > n / 2) {
        // The request covers a large part of the spectrum: dense is cheaper and exact.
        ep = solve_dense(name, fe.K, M, shift);
        break;
      }
      ep = solve_spectra_once(name, M, chol, shift, nev);
      const int found = static_cast<int>(ep.values.size());
      const bool count_ok = opt.num_elastic > 0 && found >= opt.num_elastic + 6 + kSpectraMargin;
      const bool cut_ok = lambda_cut > 0.0 && found > 0 && ep.values[found - 1] > lambda_cut;
      // Lanczos finds a 6-fold eigenvalue slowly: with a small subspace one of the
      // rigid directions can be missing (seen on a 95k-DOF block asked for 6 modes).
      // Then a larger subspace is tried, as for a short count.
      // At most twice (a supported, not free, model fails below with its own
      // message after at most two larger solves).
      if (count_ok || cut_ok) {
        const Eigen::Vector2d c = rigid_content_56(ep);
        if (c[1] >= 0.5 || rigid_retries >= 2) break;
        ++rigid_retries;
      }
      nev *= 2;
    }
#else
    fail(name, "evas was built without Spectra: use solver dense or auto");
#endif
  }

  // --- rigid eigenvectors: the 6 with the largest rigid content ------------------
  const Mat R = rigid_basis(fe.s, fe.Ms);
  const int m_all = static_cast<int>(ep.values.size());
  if (m_all < 7) fail(name, "the eigen-solver returned fewer than 7 modes (too few mass DOF)");
  const Vec content =
      (R.transpose() * apply_mass(fe.Ms, ep.vectors)).colwise().squaredNorm().transpose();
  std::vector<int> by_content(m_all);
  for (int j = 0; j < m_all; ++j) by_content[j] = j;
  std::partial_sort(by_content.begin(), by_content.begin() + 6, by_content.end(),
                    [&](int a, int b) { return content[a] > content[b]; });
  std::vector<bool> is_rigid(m_all, false);
  for (int j = 0; j < 6; ++j) {
    is_rigid[by_content[j]] = true;
    if (ep.values[by_content[j]] < -kNegativeRel * shift) {
      std::ostringstream os;
      os << "stiffness K is not positive semi-definite (eigenvalue " << ep.values[by_content[j]]
         << ")";
      fail(name, os.str());
    }
  }
  std::vector<int> elastic_cols;
  for (int j = 0; j < m_all; ++j)
    if (!is_rigid[j]) elastic_cols.push_back(j);
  const int m_el = static_cast<int>(elastic_cols.size());

  // --- project against the explicit rigid basis and re-solve ------------------
  Mat E(n, m_el);
  for (int j = 0; j < m_el; ++j) E.col(j) = ep.vectors.col(elastic_cols[j]);
  for (int pass = 0; pass < 2; ++pass) E -= R * (R.transpose() * apply_mass(fe.Ms, E));
  const Mat ME = apply_mass(fe.Ms, E);
  const Mat KE = fe.K * E;
  Mat Kr = E.transpose() * KE;
  Mat Mr = E.transpose() * ME;
  Kr = (0.5 * (Kr + Kr.transpose())).eval();
  Mr = (0.5 * (Mr + Mr.transpose())).eval();
  // Shifted form as in step 2: Mr y = nu (Kr + s Mr) y, Kr + s Mr positive definite.
  Eigen::GeneralizedSelfAdjointEigenSolver<Mat> red(Mr, Mat(Kr + shift * Mr));
  if (red.info() != Eigen::Success)
    fail(name, "projected elastic eigenproblem failed (elastic modes not independent)");
  Mat Phi = E * red.eigenvectors();
  // One more projection and M-normalisation keeps the round-off at machine level.
  Phi -= R * (R.transpose() * apply_mass(fe.Ms, Phi));
  for (int j = 0; j < Phi.cols(); ++j) {
    const double nrm2 = Phi.col(j).dot(apply_mass(fe.Ms, Phi.col(j)).col(0));
    if (!(nrm2 > 0.0)) fail(name, "an elastic mode has no mass (null mass direction)");
    Phi.col(j) /= std::sqrt(nrm2);
  }
  Vec lam(Phi.cols());
  {
    const Mat KPhi = fe.K * Phi;
    for (int j = 0; j < Phi.cols(); ++j) lam[j] = Phi.col(j).dot(KPhi.col(j));
  }
  int n_mech = 0;
  for (int j = 0; j < Phi.cols(); ++j)
    if (lam[j] < kMechanismRel * shift) ++n_mech;
  if (n_mech > 0) {
    std::ostringstream os;
    os << "K has " << 6 + n_mech
       << " zero eigenvalues, more than the 6 rigid-body modes: the model has a mechanism or "
          "unconnected nodes";
    fail(name, os.str());
  }
  if (content[by_content[5]] < 0.5)
    fail(name,
         "K does not have the 6 rigid-body modes of a free body (is the FE model supported?)");

  // --- truncation ---------------------------------------------------------------
  // Ascending eigenvalue; Spectra returned the largest nu = lowest lambda, so the
  // lowest num_elastic of them are the true lowest modes.
  std::vector<int> keep;
  if (!(lam.minCoeff() > 0.0)) fail(name, "an elastic mode has a non-positive eigenvalue");
  for (int j : ascending(lam)) {
    if (lambda_cut > 0.0 && lam[j] > lambda_cut) continue;
    if (opt.num_elastic > 0 && static_cast<int>(keep.size()) >= opt.num_elastic) break;
    keep.push_back(j);
  }
  if (keep.empty()) {
    std::ostringstream os;
    os << "no elastic modes";
    if (lambda_cut > 0.0)
      os << " below the cut-off " << opt.max_frequency << " Hz (lowest elastic mode "
         << std::sqrt(std::max(0.0, lam.minCoeff())) / kTwoPi << " Hz)";
    fail(name, os.str());
  }

  if (opt.num_elastic > static_cast<int>(keep.size()) && lambda_cut == 0.0)
    fail(name, std::to_string(opt.num_elastic) +
                   " elastic modes asked for, but the model has only " +
                   std::to_string(keep.size()) + " (ask for fewer)");

  // --- assemble -----------------------------------------------------------------
  Mat elastic(Phi.rows(), static_cast<Eigen::Index>(keep.size()));
  Vec lam_keep(static_cast<Eigen::Index>(keep.size()));
  for (std::size_t j = 0; j < keep.size(); ++j) {
    elastic.col(j) = Phi.col(keep[j]);
    lam_keep[j] = lam[keep[j]];
  }
  return assemble_modal_body(name, fe, elastic, lam_keep, opt);
}

ModalBody assemble_modal_body(const std::string& name, const FeModel& fe, const Mat& elastic,
                              const Vec& eigenvalues, const BuildOptions& opt) {
  const int n_rigid = opt.keep_rigid ? 6 : 0;
  const int n_modes = n_rigid + static_cast<int>(elastic.cols());
  ModalBody body;
  body.name = name;
  body.node_ids = fe.node_ids;
  body.s = fe.s;
  body.mass = fe.Ms;
  body.node_sets = fe.node_sets;
  body.modes.resize(elastic.rows(), n_modes);
  body.eigenvalues = Vec::Zero(n_modes);
  body.damping = Vec::Zero(n_modes);
  body.kinds.assign(n_modes, ModeKind::Elastic);
  if (opt.keep_rigid) {
    body.modes.leftCols(6) = rigid_basis(fe.s, fe.Ms);
    for (int k = 0; k < 6; ++k) body.kinds[k] = ModeKind::Rigid;
  }
  body.modes.rightCols(elastic.cols()) = elastic;
  body.eigenvalues.tail(elastic.cols()) = eigenvalues;
  body.damping.tail(elastic.cols()) = 2.0 * opt.damping_ratio * eigenvalues.cwiseSqrt();
  body.validate();
  return body;
}

}  // namespace evas
