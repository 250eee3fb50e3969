// Radau IIA, three stages, order 5 (stage order 3, stiffly accurate, L-stable):
// E. Hairer, G. Wanner, Solving Ordinary Differential Equations II, 2nd ed.
// (Springer 1996), section IV.5 and IV.8 (the
// simplified Newton iteration and its transformation).
//
// On the first-order form y = [q; v], y' = F(t, y) = [v; -f(t, q, v)], one step
// from y_n to y_{n+1} = y_n + Z_3 solves the collocation equations for the stage
// increments Z_i = Y_i - y_n (i = 1..3, at t_n + c_i h):
//     G_i(Z) = (1/h) sum_j D_ij Z_j - F(t_n + c_i h, y_n + Z_i) = 0,   D = A^-1.
// D has one real eigenvalue g and a complex pair l, conj(l): D = V diag(g, l, conj(l)) V^-1.
// With the Jacobian J = dF/dy = [0, I; -K, -C] held fixed (simplified Newton),
// the transformed increments W = V^-1 Z decouple into one real and one complex
// linear system of the first-order size,
//     (g/h I - J) dW_1 = -(V^-1 G)_1,   (l/h I - J) dW_2 = -(V^-1 G)_2,
// and dZ = V dW (the third transformed row is the conjugate of the second).
// Each is reduced to the modal size n as in integrators/second_order_ls.h: for
// (c I - J) [x_q; x_v] = [r_q; r_v],
//     (K + c C + c^2 I) x_q = r_v + (c I + C) r_q,   x_v = c x_q - r_q,
// a real matrix at c = g/h and a complex one at c = l/h, both dense LU here
// (the complex one on split real and imaginary parts, SplitComplexLU).
//
// Start values: the collocation polynomial of the last step extrapolated to
// the new stage times (Hairer & Wanner, IV.8). Convergence (IV.8):
// eta ||dZ|| <= kappa with eta = theta / (1 - theta), theta the contraction of
// the last two updates (on the first update eta carried over from the last
// step), ||.|| the weighted RMS norm of the error test (w_i = 1/(rtol |y_i| +
// atol)), kappa = kKappa below; at most min(max_iterations, 7) iterations (7:
// RADAU5's default), and the step fails early when the rate says it would not
// converge within them. The Jacobian is kept across steps and evaluated again
// (at the step's start) when an iteration fails with an older one, or after a
// step whose last update contracted more slowly than kRefreshTheta; the two
// matrices are factorized again when h changes.
//
// Steps (fixed_step.h): fixed (settings.step), cut into sub-steps where the
// iteration fails, or adaptive: the embedded order-3 estimate of IV.8,
// err = (I - h/g J)^-1 (yhat - y_{n+1}) = O(h^4), under the PI
// controller with k = 4; h is kept while the controller asks for 1 to 1.2 times
// it (RADAU5's default), since a new h costs two factorizations. Outputs
// between steps: the collocation polynomial of the step (degree 3).
//
// On the paper's engine (docs/engine-speed.md): a fifth of generalized-alpha's
// steps for the same error, but each step takes about 3 iterations of 3
// residuals and two solves, and the film forces change the Jacobian enough that
// it is evaluated every 4-5 steps.
#include "integrators/radau.h"

#include <Eigen/Dense>
#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <limits>
#include <vector>

#include "integrators/common.h"
#include "integrators/fixed_step.h"
#include "integrators/second_order_ls.h"

