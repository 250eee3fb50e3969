// An integrator plug-in with a setting of its own: the HHT-alpha method
// (H. M. Hilber, T. J. R. Hughes, R. L. Taylor, "Improved numerical
// dissipation for time integration algorithms in structural dynamics",
// Earthquake Eng. Struct. Dyn. 5 (1977) 283-292) for
//     M(q) qdd + f(t, q, v) + G^T lambda = 0,   g(t, q) = 0.
// In the notation of Chung & Hulbert (J. Appl. Mech. 60 (1993) 371-375) it is
// the generalized-alpha family with
//     alpha_m = 0,  alpha_f = -alpha,  gamma = 1/2 - alpha,  beta = (1 - alpha)^2 / 4,
// alpha in [-1/3, 0]: second-order accurate, unconditionally stable, spectral
// radius at infinity (1 + alpha) / (1 - alpha) (alpha = 0: the trapezoidal
// rule; alpha = -1/3: 1/2, the same method as generalized-alpha with
// rho_inf = 1/2).
//
// Everything but the parameters is evas's Newmark family (integrators/
// newmark_dae.h: the step, its iteration, constraints in index-3 form) and
// its fixed-step driver (integrators/fixed_step.h: step control fixed,
// substep or adaptive, dense output between steps, landing on outputs and
// stops without capping the step); `alpha` is declared as the plug-in's own
// setting, set like any other (`--set alpha=-0.1`, the scene's `integrator:`
// block, `evas study --case "hht-plugin alpha=-0.3,-0.1 step=..."`).
//
//     cmake -S examples/hht_plugin -B build-hht && cmake --build build-hht
//     evas run scenes/demo.yaml --plugin build-hht/libevas_hht.so
//         --integrator hht-plugin --set alpha=-0.1 --step 1e-4     (one line)
#include <memory>
#include <string>

#include "integrators/integrator.h"
#include "integrators/newmark_dae.h"
#include "integrators/plugin.h"

namespace {

class HhtAlpha final : public evas::NewmarkDaeIntegrator {
 public:
  std::string name() const override { return "hht-plugin"; }

 protected:
  Parameters parameters() const override {
    // own_setting: the value set, else the declared default (range checked when set)
    const double alpha = evas::own_setting(s_, "alpha");
    Parameters p;
    p.alpha_m = 0.0;
    p.alpha_f = -alpha;
    p.gamma = 0.5 - alpha;
    p.beta = 0.25 * (1.0 - alpha) * (1.0 - alpha);
    p.balance = false;                              // converged on the increment
    p.iteration = evas::Iteration::effective_mass;  // modified Newton with K, C
    return p;
  }
  bool index3_formulation(const std::string& f) const override {
    return f == "default" || f == "index-3";
  }
  std::string constraint_forms() const override {
    return "formulation=index-3 (the default) or penalty";
  }
};

}  // namespace

EVAS_PLUGIN_EXPORT int evas_plugin_init(int abi_version) {
  if (abi_version != EVAS_PLUGIN_ABI_VERSION) return 1;
  evas::IntegratorCapabilities caps = evas::newmark_capabilities();
  evas::DeclaredSetting alpha;
  alpha.key = "alpha";
  alpha.default_value = -0.05;
  alpha.min = -1.0 / 3.0;
  alpha.max = 0.0;
  alpha.doc =
      "HHT's alpha: numerical damping of the high frequencies (0: none, trapezoidal; "
      "-1/3: the most, spectral radius 1/2 at infinity)";
  caps.settings.push_back(alpha);
  evas::register_integrator(
      "hht-plugin", [] { return std::make_unique<HhtAlpha>(); },
      "HHT-alpha (Hilber, Hughes & Taylor 1977), example plug-in with its own setting alpha", caps);
  return 0;
}
