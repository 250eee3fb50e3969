// What a study measures: the selected channels, the window of output times and
// the error of a run against the reference.
//
// Error (`--norm`, ErrorMeasure): for every selected channel c the reference's
// amplitude over the window,
//     A_c = max over the window of |y_ref,c - mean_window(y_ref,c)|,
// and that of its group, A_g = max of A_c over the selected channels with c's
// unit (a group: channels that can be compared). Per channel, d = y_c - y_ref,c:
//   group (default)  e_c = max_t |d| / A_g: a channel that barely moves is
//                    measured on the scale of its group's largest, so it
//                    cannot set the error by its own small amplitude;
//   channel (max)    e_c = max_t |d| / A_c (each channel's own amplitude);
//   rms              e_c = RMS_t d / A_c;
//   floor=F          e_c = max_t |d| / max(A_c, F A_g): per channel, but a
//                    channel smaller than F of its group counts on F A_g (an
//                    atol of the measure; F = 0 is channel, F = 1 group);
//   l2               e_c = sqrt(sum_t d^2 / sum_t sum_{k in g} (y_ref,k - mean)^2):
//                    the relative L2 norm over the window of the group,
//                    e_g = sqrt(sum_{c in g} e_c^2);
//   final            e_c = |d| / A_g at the window's last time.
// The error is the largest e_c (l2: the largest e_g); the channel that sets it
// is named. Channels with no scale (A_c = 0, or A_g = 0) are left out.
//
// Window: `all` (every output time), `last-cycles=N` (crank-angle grid: the
// outputs whose crank angle is within the last N * 720 degrees of the output),
// or `T0:T1` (outputs with T0 <= t <= T1 seconds).
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "model/element.h"
#include "model/types.h"

namespace evas::study {

/// Indices of the channels whose names match any of the comma-separated glob
/// patterns; an empty pattern list selects every channel except crank_angle and
/// the constraint residuals (names ending in .g and .g_dot).
/// Throws InputError naming `option` when nothing matches: every available
/// name when there are at most 20, else the nearest ones.
std::vector<int> select_channels(const std::vector<Channel>& channels, const std::string& patterns,
                                 const std::string& option = "--channels");

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

enum class Norm { Max, Rms, Group, Floor, L2, Final };

/// The error measure of `--norm`: its kind and, for floor=F, F.
struct ErrorMeasure {
  Norm norm = Norm::Group;
  double floor = 0.0;
};

/// The default measure's `--norm` text.
constexpr const char* kDefaultNorm = "group";

/// Parses group | channel | max | rms | floor=F | l2 | final. Throws InputError.
ErrorMeasure parse_measure(const std::string& text);
/// The kind alone (floor's F dropped): parse_measure(text).norm.
Norm parse_norm(const std::string& text);
/// "group", "channel", "rms", "floor=F", "l2" or "final".
std::string norm_text(Norm n);
std::string measure_text(const ErrorMeasure& m);

/// The error of every channel and which one sets the error.
struct ChannelErrors {
  std::vector<double> error;  ///< e_c (NaN: the channel has no scale)
  std::vector<double> scale;  ///< the divisor of e_c (A_c, A_g, ...)
  double total = std::numeric_limits<double>::quiet_NaN();
  int worst = -1;  ///< the channel that sets `total` (-1 when NaN)
};

/// Every channel's error of `y` against `ref` (nt x nc on the same output
/// times) over the window rows, `units` one per column (empty: one group).
/// total is NaN when y has fewer rows than the window needs, a difference is
/// not finite, or no channel has a scale.
ChannelErrors channel_errors(const Mat& y, const Mat& ref, const std::vector<int>& rows,
                             const ErrorMeasure& m, const std::vector<std::string>& units);

/// Channel amplitudes A_c of the reference (nt x nc) over the window rows.
std::vector<double> amplitudes(const Mat& ref, const std::vector<int>& rows);

/// channel_errors(...).total with every channel in one group (floor: F = 0).
double relative_error(const Mat& y, const Mat& ref, const std::vector<int>& rows, Norm norm);

/// One sentence stating the error measure (for outputs and --help).
std::string error_definition(const ErrorMeasure& m, const Window& w);

}  // namespace evas::study
