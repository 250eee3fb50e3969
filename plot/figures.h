// `evas plot KIND RESULTS.h5 ...`: the figures an engine NVH engineer reads
// first, drawn by gnuplot from a run's results file (docs/user-guide.md,
// "evas plot"). Beside the figure (PNG or SVG, by its extension) the command
// leaves its gnuplot script and data (FIGURE.gp, FIGURE.dat), so a figure can
// be restyled without evas.
//
//   channels  channels against crank angle (crank-angle grid) or time
//   polar     polar load diagram of a journal bearing: the load on the shell
//             in the bearing's axes, and on the journal in axes turning with it
//   orbit     the journal centre's orbit inside the clearance circle
//   film      minimum film thickness and peak film pressure against crank angle
//   order     order spectrum of a channel over whole cycles
//   spectrum  amplitude spectrum over frequency (post/time_spectrum.h)
//   erp       equivalent radiated power of a surface output, per bin and in
//             third-octave bands (post/erp_spectrum.h)
// and of a sweep's sweep.h5 (plot/sweep_figures.h): waterfall, campbell,
// order-cuts
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "post/time_spectrum.h"

namespace evas {

struct PlotOptions {
  std::string kind;
  std::vector<std::string> channels;  ///< channels, order, spectrum (exact names or globs)
  std::string element;                ///< polar, orbit, film: a journal bearing
  std::string x = "auto";             ///< channels, film: auto, time or crank-angle
  /// polar, orbit, film, order: the last `cycles` whole cycles of a
  /// crank-angle grid (0: the whole record); channels: 0 by default.
  int cycles = 1;
  double cycle = 720.0;     ///< cycle length [deg]
  double max_order = 12.0;  ///< order
  TimeSpectrumOptions spectrum;
  double max_frequency = 0.0;  ///< spectrum: highest frequency shown [Hz] (0: Nyquist)
  std::vector<double> orders;  ///< order-cuts: the orders drawn (empty: 1, 2, 4)
  std::string title;           ///< "" for the kind's own title
};

/// The kinds `evas plot` draws, and the one-line description of each.
const std::vector<std::pair<std::string, std::string>>& plot_kinds();

/// Draws `o.kind` of the results file into `out` (.png or .svg), with the
/// script and data beside it; returns the files written. Throws InputError
/// for an unknown kind, an output that is neither .png nor .svg, a channel or
/// element the file does not have (naming those it has), a kind the file
/// cannot give (a waterfall from a single run), no gnuplot, or gnuplot failing.
std::vector<std::string> plot_results(const std::string& results, const PlotOptions& o,
                                      const std::filesystem::path& out);

}  // namespace evas
