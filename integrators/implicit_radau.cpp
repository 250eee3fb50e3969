#include "integrators/implicit_radau.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <complex>
#include <limits>
#include <stdexcept>

#include "dae/fixed_order_lu.h"
#include "integrators/common.h"
#include "integrators/radau.h"

namespace evas {

namespace {

using cplx = std::complex<double>;

// The transformation of the Newton iteration, V and V^-1 (D = V diag(g, l,
// conj(l)) V^-1), as the portable build computes them in radau_iia5_tableau():
// Eigen's 3 x 3 eigen-decomposition and inverse round differently in the
// x86-64-v3 build (last bits of V(1..2, 0) and V^-1), and Radau's digits
// followed (docs/problems.md, "Reproducible digits"). Checked against the
// derived values, so a change of the tableau's definition is noticed.
RadauTableau fixed_tableau() {
  RadauTableau T = radau_iia5_tableau();
  const double v[3][3][2] = {{{0x1.75b01984e65dap-4, 0x0p+0},
                              {0x1.901a8baf3f557p-5, 0x1.f356e504b1304p-4},
                              {0x1.901a8baf3f557p-5, -0x1.f356e504b1304p-4}},
                             {{0x1.ef09cfbeab854p-3, 0x0p+0},
                              {-0x1.7fd3ae831dfc4p-2, -0x1.f9a62816c19d1p-4},
                              {-0x1.7fd3ae831dfc4p-2, 0x1.f9a62816c19d1p-4}},
                             {{0x1.ee9dde0d6255dp-1, 0x0p+0},
                              {-0x1.3dffc4a312907p-3, -0x1.cac7068a3b7dep-1},
                              {-0x1.3dffc4a312907p-3, 0x1.cac7068a3b7dep-1}}};
  const double vinv[3][3][2] = {{{0x1.14d64d09039e9p+2, 0x0p+0},
                                 {0x1.5b570c758198bp-2, 0x0p+0},
                                 {0x1.1562f2bdebf51p-1, 0x0p+0}},
                                {{0x1.5454293330d61p-1, -0x1.1bb8439bc94c7p+1},
                                 {-0x1.5ccfec95e1e51p+0, -0x1.ad03a45db5de4p-2},
                                 {0x1.1cd4409880771p-2, 0x1.41b2b9f60787ap-2}},
                                {{0x1.5454293330d61p-1, 0x1.1bb8439bc94c7p+1},
                                 {-0x1.5ccfec95e1e51p+0, 0x1.ad03a45db5de4p-2},
                                 {0x1.1cd4409880771p-2, -0x1.41b2b9f60787ap-2}}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const cplx a(v[i][j][0], v[i][j][1]), b(vinv[i][j][0], vinv[i][j][1]);
      if (std::abs(a - T.V(i, j)) > 1e-14 || std::abs(b - T.Vinv(i, j)) > 1e-14)
        throw std::logic_error("radau: the fixed transformation is not the tableau's");
      T.V(i, j) = a;
      T.Vinv(i, j) = b;
    }
  return T;
}

class ImplicitRadau {
 public:
  ImplicitRadau(ImplicitDae& p, const IntegratorSettings& s)
      : p_(p), s_(s), T_(fixed_tableau()), n_(p.size()), M_(p.mass()) {
    J_.setZero(n_, n_);
    for (auto* v : {&w_, &f0_, &tmp_, &err_, &rhs_r_, &x_r_}) v->setZero(n_);
    for (int i = 0; i < 3; ++i) {
      Z_[i].setZero(n_);
      Zprev_[i].setZero(n_);
      F_[i].setZero(n_);
      dZ_[i].setZero(n_);
    }
    r2r_.setZero(n_);
    r2i_.setZero(n_);
    x2r_.setZero(n_);
    x2i_.setZero(n_);
    idx_.resize(n_);
    for (int i = 0; i < n_; ++i) idx_[i] = std::clamp(p.component_index(i), 1, 3);
    lu_c_.resize(n_);
    // RADAU5's tolerances: the embedded estimate is of order 3 (O(h^4)) while
    // the solution is of order 5, so the user's rtol is mapped to
    // 0.1 rtol^(2/3) for the estimate, atol with the same ratio (Hairer &
    // Wanner's RADAU5, its tolerance transformation); then the Newton
    // tolerance max(10 eps / rtol, min(0.03, sqrt(rtol))) on the mapped rtol.
    rtol_ = 0.1 * std::pow(s.rtol, 2.0 / 3.0);
    atol_ = rtol_ * (s.atol / s.rtol);
    fnewt_ = std::max(10.0 * std::numeric_limits<double>::epsilon() / rtol_,
                      std::min(0.03, std::sqrt(rtol_)));
    fixed_ = s.step_control == StepControl::fixed;
  }