namespace evas {

using cplx = std::complex<double>;

RadauTableau radau_iia5_tableau() {
  RadauTableau T;
  const double s6 = std::sqrt(6.0);
  T.c = {(4.0 - s6) / 10.0, (4.0 + s6) / 10.0, 1.0};
  T.A << (88.0 - 7.0 * s6) / 360.0, (296.0 - 169.0 * s6) / 1800.0, (-2.0 + 3.0 * s6) / 225.0,
      (296.0 + 169.0 * s6) / 1800.0, (88.0 + 7.0 * s6) / 360.0, (-2.0 - 3.0 * s6) / 225.0,
      (16.0 - s6) / 36.0, (16.0 + s6) / 36.0, 1.0 / 9.0;
  T.D = T.A.inverse();
  Eigen::EigenSolver<Eigen::Matrix3d> es(T.D);
  int ir = -1, ic = -1;
  for (int k = 0; k < 3; ++k) {
    const cplx e = es.eigenvalues()[k];
    if (std::abs(e.imag()) < 1e-12 * std::abs(e))
      ir = k;
    else if (e.imag() > 0.0)
      ic = k;
  }
  if (ir < 0 || ic < 0) throw std::logic_error("radau: eigenvalues of the tableau");
  T.g = es.eigenvalues()[ir].real();
  T.l = es.eigenvalues()[ic];
  // the real eigenvector made real (it may come with a complex phase)
  Eigen::Vector3cd vr = es.eigenvectors().col(ir);
  int big = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(vr[k]) > std::abs(vr[big])) big = k;
  vr /= vr[big] / std::abs(vr[big]);
  T.V.col(0) = vr;
  T.V.col(1) = es.eigenvectors().col(ic);
  T.V.col(2) = es.eigenvectors().col(ic).conjugate();
  T.Vinv = T.V.inverse();
  // Embedded order-3 formula (Hairer & Wanner IV.8): yhat = y_n + h (b0
  // F(y_n) + sum_i bh_i F(Y_i)) with b0 = 1/g and bh from the quadrature
  // conditions b0 0^(k-1) + sum_i bh_i c_i^(k-1) = 1/k, k = 1..3; since h F(Y_i) =
  // (D Z)_i, yhat - y = h b0 F(y_n) + sum_j e_j Z_j with e_j = sum_i (bh_i - b_i) D_ij.
  T.b0 = 1.0 / T.g;
  Eigen::Matrix3d vdm;
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < 3; ++i) vdm(k, i) = std::pow(T.c[static_cast<std::size_t>(i)], k);
  const Eigen::Vector3d bh = vdm.lu().solve(Eigen::Vector3d(1.0 - T.b0, 0.5, 1.0 / 3.0));
  const Eigen::Vector3d e = T.D.transpose() * (bh - T.A.row(2).transpose());
  T.e = {e[0], e[1], e[2]};
  return T;
}

namespace {

// Newton stops when the estimated remaining error is below this share of the
// error test's unit (Hairer & Wanner's fnewt is 0.03 - 0.1 of theirs).
constexpr double kKappa = 0.05;
// Newton iterations per step at most (Hairer & Wanner's RADAU5 default: 7), or
// max_iterations when smaller; a slower step takes a new Jacobian.
constexpr int kMaxNewton = 7;
// A step whose last update contracted by less than this asks for a new Jacobian
// before the next step.
constexpr double kRefreshTheta = 0.3;

class Radau final : public FixedStepIntegrator {
 public:
  std::string name() const override { return "radau"; }

 protected:
  void setup() override {
    if (!(s_.rtol > 0.0) || !(s_.atol > 0.0))
      throw InputError("radau: rtol and atol must be > 0 (they weigh the Newton test)");
    tab_ = radau_iia5_tableau();
    so_ = std::make_unique<SecondOrderSolver>(p_->jacobian_pattern());
    const int n2 = 2 * n_;
    for (int i = 0; i < 3; ++i) {
      Z_[i].setZero(n2);
      Zprev_[i].setZero(n2);
      Ztrial_[i].setZero(n2);
      F_[i].resize(n2);
      G_[i].resize(n2);
      dZ_[i].resize(n2);
    }
    w_.resize(n2);
    err_.setZero(n2);
    r1_.resize(n2);
    x1_.resize(n2);
    tq_.resize(n_);
    tv_.resize(n_);
    r2r_.resize(n2);
    r2i_.resize(n2);
    x2r_.resize(n2);
    x2i_.resize(n2);
    cqr_.resize(n_);
    cqi_.resize(n_);
    luc_.resize(n_);
    have_jacobian_ = false;
    h_factor_ = 0.0;
    eta_ = 1.0;
  }

  void accepted() override {
    for (int i = 0; i < 3; ++i) Zprev_[i].swap(Ztrial_[i]);
  }

