#include "run/step_advice.h"

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
     << "Set `step` to " << 1.0 / (50.0 * f) << " s or less (50 steps per period of that mode)"
     << (integrator_capabilities(s.name).adaptive ? " or step_control=adaptive (rtol, atol)" : "")
     << ", or leave the mode out of the body's basis.";
  return os.str();
}

std::string step_count_warning(const IntegratorSettings& s, double t_start, double t_end) {
  if (!takes_fixed_steps(s) || !(s.step > 0.0)) return "";
  const double steps = (t_end - t_start) / s.step;
  if (!(steps > kMaxPlausibleSteps)) return "";
  // at a few microseconds per step for the smallest scenes, more for an engine
  const double days_at_10us = steps * 1e-5 / 86400.0;
  std::ostringstream os;
  os.precision(3);
  os << s.name << ": step " << s.step << " s needs about " << steps
     << " steps to reach t = " << t_end << " s (more than " << kMaxPlausibleSteps
     << "; at 10 us per step that is " << days_at_10us << " days): steps are in seconds, is "
     << s.step << " a slip? (10 us is 1e-5 s, 1 us is 1e-6)";
  return os.str();
}

}  // namespace evas
