// What a study measures: the selected channels, the window of output times and
// the error of a run against the reference.
//
// Error (`--norm max`, the default): for every selected channel c,
//     A_c = max over the window of |y_ref,c - mean_window(y_ref,c)|   (the channel's amplitude)
//     e_c = max over the window of |y_c - y_ref,c| / A_c
// and the error is max_c e_c: the largest deviation relative to each
// channel's own amplitude. `--norm rms`: e_c = RMS over the window of
// (y_c - y_ref,c) / A_c, error = max_c e_c. Channels with A_c = 0 (constant in
// the window) are left out.
//
// Window: `all` (every output time), `last-cycles=N` (crank-angle grid: the
// outputs whose crank angle is within the last N * 720 degrees of the output),
// or `T0:T1` (outputs with T0 <= t <= T1 seconds).
#pragma once

#include <string>
#include <vector>

#include "model/element.h"
#include "model/types.h"

namespace evas::study {

/// Indices of the channels whose names match any of the comma-separated glob
/// patterns; an empty pattern list selects every channel except crank_angle and
/// the constraint residuals (names ending in .g and .g_dot).
/// Throws InputError listing the available names when nothing matches.
std::vector<int> select_channels(const std::vector<Channel>& channels, const std::string& patterns);

struct Window {
  enum class Kind { All, LastCycles, Time };
  Kind kind = Kind::All;
  double cycles = 1.0;
  double t0 = 0.0, t1 = 0.0;
  std::string text() const;
};

/// Parses "all", "last-cycles=N" or "T0:T1". Throws InputError.
Window parse_window(const std::string& text);

/// Rows of the window. `crank` holds the crank angle of every row [deg]
/// (empty when the output is on the time grid: last-cycles is then an error).
/// Throws InputError when the window is empty or longer than the output.
std::vector<int> window_rows(const Window& w, const std::vector<double>& time,
                             const std::vector<double>& crank);

enum class Norm { Max, Rms };
Norm parse_norm(const std::string& text);
std::string norm_text(Norm n);

/// Channel amplitudes A_c of the reference (nt x nc) over the window rows.
std::vector<double> amplitudes(const Mat& ref, const std::vector<int>& rows);

/// The error of `y` against `ref` (both nt x nc on the same output times) over
/// the window rows (see the header comment). NaN when y has fewer rows than
/// the window needs or no channel has a nonzero amplitude.
double relative_error(const Mat& y, const Mat& ref, const std::vector<int>& rows, Norm norm);

/// One sentence stating the error measure (for outputs and --help).
std::string error_definition(Norm norm, const Window& w);

}  // namespace evas::study