  // The embedded estimate filtered by the real iteration matrix (Hairer &
  // Wanner IV.8): err = (I - h/g J)^-1 (yhat - y_{n+1}), of order 4;
  // computed in step() where the factorization is at hand.
  void local_error(double, bool, Vec& eq, Vec& ev) const override {
    eq = err_.head(n_);
    ev = err_.tail(n_);
  }
  int error_order() const override { return 4; }
  // A new step costs two factorizations: keep h when the controller asks for
  // between 1 and 1.2 times it (Hairer & Wanner's RADAU5 default).
  double keep_step(double h, double proposal) const override {
    return proposal >= h && proposal <= 1.2 * h ? h : proposal;
  }
  // The collocation polynomial of the last step: y(t_prev + s h) = y_prev +
  // sum_m L_m(s) Z_m over the nodes 0, c_1, c_2, 1 (Z = 0 at s = 0).
  void interpolate(double t, Vec& q, Vec& v) const override {
    const double t0 = previous_time();
    const double s = (t - t0) / (t_ - t0);
    const std::array<double, 3> L = collocation_weights(s);
    // after accept() the previous state is in q1_, v1_ and the step's Z in Zprev_
    q = q1_ + L[0] * Zprev_[0].head(n_) + L[1] * Zprev_[1].head(n_) + L[2] * Zprev_[2].head(n_);
    v = v1_ + L[0] * Zprev_[0].tail(n_) + L[1] * Zprev_[1].tail(n_) + L[2] * Zprev_[2].tail(n_);
  }

  bool step(double t, double h) override {
    const int n = n_;
    // weights of the error test at the step's start
    for (int i = 0; i < n; ++i) {
      w_[i] = 1.0 / (s_.rtol * std::abs(q_[i]) + s_.atol);
      w_[n + i] = 1.0 / (s_.rtol * std::abs(v_[i]) + s_.atol);
    }
    for (int attempt = 0; attempt < 2; ++attempt) {
      if (!have_jacobian_) {
        p_->force_jacobian(t, q_.data(), v_.data(), so_->K(), so_->C());
        ++stats_.jacobian_evals;
        have_jacobian_ = true;
        fresh_ = true;
        h_factor_ = 0.0;
      }
      if (h != h_factor_) factorize(t, h);
      start_values(h);
      const Outcome o = iterate(t, h);
      if (o == Outcome::Converged) {
        finish(h);
        return true;
      }
      if (o == Outcome::Refused) return false;
      // diverged or too slow: a new Jacobian, unless this one is new already
      if (fresh_) return false;
      have_jacobian_ = false;
    }
    return false;
  }

 private:
  enum class Outcome { Converged, Failed, Refused };

  void factorize(double t, double h) {
    const double cr = tab_.g / h;
    if (!so_->factor_matrix(1.0, cr, cr * cr))
      throw RunError("radau: the real iteration matrix is singular" + where(t + h, h, q_, v_));
    const cplx cc = tab_.l / h, cc2 = cc * cc;
    Mat& re = luc_.re();
    Mat& im = luc_.im();
    re.setZero();
    im.setZero();
    const SpMat& K = so_->K();
    const SpMat& C = so_->C();
    for (int j = 0; j < n_; ++j) {
      for (SpMat::InnerIterator it(K, j); it; ++it) re(it.row(), j) += it.value();
      for (SpMat::InnerIterator it(C, j); it; ++it) {
        re(it.row(), j) += cc.real() * it.value();
        im(it.row(), j) += cc.imag() * it.value();
      }
      re(j, j) += cc2.real();
      im(j, j) += cc2.imag();
    }
    if (!luc_.factor())
      throw RunError("radau: the complex iteration matrix is singular" + where(t + h, h, q_, v_));
    stats_.linear_setups += 2;
    h_factor_ = h;
  }

  // Lagrange weights of the nodes c_1, c_2, 1 at s, over the nodes 0, c_1, c_2, 1
  // (the node 0 carries Z = 0): u(s) = sum_m L_m(s) Z_m.
  std::array<double, 3> collocation_weights(double s) const {
    const std::array<double, 4> x = {0.0, tab_.c[0], tab_.c[1], 1.0};
    std::array<double, 3> L{};
    for (int m = 1; m < 4; ++m) {
      double p = 1.0;
      for (int l = 0; l < 4; ++l)
        if (l != m) p *= (s - x[l]) / (x[m] - x[l]);
      L[static_cast<std::size_t>(m - 1)] = p;
    }
    return L;
  }

