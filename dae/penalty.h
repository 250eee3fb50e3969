// The penalty formulation: a constrained Problem as an ODE any integrator can
// run. The constraints become forces
//     f_pen = f + G^T (k g + c g'),   g' = G v + g_t,
// i.e. M q'' + f + G^T (k g + c g') = 0 (a stiff spring k and damper c per
// constraint equation; Bayo, Garcia de Jalon & Serna, Comput. Methods Appl.
// Mech. Eng. 71 (1988) 183-195; Hairer & Wanner, Solving ODEs II, 2nd ed.
// 1996, ch. VII, the singular perturbation g = -lambda/k). Jacobians:
//     K_pen = K + k G^T G + c G^T (G v + g_t)_q + sum_k (k g + c g')_k H_k,
//     C_pen = C + c G^T G,      H_k = the Hessian of g_k,
// the two second-derivative terms by forward differences over q (n
// evaluations of G and g), skipped when Problem::constraints_linear().
// K_pen and C_pen live on the pattern K u G^T G. The mass matrix, stops,
// initial state and the body operator are the wrapped problem's.
#pragma once

#include <array>
#include <utility>
#include <vector>

#include "model/problem.h"

namespace evas::dae {

class PenaltyProblem final : public Problem {
 public:
  /// stiffness k > 0, damping c >= 0 (per unit of g and g').
  PenaltyProblem(Problem& base, double stiffness, double damping);

  Problem& base() { return base_; }

  int size() const override { return base_.size(); }
  void initial_state(Vec& q, Vec& v) const override { base_.initial_state(q, v); }
  void force(double t, const double* q, const double* v, double* f) override;
  void force_jacobian(double t, const double* q, const double* v, SpMat& K, SpMat& C) override;
  const SpMat& jacobian_pattern() const override { return pattern_; }
  double next_stop(double t) const override { return base_.next_stop(t); }
  bool at_stop(double t, double* q, double* v) override { return base_.at_stop(t, q, v); }
  void body_operator(double t, SpMat& KB, SpMat& CB) override;
  bool has_mass() const override { return base_.has_mass(); }
  const std::vector<int>& quasi_static() const override { return base_.quasi_static(); }
  void mass(double t, const double* q, SpMat& M) override { base_.mass(t, q, M); }
  const SpMat& mass_pattern() const override { return base_.mass_pattern(); }
  std::string describe_state(double t, const double* q, const double* v) const override {
    return base_.describe_state(t, q, v);
  }
  std::string describe_coordinate(int i) const override { return base_.describe_coordinate(i); }
  // internal states: the base problem's (the penalty forces do not depend on z)
  int internal_count() const override { return base_.internal_count(); }
  bool internal_algebraic(int i) const override { return base_.internal_algebraic(i); }
  void internal_initial(double t, const Vec& q, const Vec& v, Vec& z) override {
    base_.internal_initial(t, q, v, z);
  }
  void set_internal(const double* z) override { base_.set_internal(z); }
  const double* internal() const override { return base_.internal(); }
  void internal_rate(double t, const double* q, const double* v, double* h) override {
    base_.internal_rate(t, q, v, h);
  }
  void internal_jacobian(double t, const double* q, const double* v, SpMat& Fz, SpMat& Hq,
                         SpMat& Hv, SpMat& Hz) override {
    base_.internal_jacobian(t, q, v, Fz, Hq, Hv, Hz);
  }
  void internal_patterns(SpMat& Fz, SpMat& Hq, SpMat& Hv, SpMat& Hz) const override {
    base_.internal_patterns(Fz, Hq, Hv, Hz);
  }
  std::string internal_name(int i) const override { return base_.internal_name(i); }

 private:
  Problem& base_;
  double k_, c_;
  int n_, m_;
  SpMat pattern_, Kb_, Cb_, G_, G0_;
  std::vector<int> pos_base_;                         // base pattern value -> pattern_ value
  std::vector<std::array<int, 3>> gtg_;               // (pattern_ value, G value a, G value b)
  std::vector<std::vector<std::pair<int, int>>> fd_;  // per column: (row, pattern_ value)
  Vec g_, gv_, w_, h0_, h1_, qh_;
  void second_derivative_terms(double t, const double* q, const double* v, Vec& out);
};

}  // namespace evas::dae