  ImplicitRun run(double t_end) {
    const auto started = std::chrono::steady_clock::now();
    ImplicitRun out;
    Vec yp0;
    p_.initial(y_, yp0);
    double t = 0.0;
    double h = std::min(s_.step > 0.0 ? s_.step : 1e-6 * t_end, t_end);
    const double h_fixed = h;
    if (s_.max_step > 0.0) h = std::min(h, s_.max_step);
    bool first = true, rejected = false, have_history = false, fresh_j = false;
    double h_acc = 0.0, err_acc = 0.0, h_prev = 0.0, h_lu = -1.0;
    // at most 7 iterations (RADAU5's default) or max_iterations when smaller;
    // on fixed steps max_iterations, since a failure there ends the run
    const int max_newton = std::max(1, fixed_ ? s_.max_iterations : std::min(s_.max_iterations, 7));
    double faccon = 1.0;
    try {
      eval_f(t, y_, f0_);
      eval_jacobian(t);
      fresh_j = true;
      while (t < t_end) {
        if (stats_.steps >= s_.max_steps)
          throw RunError("more than max_steps = " + std::to_string(s_.max_steps) + " steps");
        if (t + h >= t_end || t + (fixed_ ? 1e-9 : 0.01) * h + h > t_end)
          h = t_end - t;  // land on t_end
        if (!(h > std::max(s_.min_step, 10.0 * std::numeric_limits<double>::epsilon() * t)))
          throw RunError("the step fell to " + g6(h) + " (min_step " + g6(s_.min_step) + ")");
        weights(h);
        if (h != h_lu) {
          factorize(h);
          h_lu = h;
        }
        start_values(h, h_prev, have_history);
        // the simplified Newton iteration
        bool converged = false;
        double dn_old = 0.0, theta = 0.0;
        faccon = std::pow(std::max(faccon, std::numeric_limits<double>::epsilon()), 0.8);
        int nit = 0;
        for (; nit < max_newton; ++nit) {
          try {
            for (int i = 0; i < 3; ++i) {
              tmp_ = y_ + Z_[i];
              eval_f(t + T_.c[static_cast<std::size_t>(i)] * h, tmp_, F_[i]);
            }
          } catch (const RangeError&) {  // a trial state the problem refuses: a smaller step
            ++stats_.refused_states;
            break;
          }
          newton_update(h);
          double dn = 0.0;
          for (int i = 0; i < 3; ++i) dn += dae::weighted_squared_norm(dZ_[i], w_);
          dn = std::sqrt(dn / (3.0 * n_));
          ++stats_.nonlinear_iterations;
          if (!std::isfinite(dn)) break;
          if (nit > 0) {
            theta = dn / dn_old;
            if (theta >= 0.99) break;  // diverges
            faccon = theta / (1.0 - theta);
            // would not converge within the iterations left at this rate
            if (!fixed_ && faccon * dn * std::pow(theta, max_newton - 1 - nit) / fnewt_ > 1.0)
              break;
          }
          dn_old = std::max(dn, std::numeric_limits<double>::epsilon());
          for (int i = 0; i < 3; ++i) Z_[i] += dZ_[i];
          if (faccon * dn <= fnewt_) {
            converged = true;
            ++nit;
            break;
          }
        }
        if (!converged && fixed_)
          throw RunError("the Newton iteration did not converge at the fixed step");
        if (!converged) {
          ++stats_.convergence_failures;
          h *= 0.5;
          rejected = true;
          if (!fresh_j) {
            eval_jacobian(t);
            fresh_j = true;
            h_lu = -1.0;
          }
          continue;
        }
        const double err = fixed_ ? 0.0 : error_estimate(t, h, first || rejected);
        // step-size factor (RADAU5): safety falls with the iterations used
        const double fac = std::min(0.9, 0.9 * (2 * max_newton + 1) / (nit + 2 * max_newton));
        double quot = std::clamp(std::pow(err, 0.25) / fac, 0.125, 5.0);
        double h_new = h / quot;
        if (err < 1.0) {
          // accepted
          if (!first) {  // Gustafsson's predictive controller
            double facgus = (h_acc / h) * std::pow(err * err / err_acc, 0.25) / 0.9;
            facgus = std::clamp(facgus, 0.125, 5.0);
            quot = std::max(quot, facgus);
            h_new = h / quot;
          }
          h_acc = h;
          err_acc = std::max(1e-2, err);
          first = false;
          ++stats_.steps;
          stats_.last_step = h;
          note_step(stats_, h);
          y_ += Z_[2];
          t += h;
          for (int i = 0; i < 3; ++i) Zprev_[i] = Z_[i];
          have_history = true;
          h_prev = h;
          eval_f(t, y_, f0_);
          if (s_.max_step > 0.0) h_new = std::min(h_new, s_.max_step);
          if (rejected) h_new = std::min(h_new, h);
          rejected = false;
          // keep h (and the factorizations) while asked for 1 to 1.2 times it
          const double ratio = h_new / h;
          if (fixed_)
            h = std::min(h, h_fixed);  // back from a shortened last step
          else if (!(ratio >= 1.0 && ratio <= 1.2))
            h = h_new;
          if (t < t_end) {
            eval_jacobian(t);
            fresh_j = true;
            h_lu = -1.0;
          }
        } else {
          ++stats_.error_test_failures;
          rejected = true;
          fresh_j = false;
          h = first ? 0.1 * h : h_new;
        }
      }
    } catch (const RunError& e) {
      out.failure =
          "radau: " + std::string(e.what()) + " at t = " + g6(t) + " (step " + g6(h) + ")";
    }
    out.t = t;
    out.y = y_;
    out.stats = stats_;
    out.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    out.stats.wall_seconds = out.wall;
    return out;
  }