  // Z from the last step's collocation polynomial u (u(0) = 0, u(c_i) = Zprev_i
  // in units of the last step), evaluated at the new stage times 1 + r c_j.
  void start_values(double h) {
    if (!has_history() || !(h_prev_ > 0.0)) {  // Zprev_ holds the step before
      for (int i = 0; i < 3; ++i) Z_[i].setZero();
      extrapolated_ = false;
      return;
    }
    const double r = h / h_prev_;
    for (int j = 0; j < 3; ++j) {
      const double s = 1.0 + r * tab_.c[static_cast<std::size_t>(j)];
      const std::array<double, 3> L = collocation_weights(s);
      Z_[j] = L[0] * Zprev_[0] + L[1] * Zprev_[1] + (L[2] - 1.0) * Zprev_[2];
    }
    extrapolated_ = true;
  }

  double wnorm(const std::array<Vec, 3>& z) const {
    double sum = 0.0;
    for (int i = 0; i < 3; ++i) sum += z[i].cwiseProduct(w_).squaredNorm();
    return std::sqrt(sum / (6.0 * n_));
  }

  // (c I - J) x = r on the reduced real system (x, r 2n long; may not alias)
  void solve_real(double c, const Vec& r, Vec& x) {
    const int n = n_;
    tq_.noalias() = so_->C() * r.head(n);
    x.head(n) = r.tail(n) + c * r.head(n) + tq_;
    so_->solve_matrix(x.data(), x.data());
    x.tail(n) = c * x.head(n) - r.head(n);
  }

  // the complex system on split parts: (c I - J)(xr + i xi) = rr + i ri
  void solve_complex(cplx c, const Vec& rr, const Vec& ri, Vec& xr, Vec& xi) {
    const int n = n_;
    const double a = c.real(), b = c.imag();
    tq_.noalias() = so_->C() * rr.head(n);
    tv_.noalias() = so_->C() * ri.head(n);
    cqr_ = rr.tail(n) + a * rr.head(n) - b * ri.head(n) + tq_;
    cqi_ = ri.tail(n) + a * ri.head(n) + b * rr.head(n) + tv_;
    luc_.solve(cqr_, cqi_);
    xr.head(n) = cqr_;
    xi.head(n) = cqi_;
    xr.tail(n) = a * cqr_ - b * cqi_ - rr.head(n);
    xi.tail(n) = a * cqi_ + b * cqr_ - ri.head(n);
  }

  Outcome iterate(double t, double h) {
    const int n = n_;
    const double hinv = 1.0 / h;
    double prev = 0.0, theta = 0.0;
    const int max_it = std::min(s_.max_iterations, kMaxNewton);
    for (int k = 0; k < max_it; ++k) {
      bool from_zero = false;
      for (int i = 0; i < 3 && !from_zero; ++i) {
        const double ti = t + tab_.c[static_cast<std::size_t>(i)] * h;
        tq_ = q_ + Z_[i].head(n);
        tv_ = v_ + Z_[i].tail(n);
        try {
          p_->force(ti, tq_.data(), tv_.data(), F_[i].data() + n);
        } catch (const RangeError& e) {
          ++stats_.refused_states;
          if (k == 0 && extrapolated_) {  // the start values: from zero instead
            for (int m = 0; m < 3; ++m) Z_[m].setZero();
            extrapolated_ = false;
            from_zero = true;
            continue;
          }
          failure_ = "radau: stage " + std::to_string(i + 1) + " of iteration " +
                     std::to_string(k) + " reached a state the model refuses (" + e.what() + ")" +
                     where(t + h, h, q_, v_);
          return Outcome::Refused;
        }
        ++stats_.residual_evals;
        F_[i].head(n) = tv_;
        F_[i].tail(n) = -F_[i].tail(n);
      }
      if (from_zero) {
        k = -1;
        continue;
      }
      for (int i = 0; i < 3; ++i)
        G_[i] = hinv * (tab_.D(i, 0) * Z_[0] + tab_.D(i, 1) * Z_[1] + tab_.D(i, 2) * Z_[2]) - F_[i];
      // transformed residuals: real row 0, complex row 1 of V^-1
      r1_ = -(tab_.Vinv(0, 0).real() * G_[0] + tab_.Vinv(0, 1).real() * G_[1] +
              tab_.Vinv(0, 2).real() * G_[2]);
      r2r_ = -(tab_.Vinv(1, 0).real() * G_[0] + tab_.Vinv(1, 1).real() * G_[1] +
               tab_.Vinv(1, 2).real() * G_[2]);
      r2i_ = -(tab_.Vinv(1, 0).imag() * G_[0] + tab_.Vinv(1, 1).imag() * G_[1] +
               tab_.Vinv(1, 2).imag() * G_[2]);
      solve_real(tab_.g * hinv, r1_, x1_);
      solve_complex(tab_.l * hinv, r2r_, r2i_, x2r_, x2i_);
      stats_.linear_solves += 2;
      ++stats_.nonlinear_iterations;
      for (int i = 0; i < 3; ++i) {
        dZ_[i] = tab_.V(i, 0).real() * x1_ + (2.0 * tab_.V(i, 1).real()) * x2r_ -
                 (2.0 * tab_.V(i, 1).imag()) * x2i_;
        Z_[i] += dZ_[i];
      }
      {
        const double dn = wnorm(dZ_);
        if (!std::isfinite(dn)) {
          failure_ = "radau: the Newton update is not finite" + where(t + h, h, q_, v_);
          return Outcome::Failed;
        }
        if (k > 0) {
          theta = prev > 0.0 ? dn / prev : 0.0;
          if (theta >= 0.99) {
            failure_ = "radau: the Newton iteration diverges (contraction " + format_number(theta) +
                       ")" + where(t + h, h, q_, v_);
            return Outcome::Failed;
          }
          eta_ = theta / (1.0 - theta);
          // would not converge within max_iterations at this rate
          const double left = max_it - 1 - k;
          if (eta_ * dn * std::pow(theta, left) > kKappa) {
            failure_ = "radau: the Newton iteration converges too slowly (contraction " +
                       format_number(theta) + ")" + where(t + h, h, q_, v_);
            return Outcome::Failed;
          }
        } else {
          eta_ = std::pow(std::max(eta_, std::numeric_limits<double>::epsilon()), 0.8);
        }
        prev = dn;
        if (eta_ * dn <= kKappa || dn == 0.0) {
          stats_.max_step_iterations = std::max<long>(stats_.max_step_iterations, k + 1);
          theta_last_ = theta;
          return Outcome::Converged;
        }
      }
    }
    failure_ = "radau: the Newton iteration did not converge in " + std::to_string(max_it) +
               " iterations" + where(t + h, h, q_, v_);
    return Outcome::Failed;
  }

