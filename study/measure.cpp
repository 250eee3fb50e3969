// Channel selection, window and error measure (measure.h).
#include "study/measure.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "model/nearest_name.h"
#include "study/case_grid.h"

namespace evas::study {

std::vector<int> select_channels(const std::vector<Channel>& channels, const std::string& patterns,
                                 const std::string& option) {
  std::vector<std::string> pats;
  if (!patterns.empty())
    for (const auto& p : split_list(patterns, ','))
      if (!p.empty()) pats.push_back(p);
  std::vector<int> out;
  for (std::size_t i = 0; i < channels.size(); ++i) {
    const std::string& name = channels[i].name;
    bool take = false;
    if (pats.empty()) {
      // constraint residuals (joints: NAME.ROW.g, .g_dot) are not results: they
      // are measured by the statistics max_constraint, max_constraint_rate
      auto ends = [&](const std::string& tail) {
        return name.size() > tail.size() &&
               name.compare(name.size() - tail.size(), tail.size(), tail) == 0;
      };
      take = name != "crank_angle" && !ends(".g") && !ends(".g_dot");
    } else {
      for (const auto& p : pats) take = take || glob_match(p, name);
    }
    if (take) out.push_back(static_cast<int>(i));
  }
  if (out.empty()) {
    std::vector<std::string> names;
    for (const auto& c : channels) names.push_back(c.name);
    std::string list;
    if (names.size() <= 20)
      for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    throw InputError(option + " '" + patterns + "' matches no output channel (" +
                     (names.empty() ? std::string("none; the scene's output lists no channels")
                      : names.size() <= 20
                          ? "available: " + list
                          : nearest_text(pats.empty() ? patterns : pats.front(), names) +
                                "; evas info SCENE lists them") +
                     ")");
  }
  return out;
}

std::string Window::text() const {
  switch (kind) {
    case Kind::All:
      return "all";
    case Kind::LastCycles:
      return "last-cycles=" + number_text(cycles);
    case Kind::Time:
      return number_text(t0) + ":" + number_text(t1);
  }
  return "";
}

namespace {

bool to_double(const std::string& s, double& x) {
  if (s.empty()) return false;
  char* end = nullptr;
  x = std::strtod(s.c_str(), &end);
  return end != s.c_str() && *end == '\0' && std::isfinite(x);
}

}  // namespace

Window parse_window(const std::string& text) {
  Window w;
  const std::string bad = "--window '" + text + "': expected all, last-cycles=N or T0:T1 [s]";
  if (text == "all") return w;
  if (text.rfind("last-cycles=", 0) == 0) {
    w.kind = Window::Kind::LastCycles;
    if (!to_double(text.substr(12), w.cycles) || !(w.cycles > 0))
      throw InputError("--window '" + text + "': N must be a number > 0");
    return w;
  }
  const auto colon = text.find(':');
  if (colon == std::string::npos) throw InputError(bad);
  w.kind = Window::Kind::Time;
  if (!to_double(text.substr(0, colon), w.t0) || !to_double(text.substr(colon + 1), w.t1))
    throw InputError(bad);
  if (!(w.t1 > w.t0)) throw InputError("--window '" + text + "': T1 must be after T0");
  return w;
}

std::vector<int> window_rows(const Window& w, const std::vector<double>& time,
                             const std::vector<double>& crank) {
  std::vector<int> rows;
  const int nt = static_cast<int>(time.size());
  switch (w.kind) {
    case Window::Kind::All:
      for (int i = 0; i < nt; ++i) rows.push_back(i);
      break;
    case Window::Kind::LastCycles: {
      if (crank.empty())
        throw InputError("--window " + w.text() +
                         ": needs a crank-angle output grid (output: {grid: crank-angle}); this "
                         "scene's output is on the time grid (use all or T0:T1)");
      if (nt == 0) break;
      const double last = crank.back(), span = 720.0 * w.cycles;
      const double covered = std::abs(last - crank.front());
      if (covered < span * (1.0 - 1e-9))
        throw InputError("--window " + w.text() + ": the output covers " + number_text(covered) +
                         " degrees, less than " + number_text(span) +
                         " (lengthen the run with --t-end or choose fewer cycles)");
      const double dir = last >= crank.front() ? 1.0 : -1.0;
      // the last N * 720 degrees: angles in [last - span, last]; the first angle of
      // the window is excluded when it lies exactly one span back (it repeats the last)
      for (int i = 0; i < nt; ++i)
        if (dir * (last - crank[static_cast<std::size_t>(i)]) < span * (1.0 - 1e-9))
          rows.push_back(i);
      break;
    }
    case Window::Kind::Time: {
      const double eps = 1e-9 * std::max(std::abs(w.t0), std::abs(w.t1));
      for (int i = 0; i < nt; ++i)
        if (time[static_cast<std::size_t>(i)] >= w.t0 - eps &&
            time[static_cast<std::size_t>(i)] <= w.t1 + eps)
          rows.push_back(i);
      break;
    }
  }
  if (rows.empty()) throw InputError("--window " + w.text() + ": no output time in the window");
  return rows;
}

ErrorMeasure parse_measure(const std::string& text) {
  ErrorMeasure m;
  if (text == "group") return m;
  if (text == "channel" || text == "max") {
    m.norm = Norm::Max;
    return m;
  }
  if (text == "rms") {
    m.norm = Norm::Rms;
    return m;
  }
  if (text == "l2") {
    m.norm = Norm::L2;
    return m;
  }
  if (text == "final") {
    m.norm = Norm::Final;
    return m;
  }
  if (text.rfind("floor=", 0) == 0) {
    m.norm = Norm::Floor;
    if (!to_double(text.substr(6), m.floor) || !(m.floor >= 0.0) || m.floor > 1.0)
      throw InputError("--norm '" + text + "': F must be a number in [0, 1] (a fraction of " +
                       "the largest amplitude among the channels of the same unit)");
    return m;
  }
  throw InputError("--norm '" + text + "': expected group, channel, rms, floor=F, l2 or final");
}

Norm parse_norm(const std::string& text) { return parse_measure(text).norm; }

std::string norm_text(Norm n) {
  switch (n) {
    case Norm::Max:
      return "channel";
    case Norm::Rms:
      return "rms";
    case Norm::Group:
      return "group";
    case Norm::Floor:
      return "floor";
    case Norm::L2:
      return "l2";
    case Norm::Final:
      return "final";
  }
  return "";
}

std::string measure_text(const ErrorMeasure& m) {
  return m.norm == Norm::Floor ? "floor=" + number_text(m.floor) : norm_text(m.norm);
}

std::vector<double> amplitudes(const Mat& ref, const std::vector<int>& rows) {
  std::vector<double> amp(static_cast<std::size_t>(ref.cols()), 0.0);
  if (rows.empty()) return amp;
  for (int c = 0; c < ref.cols(); ++c) {
    double mean = 0.0;
    for (int r : rows) mean += ref(r, c);
    mean /= static_cast<double>(rows.size());
    double a = 0.0;
    for (int r : rows) a = std::max(a, std::abs(ref(r, c) - mean));
    amp[static_cast<std::size_t>(c)] = a;
  }
  return amp;
}

namespace {

// Sum over the window of (y_ref - mean)^2 per channel (the l2 measure's scale).
std::vector<double> swing_squares(const Mat& ref, const std::vector<int>& rows) {
  std::vector<double> s(static_cast<std::size_t>(ref.cols()), 0.0);
  for (int c = 0; c < ref.cols(); ++c) {
    double mean = 0.0;
    for (int r : rows) mean += ref(r, c);
    mean /= static_cast<double>(rows.size());
    for (int r : rows) s[static_cast<std::size_t>(c)] += (ref(r, c) - mean) * (ref(r, c) - mean);
  }
  return s;
}

// For every channel, the largest of `v` over the channels of its unit (its sum with `sum`).
std::vector<double> over_group(const std::vector<double>& v, const std::vector<std::string>& units,
                               bool sum) {
  std::vector<double> g(v.size(), 0.0);
  for (std::size_t c = 0; c < v.size(); ++c)
    for (std::size_t k = 0; k < v.size(); ++k)
      if (units.empty() || units[k] == units[c]) g[c] = sum ? g[c] + v[k] : std::max(g[c], v[k]);
  return g;
}

}  // namespace

ChannelErrors channel_errors(const Mat& y, const Mat& ref, const std::vector<int>& rows,
                             const ErrorMeasure& m, const std::vector<std::string>& units) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::size_t nc = static_cast<std::size_t>(ref.cols());
  ChannelErrors out;
  out.error.assign(nc, nan);
  out.scale.assign(nc, nan);
  if (rows.empty() || y.cols() != ref.cols() || (!units.empty() && units.size() != nc)) return out;
  for (int r : rows)
    if (r >= y.rows() || r >= ref.rows()) return out;
  const std::vector<double> amp = amplitudes(ref, rows);
  const std::vector<double> group = over_group(amp, units, false);
  std::vector<double> group_l2;
  if (m.norm == Norm::L2) group_l2 = over_group(swing_squares(ref, rows), units, true);
  for (std::size_t c = 0; c < nc; ++c) {
    double scale = 0.0;
    switch (m.norm) {
      case Norm::Max:
      case Norm::Rms:
        scale = amp[c];
        break;
      case Norm::Group:
      case Norm::Final:
        scale = group[c];
        break;
      case Norm::Floor:
        scale = std::max(amp[c], m.floor * group[c]);
        break;
      case Norm::L2:
        scale = std::sqrt(group_l2[c]);
        break;
    }
    if (!(scale > 0.0)) continue;
    const int col = static_cast<int>(c);
    double e = 0.0;
    if (m.norm == Norm::Final) {
      e = std::abs(y(rows.back(), col) - ref(rows.back(), col));
    } else {
      for (int r : rows) {
        const double d = std::abs(y(r, col) - ref(r, col));
        e = (m.norm == Norm::Rms || m.norm == Norm::L2) ? e + d * d : std::max(e, d);
      }
      if (m.norm == Norm::Rms) e = std::sqrt(e / static_cast<double>(rows.size()));
      if (m.norm == Norm::L2) e = std::sqrt(e);
    }
    e /= scale;
    if (!std::isfinite(e)) return ChannelErrors{std::vector<double>(nc, nan), out.scale, nan, -1};
    out.error[c] = e;
    out.scale[c] = scale;
  }
  // the total: the largest e_c, or for l2 the largest group norm sqrt(sum e_c^2)
  double best = -1.0;
  for (std::size_t c = 0; c < nc; ++c) {
    if (std::isnan(out.error[c])) continue;
    double v = out.error[c];
    if (m.norm == Norm::L2) {
      v = 0.0;
      for (std::size_t k = 0; k < nc; ++k)
        if ((units.empty() || units[k] == units[c]) && !std::isnan(out.error[k]))
          v += out.error[k] * out.error[k];
      v = std::sqrt(v);
    }
    // the channel that sets it: the largest e_c (within the group for l2)
    if (v > best || (v == best && out.error[c] > out.error[static_cast<std::size_t>(out.worst)])) {
      best = v;
      out.worst = static_cast<int>(c);
    }
  }
  if (best >= 0.0) out.total = best;
  return out;
}