 private:
  void eval_f(double t, const Vec& y, Vec& f) {
    ++stats_.residual_evals;
    ++p_.rhs_evals;
    p_.rhs(t, y.data(), f.data());
    for (int i = 0; i < n_; ++i)
      if (!std::isfinite(f(i))) throw RangeError("f of " + p_.component_name(i) + " is not finite");
  }

  void eval_jacobian(double t) {
    ++stats_.jacobian_evals;
    ++p_.jacobian_evals;
    p_.rhs_jacobian(t, y_.data(), J_);
  }

  // 1 / scal_i, scal_i = (atol + rtol |y_i|) / hs^(index - 1), hs = min(h, 1):
  // RADAU5 divides by h itself, which relaxes the higher-index components'
  // tolerance as h -> 0 (their estimate grows as h^(1 - index), Hairer &
  // Wanner VII.8) but tightens it for steps longer than one unit of time
  // (Fekete's steps reach 30 s: index-3 at rtol 1e-12 then failed at
  // t = 316 s with the step at 7e-13 s; with the cap it completes).
  void weights(double h) {
    const double hs = std::min(h, 1.0);
    for (int i = 0; i < n_; ++i) {
      double sc = std::fma(rtol_, std::abs(y_(i)), atol_);
      if (idx_[i] == 2) sc /= hs;
      if (idx_[i] == 3) sc /= hs * hs;
      w_(i) = 1.0 / sc;
    }
  }

  void factorize(double h) {
    ++stats_.linear_setups;
    const double gh = T_.g / h;
    const bool real_ok = lu_r_.factor(gh * M_ - J_);
    const cplx lh = T_.l / h;
    lu_c_.re() = lh.real() * M_ - J_;
    lu_c_.im() = lh.imag() * M_;
    if (!lu_c_.factor()) throw RunError("the complex iteration matrix is singular");
    if (!real_ok) throw RunError("the real iteration matrix (g/h M - J) is singular");
  }

  // Lagrange weight of node m (0: c1, 1: c2, 2: 1) at s over the nodes 0, c1, c2, 1
  double lagrange(int m, double s) const {
    const double nodes[4] = {0.0, T_.c[0], T_.c[1], 1.0};
    double w = 1.0;
    for (int k = 0; k < 4; ++k)
      if (k != m + 1) w *= (s - nodes[k]) / (nodes[m + 1] - nodes[k]);
    return w;
  }

