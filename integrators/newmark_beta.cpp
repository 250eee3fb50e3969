// The Newmark method (N. M. Newmark, "A method of computation for structural
// dynamics", J. Eng. Mech. Div. ASCE 85 (1959) 67-94) with its two parameters
// as settings, on qdd + f(t, q, v) = 0:
//     q_{n+1} = q_n + h v_n + h^2 ((1/2 - beta) a_n + beta a_{n+1}),
//     v_{n+1} = v_n + h ((1 - gamma) a_n + gamma a_{n+1}),
// the equation of motion at t_{n+1} (newmark.h, alpha_m = alpha_f = 0).
// beta = 1/4, gamma = 1/2 (the defaults) is the average acceleration
// (trapezoidal) rule, unconditionally stable and without damping; beta = 1/6
// is linear acceleration; beta = 0 the central difference. Second order only
// at gamma = 1/2; gamma > 1/2 damps (first order). Stability (T. J. R.
// Hughes, The Finite Element Method, Dover 2000, section 9.1.2): unconditional
// for 2 beta >= gamma >= 1/2, otherwise for h omega <= (gamma/2 - beta)^(-1/2)
// (undamped); gamma < 1/2 is refused (it amplifies every mode).
//
// Constraints: the index-3 form of newmark_dae.h on request (formulation=
// index-3; it drifts or diverges without damping, gamma = 1/2) or penalty.
#include "integrators/common.h"
#include "integrators/newmark_dae.h"

namespace evas {
namespace {

class NewmarkBeta final : public NewmarkDaeIntegrator {
 public:
  std::string name() const override { return "newmark"; }

 protected:
  Parameters parameters() const override {
    Parameters p;
    p.beta = own_setting(s_, "beta");
    p.gamma = own_setting(s_, "gamma");
    p.balance = false;
    p.iteration = Iteration::effective_mass;
    return p;
  }
  bool index3_formulation(const std::string& f) const override { return f == "index-3"; }
  std::string constraint_forms() const override {
    return "formulation=index-3 (on request: without damping it drifts) or penalty";
  }
};

}  // namespace

IntegratorEntry newmark_entry() {
  IntegratorCapabilities c = newmark_capabilities();
  DeclaredSetting beta, gamma;
  beta.key = "beta";
  beta.default_value = 0.25;
  beta.min = 0.0;
  beta.max = 0.5;
  beta.doc =
      "Newmark's beta (1/4: average acceleration; 1/6: linear acceleration; 0: central "
      "difference)";
  gamma.key = "gamma";
  gamma.default_value = 0.5;
  gamma.min = 0.5;
  gamma.max = 1.0;
  gamma.doc = "Newmark's gamma (1/2: second order, no damping; above: first order, damped)";
  c.settings.push_back(beta);
  c.settings.push_back(gamma);
  c.stability_limit = [](const IntegratorSettings& s) {
    return NewmarkIntegrator::stability_limit(own_setting(s, "beta"), own_setting(s, "gamma"));
  };
  return {"newmark", [] { return std::make_unique<NewmarkBeta>(); },
          "the Newmark method (1959) with beta and gamma as settings", c};
}

}  // namespace evas
