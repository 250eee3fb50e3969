// The explicit central difference method on qdd + f(t, q, v) = 0, in the
// Newmark form beta = 0, gamma = 1/2 (T. J. R. Hughes, The Finite Element
// Method, Dover 2000, section 9.1.3):
//     q_{n+1} = q_n + h v_n + h^2/2 a_n,   v_{n+1} = v_n + h/2 (a_n + a_{n+1}),
//     a_{n+1} = -f(t_{n+1}, q_{n+1}, v_{n+1}).
// The displacement is explicit; a damping force (f depending on v) makes the
// velocity implicit, solved by the effective-mass iteration with S = I +
// (h/2) C alone (no stiffness in the matrix: newmark.h). Second order, no
// algorithmic damping, stable for h omega <= 2 (undamped; h/T <= 1/pi).
// Without damping forces it reproduces the classical central difference
// q_{n+1} - 2 q_n + q_{n-1} = -h^2 f(q_n). Constraints only as penalty
// forces; no mass matrix.
#include "integrators/common.h"
#include "integrators/newmark_dae.h"

namespace evas {
namespace {

class CentralDifference final : public NewmarkDaeIntegrator {
 public:
  std::string name() const override { return "central-difference"; }

 protected:
  Parameters parameters() const override {
    Parameters p;
    p.beta = 0.0;
    p.gamma = 0.5;
    p.balance = false;
    p.iteration = Iteration::effective_mass;
    return p;
  }
  bool index3_formulation(const std::string&) const override { return false; }
  std::string constraint_forms() const override { return "penalty forces (formulation=penalty)"; }
};

}  // namespace

IntegratorEntry central_difference_entry() {
  IntegratorCapabilities c = newmark_capabilities();
  c.formulations.clear();
  c.stability_limit = [](const IntegratorSettings&) {
    return NewmarkIntegrator::stability_limit(0.0, 0.5);
  };
  return {"central-difference", [] { return std::make_unique<CentralDifference>(); },
          "the explicit central difference (Newmark beta = 0, gamma = 1/2)", c};
}

}  // namespace evas