  // Z from the last step's collocation polynomial at the new stage times
  // (Hairer & Wanner IV.8), or zero on the first step and after a restart
  void start_values(double h, double h_prev, bool have_history) {
    if (!have_history || !(h_prev > 0.0)) {
      for (auto& z : Z_) z.setZero();
      return;
    }
    const double r = h / h_prev;
    for (int j = 0; j < 3; ++j) {
      const double s = 1.0 + r * T_.c[static_cast<std::size_t>(j)];
      Z_[j] = -Zprev_[2];
      for (int m = 0; m < 3; ++m) Z_[j] += lagrange(m, s) * Zprev_[m];
    }
  }

  // dZ from the transformed systems for the residuals of the current Z, F
  void newton_update(double h) {
    // R_i = (1/h) sum_j D_ij M Z_j - F_i; its transforms by Vinv: real row 0, complex row 1
    std::array<Vec, 3> MZ;
    for (int j = 0; j < 3; ++j) dae::mat_vec_fixed_order(M_, Z_[j], MZ[j]);
    std::array<Vec, 3> R;
    for (int i = 0; i < 3; ++i) {
      R[i] = -F_[i];
      for (int j = 0; j < 3; ++j) R[i] += (T_.D(i, j) / h) * MZ[j];
    }
    rhs_r_.setZero();
    r2r_.setZero();
    r2i_.setZero();
    for (int j = 0; j < 3; ++j) {
      rhs_r_ -= T_.Vinv(0, j).real() * R[j];
      r2r_ -= T_.Vinv(1, j).real() * R[j];
      r2i_ -= T_.Vinv(1, j).imag() * R[j];
    }
    lu_r_.solve(rhs_r_, x_r_);
    x2r_ = r2r_;
    x2i_ = r2i_;
    lu_c_.solve(x2r_, x2i_);
    for (int i = 0; i < 3; ++i) {
      const cplx v2 = T_.V(i, 1);
      dZ_[i] = T_.V(i, 0).real() * x_r_ + 2.0 * (v2.real() * x2r_ - v2.imag() * x2i_);
    }
  }

  double error_estimate(double t, double h, bool again) {
    // f0 + (g/h) sum_j e_j M Z_j, filtered by (g/h M - J)^-1
    Vec sumz = Vec::Zero(n_);
    for (int j = 0; j < 3; ++j) sumz += T_.e[static_cast<std::size_t>(j)] * Z_[j];
    Vec msum;
    dae::mat_vec_fixed_order(M_, sumz, msum);
    const Vec mz = (T_.g / h) * msum;
    lu_r_.solve(f0_ + mz, err_);
    double e = std::sqrt(dae::weighted_squared_norm(err_, w_) / n_);
    if (e >= 1.0 && again) {
      tmp_ = y_ + err_;
      Vec f1(n_);
      try {
        eval_f(t, tmp_, f1);
      } catch (const RangeError&) {
        ++stats_.refused_states;
        return e;  // the first estimate stands
      }
      lu_r_.solve(f1 + mz, err_);
      e = std::sqrt(dae::weighted_squared_norm(err_, w_) / n_);
    }
    return std::max(e, 1e-10);
  }

  ImplicitDae& p_;
  const IntegratorSettings& s_;
  const RadauTableau T_;
  const int n_;
  const Mat M_;
  Mat J_;
  Vec y_, w_, f0_, tmp_, err_, rhs_r_, x_r_, r2r_, r2i_, x2r_, x2i_;
  std::array<Vec, 3> Z_, Zprev_, F_, dZ_;
  std::vector<int> idx_;

  // Fixed-order kernels (dae/fixed_order_lu.h) so the portable and the
  // x86-64-v3 build give the same digits; SplitComplexLU is plain loops already.
  dae::FixedOrderLU lu_r_;
  SplitComplexLU lu_c_;
  double fnewt_ = 0.03, rtol_ = 0.0, atol_ = 0.0;
  bool fixed_ = false;  // step_control=fixed: every step accepted, h kept
  IntegratorStats stats_;
};

}  // namespace

ImplicitRun integrate_implicit_radau(ImplicitDae& p, double t_end, const IntegratorSettings& s) {
  if (!(s.rtol > 0.0) || !(s.atol > 0.0)) throw InputError("radau: rtol and atol must be > 0");
  ImplicitRadau r(p, s);
  return r.run(t_end);
}

}  // namespace evas
