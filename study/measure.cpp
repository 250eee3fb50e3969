// Channel selection, window and error measure (measure.h).
#include "study/measure.h"

#include <cmath>
#include <cstdlib>
#include <limits>

#include "study/case_grid.h"

namespace evas::study {

std::vector<int> select_channels(const std::vector<Channel>& channels,
                                 const std::string& patterns) {
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
    std::string names;
    for (const auto& c : channels) names += (names.empty() ? "" : ", ") + c.name;
    throw InputError(
        "--channels '" + patterns + "' matches no output channel (available: " +
        (names.empty() ? std::string("none; the scene's output lists no channels") : names) + ")");
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

Norm parse_norm(const std::string& text) {
  if (text == "max") return Norm::Max;
  if (text == "rms") return Norm::Rms;
  throw InputError("--norm '" + text + "': expected max or rms");
}

std::string norm_text(Norm n) { return n == Norm::Max ? "max" : "rms"; }

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

double relative_error(const Mat& y, const Mat& ref, const std::vector<int>& rows, Norm norm) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (rows.empty() || y.cols() != ref.cols()) return nan;
  for (int r : rows)
    if (r >= y.rows() || r >= ref.rows()) return nan;
  const std::vector<double> amp = amplitudes(ref, rows);
  double err = -1.0;
  for (int c = 0; c < ref.cols(); ++c) {
    const double a = amp[static_cast<std::size_t>(c)];
    if (!(a > 0.0)) continue;
    double e = 0.0;
    for (int r : rows) {
      const double d = std::abs(y(r, c) - ref(r, c)) / a;
      if (!std::isfinite(d)) return nan;
      e = norm == Norm::Max ? std::max(e, d) : e + d * d;
    }
    if (norm == Norm::Rms) e = std::sqrt(e / static_cast<double>(rows.size()));
    err = std::max(err, e);
  }
  return err < 0.0 ? nan : err;
}

std::string error_definition(Norm norm, const Window& w) {
  const std::string per = norm == Norm::Max ? "max over the window of |y - y_ref| / A_c"
                                            : "RMS over the window of (y - y_ref) / A_c";
  return "error = max over the selected channels c of the " + per +
         ", A_c = max over the window of |y_ref - mean(y_ref)| (channels with A_c = 0 left "
         "out); window: " +
         w.text();
}

}  // namespace evas::study
