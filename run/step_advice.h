// A newcomer's trap caught before a run: a fixed step too coarse for the
// bodies' highest modes (generalized-alpha and linear-acceleration default to
// 1e-4 s, ten times what the paper's engine needs).
#pragma once

#include <string>

#include "elements/plausibility.h"
#include "integrators/integrator.h"
#include "model/model.h"

namespace evas {

/// Fewer steps per period of the highest elastic mode than this draw a warning.
constexpr double kMinStepsPerPeriod = 10.0;

/// "" unless `s` names a fixed-step method (generalized-alpha,
/// linear-acceleration; not step_control=adaptive) whose step gives fewer than
/// kMinStepsPerPeriod steps per period of the highest mode of the model's
/// bodies; then a warning naming the step, the mode and what to do.
std::string coarse_step_warning(const Model& model, const IntegratorSettings& s);

/// "" unless `s` takes fixed steps so small that the run from `t_start` to
/// `t_end` needs more than kMaxPlausibleSteps (elements/plausibility.h) steps;
/// then a warning with the estimated count, said before the run starts.
std::string step_count_warning(const IntegratorSettings& s, double t_start, double t_end);

}  // namespace evas
