// Generalized-alpha method (J. Chung, G. M. Hulbert, "A time integration
// algorithm for structural dynamics with improved numerical dissipation: the
// generalized-alpha method", J. Appl. Mech. 60 (1993) 371-375) on
//     qdd + f(t, q, v) = 0,
// spectral radius at infinity rho = settings.rho_inf in [0, 1]:
//     alpha_m = (2 rho - 1)/(rho + 1),  alpha_f = rho/(rho + 1),
//     gamma = 1/2 - alpha_m + alpha_f,  beta = (1 - alpha_m + alpha_f)^2 / 4.
// gamma = 1/2 - alpha_m + alpha_f makes the method second-order accurate.
// The step, its iterations (default: effective-mass, i.e. modified Newton with
// the analytic K, C), the convergence test on the increment and the local error
// estimate are those of the Newmark family (newmark.h); step control in
// fixed_step.h.
//
// Constrained problems and mass matrices: the index-3 form of Arnold & Bruls
// (2007) in newmark_dae.h, formulation index-3 (the default here) or penalty.
#include "integrators/common.h"
#include "integrators/newmark_dae.h"

namespace evas {
namespace {

class GeneralizedAlpha final : public NewmarkDaeIntegrator {
 public:
  std::string name() const override { return "generalized-alpha"; }

 protected:
  Parameters parameters() const override {
    const double rho = s_.rho_inf;
    if (!(rho >= 0.0 && rho <= 1.0))
      throw InputError("generalized-alpha: rho_inf must be in [0, 1] (got " + format_number(rho) +
                       ")");
    return alpha_method((2.0 * rho - 1.0) / (rho + 1.0), rho / (rho + 1.0));
  }
  bool index3_formulation(const std::string& f) const override {
    return f == "default" || f == "index-3";
  }
  std::string constraint_forms() const override {
    return "formulation=index-3 (the default; Arnold & Bruls 2007) or penalty";
  }
};

}  // namespace

IntegratorEntry generalized_alpha_entry() {
  IntegratorCapabilities c = newmark_capabilities();
  c.reads.push_back("rho_inf");
  return {"generalized-alpha", [] { return std::make_unique<GeneralizedAlpha>(); },
          "generalised-alpha (Chung-Hulbert 1993) on the second-order form", c};
}

}  // namespace evas
