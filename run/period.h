// The period of a scene's forcing: the cycle after which the model's equations
// repeat, so that a steady run repeats too (evas periodic, the settledness of
// every run).
//
// A scene repeats when every body's LOF is the same at t and t + T (pose,
// velocity, angular velocity; a spin frame at constant speed turns by a whole
// number of turns in T) and its elements' forcing repeats: four-stroke
// pistons (`piston-conrod`) every 720 degrees of the crank, everything else
// that follows a spinning frame (unbalance, belts, bearings) every 360 degrees.
// The crank is the output's crank-angle body, or the one body with a spin LOF.
#pragma once

#include <optional>
#include <string>

#include "io/scene.h"

namespace evas::run {

struct ScenePeriod {
  double seconds = 0.0;  ///< T [s]
  double degrees = 0.0;  ///< T in degrees of the crank (0 when no body spins)
  int crank_body = -1;   ///< the body whose spin sets the angle (-1: none)
  std::string basis;     ///< why, e.g. "720 deg of 'crank' (four-stroke pistons) at 314.159 rad/s"
};

/// The scene's own period, or nothing with the reason in `why` (no spinning
/// body, a speed that changes, a frame that does not repeat).
std::optional<ScenePeriod> natural_period(const Scene& scene, std::string& why);

/// The period given on the command line ("720deg", "360 deg", "0.04s", "0.04 s"),
/// checked against the scene: it must be a whole multiple of the scene's own
/// period when it has one, and every LOF must repeat after it. Empty `given`:
/// the scene's own period. Throws InputError naming the scene and the reason.
ScenePeriod scene_period(const Scene& scene, const std::string& given);

}  // namespace evas::run
