// `evas bearing --load-cycle FILE`: the journal's orbit under a periodic load
// (elements/bearing_orbit.h), its summary, DIR/orbit.csv and the figure.
#pragma once

#include <string>

#include "elements/bearing_orbit.h"

namespace evas::cli {

struct OrbitCommand {
  std::string load_file;  ///< the load cycle (io/load_cycle.h)
  std::string out_dir;    ///< where orbit.csv, orbit.gp and orbit.png go
  OrbitOptions options;
  bool json = false;  ///< the summary as JSON
  bool plot = true;   ///< run gnuplot on orbit.gp
};

/// Runs the orbit of `b` at om [rad/s], writes the files and prints the
/// summary (whether the orbit settled among it); returns 0, or 2 when the
/// orbit broke off (orbit.csv holds the points reached, the message says where).
int bearing_orbit_command(const JournalBearing& b, double om, const std::string& film,
                          const OrbitCommand& cmd);

}  // namespace evas::cli
