// An integrator plug-in for evas: the two-stage Radau IIA method (order 3,
// L-stable; E. Hairer, G. Wanner, "Solving Ordinary Differential Equations II",
// 2nd ed., Springer 1996, sec. IV.5, Table 5.5) on the first-order form of
//     qdd + f(t, q, v) = 0,   y = [q; v],   y' = F(t, y) = [v; -f(t, q, v)],
// with a fixed step (halved on a failed Newton iteration, as evas's own fixed-
// step methods do). Stage equations (Hairer-Wanner IV.8, in the increments
// Z_i = Y_i - y_n):
//     Z_i = h sum_j a_ij F(t_n + c_j h, y_n + Z_j),   i = 1, 2,
//     c = (1/3, 1),  A = [5/12 -1/12; 3/4 1/4],  y_{n+1} = y_n + Z_2,
// solved by simplified Newton with the matrix I - h A (x) J, J = dF/dy at
// (t_n, y_n) = [0 I; -K -C] from the model's analytic K = df/dq, C = df/dv,
// factorised by Eigen's sparse LU once per step. (A teaching example: evas's
// built-in `radau` is the three-stage, fifth-order method, integrators/radau.cpp.)
//
// Build it against an installed evas (docs/extending.md):
//     cmake -S examples/radau_plugin -B build-radau && cmake --build build-radau
//     evas run scenes/demo.yaml --plugin build-radau/libevas_radau.so --integrator radau-iia
#include <Eigen/SparseLU>
#include <chrono>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "integrators/integrator.h"
#include "integrators/plugin.h"

namespace {

using evas::Integrator;
using evas::IntegratorSettings;
using evas::IntegratorStats;
using evas::Problem;
using evas::RunError;
using evas::SpMat;
using evas::Vec;

constexpr double kC[2] = {1.0 / 3.0, 1.0};
constexpr double kA[2][2] = {{5.0 / 12.0, -1.0 / 12.0}, {3.0 / 4.0, 1.0 / 4.0}};

class RadauIIA final : public Integrator {
 public:
  std::string name() const override { return "radau-iia"; }

  void init(Problem& p, double t0, const Vec& q0, const Vec& v0,
            const IntegratorSettings& s) override {
    if (p.constraint_count() > 0 || p.has_mass())
      throw RunError("radau-iia: this example solves qdd + f = 0 only (no constraints, M = I)");
    if (!(s.step > 0.0)) throw RunError("radau-iia: step must be > 0");
    p_ = &p;
    s_ = s;
    n_ = p.size();
    stats_ = IntegratorStats{};
    K_ = p.jacobian_pattern();
    C_ = p.jacobian_pattern();
    f_.resize(n_);
    restart(t0, q0, v0);
  }

  void restart(double t, const Vec& q, const Vec& v) override {
    t_ = t;
    y_.resize(2 * n_);
    y_ << q, v;
  }

  void advance(double tout, bool land, Vec& q, Vec& v) override {
    (void)land;  // every output is landed on exactly: no interpolation
    const auto start = std::chrono::steady_clock::now();
    while (tout - t_ > 1e-14 * std::max(1.0, std::abs(tout))) {
      double h = std::min(s_.step, tout - t_);
      while (!step(h)) {
        h *= 0.5;
        ++stats_.convergence_failures;
        if (h < s_.min_step)
          throw RunError("radau-iia: Newton failed at t = " + std::to_string(t_) +
                         " s with the step cut below min_step = " + std::to_string(s_.min_step) +
                         " s; " + p_->describe_state(t_, y_.data(), y_.data() + n_));
      }
      step_done(t_, h);
    }
    q = y_.head(n_);
    v = y_.tail(n_);
    stats_.wall_seconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }

  IntegratorStats stats() const override { return stats_; }

 private:
  // F(t, y) into out (2n).
  void rhs(double t, const Vec& y, Eigen::Ref<Vec> out) {
    p_->force(t, y.data(), y.data() + n_, f_.data());
    ++stats_.residual_evals;
    out.head(n_) = y.tail(n_);
    out.tail(n_) = -f_;
  }

