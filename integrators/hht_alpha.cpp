// HHT-alpha (H. M. Hilber, T. J. R. Hughes, R. L. Taylor, "Improved numerical
// dissipation for time integration algorithms in structural dynamics",
// Earthquake Eng. Struct. Dyn. 5 (1977) 283-292) on qdd + f(t, q, v) = 0: the
// member of the generalized-alpha family (newmark.h) with, in Chung &
// Hulbert's notation and Hilber's alpha in [-1/3, 0],
//     alpha_m = 0,  alpha_f = -alpha,  gamma = 1/2 - alpha,  beta = (1 - alpha)^2 / 4.
// Second-order accurate and unconditionally stable; the spectral radius at
// infinity is (1 + alpha) / (1 - alpha): alpha = 0 is the trapezoidal rule
// (average acceleration, no damping), alpha = -1/3 damps the highest
// frequencies to 1/2. Its own setting `alpha` (default -0.05).
//
// Constraints: the index-3 form of newmark_dae.h (HHT-I3, D. Negrut, R.
// Rampalli, G. Ottarsson, A. Sajdak, J. Comput. Nonlinear Dyn. 2 (2007) 73-85)
// or penalty.
#include "integrators/common.h"
#include "integrators/newmark_dae.h"

namespace evas {
namespace {

class HhtAlpha final : public NewmarkDaeIntegrator {
 public:
  std::string name() const override { return "hht-alpha"; }

 protected:
  Parameters parameters() const override {
    const double alpha = own_setting(s_, "alpha");
    return alpha_method(0.0, -alpha);  // gamma = 1/2 - alpha, beta = (1 - alpha)^2 / 4
  }
  bool index3_formulation(const std::string& f) const override {
    return f == "default" || f == "index-3";
  }
  std::string constraint_forms() const override {
    return "formulation=index-3 (the default; HHT-I3) or penalty";
  }
};

}  // namespace

IntegratorEntry hht_alpha_entry() {
  IntegratorCapabilities c = newmark_capabilities();
  DeclaredSetting alpha;
  alpha.key = "alpha";
  alpha.default_value = -0.05;
  alpha.min = -1.0 / 3.0;
  alpha.max = 0.0;
  alpha.doc =
      "HHT's alpha: damping of the high frequencies (0: none, the trapezoidal rule; -1/3: "
      "spectral radius 1/2 at infinity)";
  c.settings.push_back(alpha);
  return {"hht-alpha", [] { return std::make_unique<HhtAlpha>(); },
          "HHT-alpha (Hilber, Hughes & Taylor 1977) on the second-order form", c};
}

}  // namespace evas