double relative_error(const Mat& y, const Mat& ref, const std::vector<int>& rows, Norm norm) {
  return channel_errors(y, ref, rows, ErrorMeasure{norm, 0.0}, {}).total;
}

std::string error_definition(const ErrorMeasure& m, const Window& w) {
  std::string per;
  switch (m.norm) {
    case Norm::Max:
      per = "max over the channels c of max_t |y - y_ref| / A_c";
      break;
    case Norm::Rms:
      per = "max over the channels c of RMS_t (y - y_ref) / A_c";
      break;
    case Norm::Group:
      per = "max over the channels c of max_t |y - y_ref| / A_g";
      break;
    case Norm::Floor:
      per = "max over the channels c of max_t |y - y_ref| / max(A_c, " + number_text(m.floor) +
            " A_g)";
      break;
    case Norm::L2:
      per =
          "max over the unit groups g of sqrt(sum_t sum_c (y - y_ref)^2 / sum_t sum_c (y_ref - "
          "mean(y_ref))^2), c in g";
      break;
    case Norm::Final:
      per = "max over the channels c of |y - y_ref| / A_g at the window's last time";
      break;
  }
  return "error (--norm " + measure_text(m) + ") = " + per +
         "; A_c = max over the window of |y_ref - mean(y_ref)|, A_g = the largest A_c among the "
         "selected channels of c's unit (channels without a scale left out); window: " +
         w.text();
}

}  // namespace evas::study
