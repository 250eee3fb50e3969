// Implicit first-order residuals F(t, y, y') = 0 of a constrained mechanical
// system  M(q) q'' + f(t, q, v) + G^T lambda = 0,  g(t, q) = 0  (solver/problem.h),
// one per formulation, with the iteration matrix dF/dy + cj dF/dy' that IDA
// factorizes (SUNDIALS IDA user guide, "Mathematical considerations").
//
// Layout y = [q (n); v (n); lambda (m); mu (m, GGL only); z (nz)]:
//   index-3  [q' - v;            M v' + f + G^T lambda;  g]
//   index-2  [q' - v;            M v' + f + G^T lambda;  G v + g_t]
//   ggl      [q' - v + G^T mu;   M v' + f + G^T lambda;  g;  G v + g_t]
//   index-1  [q' - v;            M v' + f + G^T lambda;  G v' + ga + 2 alpha g' + beta^2 g]
// (Hairer & Wanner, Solving ODEs II, 2nd ed. 1996, ch. VII.1; Gear, Leimkuhler
// & Gupta, J. Comput. Appl. Math. 12-13 (1985) 77-90 for ggl; Baumgarte,
// Comput. Methods Appl. Mech. Eng. 1 (1972) 1-16 for alpha, beta.) With m = 0
// every formulation is the mass-matrix ODE [q' - v; M v' + f].
// Element internal states z (Problem::internal_count()) add the rows
// z' - h(t, q, v, z) (differential) or -h(t, q, v, z) (algebraic, index 1 when
// dh/dz of the algebraic ones is regular), with f = f(t, q, v, z); their
// Jacobian blocks Fz, Hq, Hv, Hz are analytic.
//
// Iteration matrix: K, C, M and G are analytic. The second-derivative terms
// d(G^T lambda)/dq, d(G^T mu)/dq, d(G v + g_t)/dq, d(G v' + ga)/dq, d(ga)/dv and
// d(M v')/dq come from forward differences over q (and v for ga): n extra
// evaluations of G, g and M per Jacobian. They are skipped when
// Problem::constraints_linear() (the M term only when !has_mass()). Their
// pattern assumes that row k of G (and row i of M) depends only on the
// coordinates in that row's pattern.
#pragma once

#include <string>
#include <vector>

#include "dae/internal_blocks.h"
#include "model/problem.h"

namespace evas::dae {

enum class Formulation { index3, index2, ggl, index1, penalty };

/// The formulation named by IntegratorSettings::formulation; "default" gives
/// `fallback`. Throws InputError for an unknown name.
Formulation parse_formulation(const std::string& name, Formulation fallback);
std::string formulation_name(Formulation f);

class DaeForm {
 public:
  /// `f` must not be penalty (dae/penalty.h turns that one into an ODE).
  DaeForm(Problem& p, Formulation f, double baumgarte_alpha, double baumgarte_beta);

  Problem& problem() { return p_; }
  Formulation formulation() const { return f_; }
  int n() const { return n_; }
  int m() const { return m_; }
  int internal_count() const { return nz_; }
  /// First component of z in y.
  int z_offset() const { return z0_; }
  int size() const { return size_; }

  void residual(double t, const double* y, const double* yd, double* F);
  void residual_jacobian(double t, const double* y, const double* yd, double cj, SpMat& J);
  const SpMat& residual_pattern() const { return J_; }

  /// 1 for differential components (q, v), 0 for algebraic ones (lambda, mu):
  /// IDASetId before IDACalcIC.
  const Vec& differential_id() const { return diff_id_; }
  /// 1 for the components in IDA's local error test, 0 for those left out
  /// (IDASetSuppressAlg): lambda and mu always; for index-3 also v (Brenan,
  /// Campbell & Petzold 1996, ch. 5; Hairer & Wanner ch. VII).
  const Vec& error_test_id() const { return err_id_; }

  /// Power p of the step h multiplying the error weight of each component
  /// (the weight 1/(rtol |y| + atol) becomes h^p/(rtol |y| + atol), so p = 0 is
  /// unscaled): p = nu - 1 for a variable of index nu, i.e. 1 for lambda and mu
  /// of index-2 and ggl and for v of index-3, 2 for lambda of index-3, 0
  /// otherwise (Brenan, Campbell & Petzold 1996, ch. 5: the Newton and error
  /// tests of BDF on higher-index systems). At h -> 0 those components leave
  /// the tests, as the Newton corrections of round-off in g grow like h^-p.
  const std::vector<int>& weight_power() const { return weight_power_; }

  /// y, y' (size()) from (q, v) at t via consistent_state (dae/consistent.h):
  /// q, v projected onto the constraints, v' and lambda from the saddle-point
  /// system, mu = 0, lambda' = mu' = 0. Internal states: z from the problem's
  /// current z, its algebraic part solved by Newton for h = 0 at (q, v), z' = h
  /// (differential), 0 (algebraic). Returns max |F(t, y, y')|.
  double consistent_start(double t, const Vec& q, const Vec& v, double* y, double* yd);
  /// True when some internal state is algebraic.
  bool has_algebraic_states() const { return !zalg_.empty(); }

 private:
  // The parts of F that need finite differences, at (q, v) with y' and the
  // multipliers of `y`; rows as in F, others zero.
  void nonlinear_terms(double t, const double* q, const double* v, const double* y,
                       const double* yd, Vec& out);
  void gt_times(const double* w, double* out, double sign = 1.0) const;
  /// G at (t, q) into G_ (evaluated once when the constraints are linear).
  void g_jacobian(double t, const double* q);
  /// Newton on the algebraic internal states at (q, v) (current z updated).
  void solve_algebraic_states(double t, const Vec& q, const Vec& v);

  Problem& p_;
  Formulation f_;
  double alpha_, beta_;
  int n_, m_, size_, nz_ = 0, z0_ = 0;
  bool mass_, nonlinear_, fd_;
  bool g_cached_ = false;
  SpMat K_, C_, M_, G_, J_;
  Vec diff_id_, err_id_;
  std::vector<int> weight_power_;
  Vec g_, gv_, ga_, A0_, A1_, qh_, vh_;
  // value positions in J_
  std::vector<int> pK_, pC_, pM_, pQQ_, pQV_, pVV_;
  std::vector<int> pGtLam_, pGtMu_, pGq_, pGv_;
  std::vector<std::vector<std::pair<int, int>>> fdq_, fdv_;  // per column: (row, position)
  // internal states: Jacobian blocks, their positions, the (z, z) diagonal of
  // the differential ones, and the algebraic states' indices
  InternalBlocks zb_;
  std::vector<int> pZdiag_, zalg_;
  Vec zcur_;
};

}  // namespace evas::dae
