#include "apps/step_advice.h"

#include <cmath>
#include <sstream>

#include "integrators/settings.h"

namespace evas {

std::string coarse_step_warning(const Model& model, const IntegratorSettings& s) {
  if (!takes_fixed_steps(s) || !(s.step > 0.0)) return "";
  double lam = 0.0;
  std::string body;
  int mode = -1;
  for (const auto& b : model.bodies())
    for (int k = 0; k < b.data->eigenvalues.size(); ++k)
      if (b.data->eigenvalues[k] > lam) {
        lam = b.data->eigenvalues[k];
        body = b.name;
        mode = k;
      }
  if (!(lam > 0.0)) return "";
  const double f = std::sqrt(lam) / (2.0 * M_PI);
  const double per_period = 1.0 / (f * s.step);
  if (per_period >= kMinStepsPerPeriod) return "";
  std::ostringstream os;
  os.precision(3);
  os << s.name << ": step " << s.step << " s is " << per_period
     << " steps per period of the highest mode (" << std::lround(f) << " Hz, body '" << body
     << "' mode " << mode << "); below " << kMinStepsPerPeriod
     << " the fixed step cannot follow it, and elements may meet states outside their range. "
     << (s.name == "radau"
             ? "Set `step` or step_control=adaptive (on the paper's engine rtol 1e-3 gives an "
               "error of 1e-3 in the main-bearing loads)"
             : "Set `step` (on the paper's engine about 50 per period, 8e-6 s, for an error of "
               "1e-3 in the main-bearing loads) or step_control=adaptive");
  return os.str();
}

}  // namespace evas
