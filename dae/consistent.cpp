// Consistent initial values (see consistent.h for the method and sources).
#include "dae/consistent.h"

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <string>

#include "dae/fixed_order_dense.h"
#include "model/types.h"

namespace evas::dae {

namespace {

Mat dense_g(Problem& p, double t, const Vec& q) {
  SpMat G = p.constraint_pattern();
  p.constraint_jacobian(t, q.data(), G);
  return Mat(G);
}

// Minimum-norm solution x of G x = r. The decomposition decides the rank;
// for G of full row rank the solution is summed in a fixed order
// (fixed_order_dense.h), so that the start is the same in every build.
Vec min_norm(const Mat& G, const Vec& r) {
  const Eigen::CompleteOrthogonalDecomposition<Mat> cod(G);
  Vec x;
  if (cod.rank() == G.rows() && min_norm_fixed_order(G, r, x)) return x;
  return cod.solve(r);
}

int worst(const Vec& x) {
  Eigen::Index i = 0;
  if (x.size() > 0) x.cwiseAbs().maxCoeff(&i);
  return static_cast<int>(i);
}

}  // namespace

ConsistentState consistent_state(Problem& p, double t, const Vec& q0, const Vec& v0) {
  const int n = p.size(), m = p.constraint_count();
  ConsistentState s;
  s.q = q0;
  s.v = v0;
  s.lambda = Vec::Zero(m);
  Vec g(m), gv(m), ga(m);
  if (m > 0) {
    // 1. positions
    const double eps = std::numeric_limits<double>::epsilon();
    bool converged = false;
    for (int it = 0; it < 50 && !converged; ++it) {
      p.constraint(t, s.q.data(), s.v.data(), g.data(), nullptr, nullptr);
      const Vec dq = min_norm(dense_g(p, t, s.q), g);
      s.q -= dq;
      ++s.iterations;
      converged = dq.lpNorm<Eigen::Infinity>() <= 10 * eps * (1.0 + s.q.lpNorm<Eigen::Infinity>());
    }
    p.constraint(t, s.q.data(), s.v.data(), g.data(), nullptr, nullptr);
    if (!converged || !g.allFinite())
      throw RunError("consistent start at t = " + format_number(t) +
                     " s: the positions could not be projected onto the constraints in 50 "
                     "Gauss-Newton iterations (|g| = " +
                     format_number(g.cwiseAbs().maxCoeff()) + " on constraint '" +
                     p.constraint_name(worst(g)) + "')");
    // 2. velocities
    const Mat G = dense_g(p, t, s.q);
    p.constraint(t, s.q.data(), s.v.data(), nullptr, gv.data(), nullptr);
    s.v -= min_norm(G, gv);
    p.constraint(t, s.q.data(), s.v.data(), g.data(), gv.data(), ga.data());
    s.g_norm = g.cwiseAbs().maxCoeff();
    s.gv_norm = gv.cwiseAbs().maxCoeff();
  }
  // 3. accelerations and multipliers
  Vec f(n);
  p.force(t, s.q.data(), s.v.data(), f.data());
  Mat A = Mat::Zero(n + m, n + m);
  if (p.has_mass()) {
    SpMat M = p.mass_pattern();
    p.mass(t, s.q.data(), M);
    A.topLeftCorner(n, n) = Mat(M);
  } else {
    A.topLeftCorner(n, n).setIdentity();
  }
  Vec rhs(n + m);
  rhs.head(n) = -f;
  if (m > 0) {
    const Mat G = dense_g(p, t, s.q);
    A.topRightCorner(n, m) = G.transpose();
    A.bottomLeftCorner(m, n) = G;
    rhs.tail(m) = -ga;
  }
  const Eigen::CompleteOrthogonalDecomposition<Mat> cod(A);
  if (cod.rank() < n)
    throw RunError("consistent start at t = " + format_number(t) +
                   " s: the mass matrix is singular on the constraint manifold");
  // a regular A (independent constraints): the fixed-order solve, the same in
  // every build (fixed_order_dense.h); redundant constraints: the decomposition's
  // least-squares solution
  Vec x;
  if (cod.rank() < n + m || !solve_fixed_order(A, rhs, x)) x = cod.solve(rhs);
  if (!x.allFinite())
    throw RunError("consistent start at t = " + format_number(t) +
                   " s: the accelerations and multipliers are not finite");
  s.a = x.head(n);
  s.lambda = x.tail(m);
  return s;
}

}  // namespace evas::dae