  // Iteration matrix I - h A (x) J (4n x 4n) from K, C at (t_n, y_n).
  void build_matrix(double h) {
    p_->force_jacobian(t_, y_.data(), y_.data() + n_, K_, C_);
    ++stats_.jacobian_evals;
    const int m = 2 * n_;
    std::vector<Eigen::Triplet<double>> tr;
    tr.reserve(static_cast<std::size_t>(4 * (m + 2 * K_.nonZeros() + n_)));
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) {
        const double ha = h * kA[i][j];
        const int r0 = i * m, c0 = j * m;
        if (i == j)
          for (int k = 0; k < m; ++k) tr.emplace_back(r0 + k, c0 + k, 1.0);
        // J = [0 I; -K -C]: the q rows take -ha * I on the v columns
        for (int k = 0; k < n_; ++k) tr.emplace_back(r0 + k, c0 + n_ + k, -ha);
        for (int col = 0; col < n_; ++col) {
          for (SpMat::InnerIterator it(K_, col); it; ++it)
            tr.emplace_back(r0 + n_ + static_cast<int>(it.row()), c0 + col, ha * it.value());
          for (SpMat::InnerIterator it(C_, col); it; ++it)
            tr.emplace_back(r0 + n_ + static_cast<int>(it.row()), c0 + n_ + col, ha * it.value());
        }
      }
    SpMat A(2 * m, 2 * m);
    A.setFromTriplets(tr.begin(), tr.end());
    lu_.compute(A);
    ++stats_.linear_setups;
    if (lu_.info() != Eigen::Success)
      throw RunError("radau-iia: the iteration matrix is singular at t = " + std::to_string(t_));
  }

  // One step of size h from (t_, y_); false when Newton does not converge.
  bool step(double h) {
    build_matrix(h);
    const int m = 2 * n_;
    Vec Z = Vec::Zero(2 * m), F(2 * m), r(2 * m), Y(m);
    // weights of the convergence test: SUNDIALS' WRMS norm
    Vec w(m);
    for (int k = 0; k < m; ++k) w[k] = 1.0 / (s_.rtol * std::abs(y_[k]) + s_.atol);
    double prev = 0.0;
    for (int it = 0; it < s_.max_iterations; ++it) {
      for (int i = 0; i < 2; ++i) {
        Y = y_ + Z.segment(i * m, m);
        rhs(t_ + kC[i] * h, Y, F.segment(i * m, m));
      }
      for (int i = 0; i < 2; ++i)
        r.segment(i * m, m) =
            -(Z.segment(i * m, m) - h * (kA[i][0] * F.head(m) + kA[i][1] * F.tail(m)));
      const Vec dZ = lu_.solve(r);
      ++stats_.linear_solves;
      ++stats_.nonlinear_iterations;
      if (!dZ.allFinite()) return false;
      Z += dZ;
      double norm = 0.0;
      for (int i = 0; i < 2; ++i)
        norm = std::max(norm, std::sqrt((dZ.segment(i * m, m).cwiseProduct(w)).squaredNorm() / m));
      if (norm <= 1e-2) {  // well inside the tolerance (cf. SUNDIALS' 0.33 x 0.1)
        y_ += Z.tail(m);
        t_ += h;
        ++stats_.steps;
        stats_.last_step = h;
        if (stats_.min_step == 0.0 || h < stats_.min_step) stats_.min_step = h;
        stats_.max_step = std::max(stats_.max_step, h);
        return true;
      }
      if (it > 0 && norm > 2.0 * prev) return false;  // diverging
      prev = norm;
    }
    return false;
  }

  Problem* p_ = nullptr;
  IntegratorSettings s_;
  int n_ = 0;
  double t_ = 0.0;
  Vec y_, f_;
  SpMat K_, C_;
  Eigen::SparseLU<SpMat> lu_;
  IntegratorStats stats_;
};

}  // namespace

EVAS_PLUGIN_EXPORT int evas_plugin_init(int abi_version) {
  if (abi_version != EVAS_PLUGIN_ABI_VERSION) return 1;
  evas::register_integrator(
      "radau-iia", [] { return std::make_unique<RadauIIA>(); },
      "two-stage Radau IIA (order 3, L-stable), fixed step; example plug-in");
  return 0;
}
