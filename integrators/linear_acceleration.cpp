// The paper's linear acceleration method (Inagaki et al. 2002, Sec. 4, Fig. 9):
// Newmark with beta = 1/6, gamma = 1/2 (the acceleration varies linearly over
// the step) on
//     qdd + f(t, q, v) = 0,   f = f0(t) + KB q + CB v + (element loads).
// Per step (the paper's Steps <4>-<6>): guess a = a_n, then repeat
//     q = q_n + h v_n + h^2 (a_n/3 + a/6),   v = v_n + h (a_n + a)/2
//     r = a + f(t_{n+1}, q, v)                          (out-of-balance of Eq. 1)
//     eps = ||r||_2 / max(||a||_2, ||a_n||_2, atol)     (balance error)
// until eps <= balance_tol (default 1e-3, the paper's 0.1 %).
//
// Balance error: the 2-norm of the out-of-balance of Eq. 1 (inertia plus all
// forces, r = a + f) relative to the 2-norm of the inertia term over the step
// (the larger of a and a_n, so a step ending where the acceleration crosses zero
// is not measured against round-off; floored at atol so a state at rest does not
// divide by zero). eps = 0.001 means the equation of motion balances to 0.1 % of
// the inertia forces.
//
// The update of a is the iteration named by settings.iteration (newmark.h):
// the paper's fixed point (default: a -= Meff^-1 r with Meff = I + (h/2) CB +
// (h^2/6) KB, the bodies' own modal terms only), Anderson-accelerated, with
// the elements' K, C in Meff (effective-mass), or full Newton. All of them stop
// on the same balance test, so they solve the same discrete equations.
//
// Constrained problems and mass matrices: formulation=index-3 (the Newmark
// index-3 form of newmark_dae.h with alpha_m = alpha_f = 0, increment test
// instead of the balance test; it diverges at any step, as beta = 1/6 is only
// conditionally stable, h omega <= 3.46, and the constrained directions are
// infinitely stiff: kept for the study of exactly that) or penalty, whose
// stiffness k bounds the step by h <= 3.46 sqrt(m/k).
//
// Counters: nonlinear_iterations = updates of a; residual_evals = force
// evaluations; jacobian_evals = body_operator (fixed point) or force_jacobian
// evaluations; linear_setups / linear_solves = factorizations of / solves with
// Meff (none for the fixed point when there is no body part, Meff = I).
#include "integrators/common.h"
#include "integrators/newmark_dae.h"

namespace evas {
namespace {

class LinearAcceleration final : public NewmarkDaeIntegrator {
 public:
  std::string name() const override { return "linear-acceleration"; }

 protected:
  Parameters parameters() const override {
    if (!(s_.balance_tol > 0.0))
      throw InputError("linear-acceleration: balance_tol must be > 0 (got " +
                       format_number(s_.balance_tol) + ")");
    Parameters p;  // alpha_m = alpha_f = 0, beta = 1/6, gamma = 1/2
    p.balance = true;
    p.iteration = Iteration::fixed_point;
    return p;
  }
  bool index3_formulation(const std::string& f) const override { return f == "index-3"; }
  std::string constraint_forms() const override {
    return "formulation=index-3 (which diverges: beta = 1/6 is only conditionally stable "
           "and a constraint is infinitely stiff; docs/theory.md section 10.5) or penalty";
  }
};

}  // namespace

IntegratorEntry linear_acceleration_entry() {
  IntegratorCapabilities c = newmark_capabilities();
  c.reads.push_back("balance_tol");
  c.stability_limit = [](const IntegratorSettings&) {
    return NewmarkIntegrator::stability_limit(1.0 / 6.0, 0.5);
  };
  return {"linear-acceleration", [] { return std::make_unique<LinearAcceleration>(); },
          "the paper's linear-acceleration iteration (Newmark beta = 1/6)", c};
}

}  // namespace evas
