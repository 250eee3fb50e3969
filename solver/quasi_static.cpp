// Quasi-static coordinates: mass diagonal and consistent start (quasi_static.h).
#include "solver/quasi_static.h"

#include <Eigen/LU>
#include <cmath>
#include <string>

namespace evas {

namespace {

// The block of A (on the problem's Jacobian pattern) in the rows and columns
// of the quasi-static coordinates qs, dense.
Mat quasi_static_block(const SpMat& A, const std::vector<int>& qs) {
  const int nq = static_cast<int>(qs.size());
  std::vector<int> at(static_cast<std::size_t>(A.cols()), -1);
  for (int k = 0; k < nq; ++k) at[static_cast<std::size_t>(qs[k])] = k;
  Mat B = Mat::Zero(nq, nq);
  for (int k = 0; k < nq; ++k)
    for (SpMat::InnerIterator it(A, qs[k]); it; ++it)
      if (const int r = at[static_cast<std::size_t>(it.row())]; r >= 0) B(r, k) = it.value();
  return B;
}

}  // namespace

Vec mass_diagonal(const Problem& p) {
  Vec m = Vec::Ones(p.size());
  for (int i : p.quasi_static()) m[i] = 0.0;
  return m;
}

void settle_quasi_static(Problem& p, double t, Vec& q, Vec& v) {
  const std::vector<int>& qs = p.quasi_static();
  if (qs.empty()) return;
  const int n = p.size(), nq = static_cast<int>(qs.size());
  for (int i : qs) v[i] = 0.0;
  SpMat K = p.jacobian_pattern(), C = p.jacobian_pattern();
  Vec f(n), r(nq), dq(nq);
  constexpr int kMaxIterations = 50;
  // f at q, or false when the model refuses the state (RangeError: a film
  // closed, a contact out of range): the step is then halved
  auto residual = [&](const Vec& qt, Vec& rt) {
    try {
      p.force(t, qt.data(), v.data(), f.data());
    } catch (const RangeError&) {
      return false;
    }
    for (int a = 0; a < nq; ++a) rt[a] = f[qs[a]];
    return rt.allFinite();
  };
  if (!residual(q, r)) {
    p.force(t, q.data(), v.data(), f.data());  // (the model's own message)
    throw RunError("the quasi-static modes' start: the loads at the initial state are not finite");
  }
  Vec qt = q, rt(nq);
  for (int it = 0; it < kMaxIterations; ++it) {
    p.force_jacobian(t, q.data(), v.data(), K, C);
    const Eigen::PartialPivLU<Mat> lu(quasi_static_block(K, qs));
    dq = lu.solve(r);
    if (!dq.allFinite()) break;
    double qmax = 0.0;
    for (int a = 0; a < nq; ++a) qmax = std::max(qmax, std::abs(q[qs[a]]));
    // Newton converges quadratically: a correction at round-off of q ends it
    if (dq.lpNorm<Eigen::Infinity>() <= 1e-13 * qmax) {
      for (int a = 0; a < nq; ++a) q[qs[a]] -= dq[a];
      return;
    }
    // damped: the full step, halved while the model refuses the state or the
    // residual grows (Deuflhard, Newton Methods for Nonlinear Problems, 2004,
    // ch. 3: a monotonicity test on the residual)
    double lambda = 1.0;
    bool taken = false;
    for (int cut = 0; cut < 30; ++cut) {
      qt = q;
      for (int a = 0; a < nq; ++a) qt[qs[a]] -= lambda * dq[a];
      if (residual(qt, rt) && (rt.norm() < r.norm() || lambda < 1e-3)) {
        taken = true;
        break;
      }
      lambda *= 0.5;
    }
    if (!taken) break;
    q = qt;
    r = rt;
    if (r.lpNorm<Eigen::Infinity>() == 0.0) return;
  }
  Eigen::Index worst = 0;
  if (r.size() > 0) r.cwiseAbs().maxCoeff(&worst);
  throw RunError(
      "the quasi-static modes' start (their static deflection at t = " + format_number(t) +
      " s) did not converge (Newton's method with step halving, at "
      "most " +
      std::to_string(kMaxIterations) + " iterations); largest residual " +
      format_number(std::abs(r[worst])) + " at " +
      p.describe_coordinate(qs[static_cast<std::size_t>(worst)]));
}

void quasi_static_accelerations(Problem& p, double t, const Vec& q, const Vec& v, Vec& a) {
  const std::vector<int>& qs = p.quasi_static();
  if (qs.empty()) return;
  const int n = p.size(), nq = static_cast<int>(qs.size());
  for (int i : qs) a[i] = 0.0;
  // step: 1e-8 of the time scale set by the fastest quasi-static coordinate's
  // velocity against its size, never above 1e-8 s; error O(e^2 omega^3)
  double scale = 1e-8;
  for (int i : qs)
    if (std::abs(v[i]) > 0.0 && std::abs(q[i]) > 0.0)
      scale = std::min(scale, 1e-8 * std::abs(q[i] / v[i]));
  const double e = scale;
  Vec f0(n), f1(n), f2(n), qe(n), ve(n);
  auto at = [&](double s, Vec& out) {
    qe = q + s * v;
    ve = v + s * a;
    p.force(t + s, qe.data(), ve.data(), out.data());
  };
  at(0.0, f0);
  at(e, f1);
  at(2.0 * e, f2);
  Vec g(nq);
  for (int k = 0; k < nq; ++k) g[k] = (-3.0 * f0[qs[k]] + 4.0 * f1[qs[k]] - f2[qs[k]]) / (2.0 * e);
  SpMat K = p.jacobian_pattern(), C = p.jacobian_pattern();
  p.force_jacobian(t, q.data(), v.data(), K, C);
  const Vec aq = Eigen::PartialPivLU<Mat>(quasi_static_block(C, qs)).solve(g);
  if (!aq.allFinite()) return;  // (a_Q = 0 stays: the integrator's first steps resolve it)
  for (int k = 0; k < nq; ++k) a[qs[k]] = -aq[k];
}

}  // namespace evas