  void finish(double h) {
    const int n = n_;
    q1_ = q_ + Z_[2].head(n);
    v1_ = v_ + Z_[2].tail(n);
    // y' at the end from the collocation polynomial: (D Z)_3 / h
    a1_ = (tab_.D(2, 0) * Z_[0].tail(n) + tab_.D(2, 1) * Z_[1].tail(n) +
           tab_.D(2, 2) * Z_[2].tail(n)) /
          h;
    f1_ = -a1_;
    if (s_.step_control == StepControl::adaptive) {
      r1_.head(n) = (h * tab_.b0) * v_;
      r1_.tail(n) = (h * tab_.b0) * a_;
      for (int j = 0; j < 3; ++j) r1_ += tab_.e[static_cast<std::size_t>(j)] * Z_[j];
      const double cr = tab_.g / h;
      solve_real(cr, r1_, err_);
      err_ *= cr;
    }
    // kept for accepted(); start_values() writes Z_ anew before it is read again
    for (int i = 0; i < 3; ++i) Ztrial_[i].swap(Z_[i]);
    fresh_ = false;
    if (theta_last_ > kRefreshTheta) have_jacobian_ = false;
  }

  RadauTableau tab_;
  std::unique_ptr<SecondOrderSolver> so_;
  std::array<Vec, 3> Z_, Zprev_, Ztrial_, F_, G_, dZ_;
  Vec w_, r1_, x1_, tq_, tv_, err_;
  Vec r2r_, r2i_, x2r_, x2i_, cqr_, cqi_;
  SplitComplexLU luc_;
  bool have_jacobian_ = false, fresh_ = false, extrapolated_ = false;
  double h_factor_ = 0.0, eta_ = 1.0, theta_last_ = 0.0;
};

}  // namespace

IntegratorEntry radau_entry() {
  IntegratorCapabilities c;
  c.declared = true;
  c.adaptive = true;
  c.fixed_step = true;
  c.reads = {
      "rtol",         "atol",           "step",        "max_step",          "min_step",
      "step_control", "max_iterations", "formulation", "penalty_stiffness", "penalty_damping"};
  return {"radau", [] { return std::make_unique<Radau>(); },
          "Radau IIA, 3 stages, order 5 (Hairer-Wanner), simplified Newton on n x n matrices", c};
}

}  // namespace evas
