// The Newmark family on constrained systems and mass matrices (public for
// plug-ins: derive from NewmarkDaeIntegrator, give parameters(); examples/
// hht_plugin),
//     M(q) qdd + f(t, q, v) + G^T lambda = 0,   g(t, q) = 0,
// in the index-3 form of M. Arnold, O. Bruls, "Convergence of the
// generalized-alpha scheme for constrained mechanical systems", Multibody
// Syst. Dyn. 18 (2007) 185-202 (docs/theory.md s. 10.5).
//
// The equations of motion hold at t_{n+1} itself; the Newmark formulas run on
// a filtered acceleration a,
//     (1 - alpha_m) a_{n+1} + alpha_m a_n = (1 - alpha_f) qdd_{n+1} + alpha_f qdd_n,
//     q_{n+1} = q_n + h v_n + h^2 ((1/2 - beta) a_n + beta a_{n+1}),
//     v_{n+1} = v_n + h ((1 - gamma) a_n + gamma a_{n+1}),
// and g(t_{n+1}, q_{n+1}) = 0 closes the step (index 3). With alpha_m =
// alpha_f = 0 (linear acceleration) a is qdd. Newton on (q_{n+1}, lambda_{n+1})
// with the iteration matrix
//     [ beta' M + gamma' C + K    G^T ]      beta' = (1 - alpha_m) / ((1 - alpha_f) beta h^2)
//     [ G / (beta h^2)            0   ]      gamma' = gamma / (beta h)
// (constraint rows scaled by 1/(beta h^2): Bottasso, Dopico & Trainelli,
// Multibody Syst. Dyn. 19 (2008) 3-20), without the terms (M qdd)_q and
// (G^T lambda)_q (modified Newton: O(h^2) against beta' M), factorized by KLU
// and kept across steps of one h until an iteration contracts by less than a
// factor 4. Converged when ||delta a||_inf <= rtol ||a||_inf + atol or delta q
// is at round-off. Start: qdd_0 and lambda_0 from the saddle-point system
// (dae/consistent.h), a_0 = qdd_0. Problems without constraints and mass
// matrix take the ODE path of newmark.h unchanged.
#pragma once

#include <Eigen/KLUSupport>
#include <string>

#include "integrators/newmark.h"

namespace evas {

class NewmarkDaeIntegrator : public NewmarkIntegrator {
 public:
  bool multipliers(Vec& lambda) const override;

 protected:
  /// The formulations (settings.formulation) this method solves in the
  /// index-3 form, e.g. {"default", "index-3"}.
  virtual bool index3_formulation(const std::string& f) const = 0;

  bool takes_constraints(const IntegratorSettings& s) const override {
    return index3_formulation(s.formulation);
  }
  void setup() override;
  void start_acceleration() override;
  void accepted() override;
  bool step(double t, double h) override;
  void local_error(double h, bool hist, Vec& eq, Vec& ev) const override;

 private:
  // one step of h from (t_, q_, v_, aa_): Newton on (q, lambda)
  bool iterate_dae(double t, double h);
  // r = [M qdd + f + G^T lambda; g / (beta h^2)] at the trial state
  void residual(double t1, double bh2);
  bool factorize(double t1, double bp, double gp, double bh2);

  bool dae_ = false;
  int m_ = 0;
  Parameters par_;
  SpMat K_, C_, M_, G_, A_;
  Eigen::KLU<SpMat> lu_;
  Vec aa_, aa1_;               // filtered acceleration at t_ and of the trial step
  Vec aa_prev_, aa_save_;      // aa of the step before; aa_ before step() shifted it
  Vec lam_, lam1_, lam_prev_;  // multipliers at t_, of the trial step, at the step before
  Vec r_, g_, Mqdd_;
  bool factored_ = false;
  double h_factored_ = 0.0;
};

}  // namespace evas
