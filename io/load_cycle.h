// Reading a bearing's load cycle (`evas bearing --load-cycle FILE`): a CSV
// file, `#` comments, the header `angle_deg,fx,fy`, then one row per angle:
// crank angle [deg], load on the journal along the bearing's x and y [N]. The
// last row closes the cycle (one period after the first, the first's load).
#pragma once

#include <string>

#include "elements/bearing_orbit.h"

namespace evas {

/// Throws InputError naming the file, the line and what is wrong.
LoadCycle read_load_cycle(const std::string& path);

}  // namespace evas
