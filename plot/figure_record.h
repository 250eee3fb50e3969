// Private to plot/: what the kinds of `evas plot` (figures.cpp,
// figures_spectra.cpp) share: the results file and its channels (Record), the
// figure's script and data (Figure, draw) and number formatting.
#pragma once

#include <fnmatch.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include "io/results.h"
#include "model/nearest_name.h"
#include "model/types.h"
#include "plot/figures.h"
#include "plot/gnuplot.h"

namespace evas::figure_detail {

namespace fs = std::filesystem;

inline std::string num(double x) {
  std::ostringstream os;
  os << std::setprecision(10) << x;
  return os.str();
}

inline std::string short_num(double x) {
  std::ostringstream os;
  os << std::setprecision(4) << x;
  return os.str();
}

inline std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

// A channel's display unit and the factor from its SI unit (plot/gnuplot.h).
using Scale = DisplayScale;
inline Scale display(const std::string& unit) { return display_scale(unit); }

// The quantity a unit measures, for an axis label ("" when not known).
inline std::string quantity(const std::string& unit) {
  static const std::vector<std::pair<std::string, std::string>> q = {
      {"N", "force"},
      {"N m", "torque"},
      {"W", "power"},
      {"m/s", "velocity"},
      {"m/s^2", "acceleration"},
      {"rad", "angle"},
      {"rad/s", "angular velocity"},
      {"rad/s^2", "angular acceleration"},
      {"Pa", "pressure"},
      {"m", "displacement"},
      {"deg", "angle"}};
  for (const auto& [u, name] : q)
    if (u == unit) return name;
  return "";
}

// The results file, its channels by name, and the rows a figure uses.
class Record {
 public:
  explicit Record(const std::string& path) : path_(path), d_(read_results(path)) {
    if (d_.time.empty()) throw InputError(path + ": the results hold no output row");
    for (std::size_t i = 0; i < d_.names.size(); ++i)
      if (d_.names[i] == "crank_angle") crank_ = static_cast<int>(i);
  }
  const ResultsData& data() const { return d_; }
  bool has_crank() const { return crank_ >= 0; }
  double crank(Eigen::Index r) const { return d_.values(r, crank_); }

  int find(const std::string& name) const {
    for (std::size_t i = 0; i < d_.names.size(); ++i)
      if (d_.names[i] == name) return static_cast<int>(i);
    return -1;
  }
  // The channel, or an error naming the channels there are like it.
  int require(const std::string& name, const std::string& why) const {
    const int i = find(name);
    if (i >= 0) return i;
    throw InputError(path_ + ": no channel '" + name + "'" + why + "; channels here: " + listing() +
                     " (" + nearest_text(name, d_.names) + ")");
  }
  // Exact names and globs (main*.fx), in file order, each once.
  std::vector<int> select(const std::vector<std::string>& patterns) const {
    std::vector<int> out;
    for (const auto& p : patterns) {
      bool any = false;
      for (std::size_t i = 0; i < d_.names.size(); ++i)
        if (fnmatch(p.c_str(), d_.names[i].c_str(), 0) == 0) {
          any = true;
          if (std::find(out.begin(), out.end(), static_cast<int>(i)) == out.end())
            out.push_back(static_cast<int>(i));
        }
      if (!any)
        throw InputError(path_ + ": no channel matches '" + p + "'; channels here: " + listing() +
                         " (" + nearest_text(p, d_.names) + ")");
    }
    return out;
  }
  // The journal bearings of the file: elements with ex, ey, eps channels.
  std::vector<std::string> bearings() const {
    std::vector<std::string> out;
    for (const auto& n : d_.names)
      if (n.size() > 3 && n.compare(n.size() - 3, 3, ".ex") == 0) {
        const std::string e = n.substr(0, n.size() - 3);
        if (find(e + ".ey") >= 0 && find(e + ".eps") >= 0) out.push_back(e);
      }
    return out;
  }
  int bearing_channel(const std::string& element, const std::string& ch) const {
    const int i = find(element + "." + ch);
    if (i >= 0) return i;
    const auto b = bearings();
    throw InputError(path_ + ": no channel '" + element + "." + ch +
                     "': this figure needs a journal-bearing element's channels (output: "
                     "{element: NAME}); journal bearings in this file: " +
                     (b.empty() ? std::string("none") : join(b)));
  }
  // The first row of the last `cycles` whole cycles (0: every row). n rows of
  // the uniform crank-angle grid cover n steps, as evas spectrum counts them:
  // evas periodic's 0 .. 719 deg is one whole cycle, its last cycle 720 rows.
  Eigen::Index first_row(int cycles, double cycle) const {
    if (cycles <= 0 || !has_crank()) return 0;
    const Eigen::Index n = d_.values.rows();
    const double end = crank(n - 1), span = end - crank(0);
    const double step = n > 1 ? span / static_cast<double>(n - 1) : 0.0;
    if (span + step < cycles * cycle * (1.0 - 1e-9))
      throw InputError(path_ + ": the record covers " + num(span + step) +
                       " deg of crank angle, less than " + std::to_string(cycles) +
                       " cycle(s) of " + num(cycle) +
                       " deg (give --cycles 0 for the whole record, or run longer)");
    Eigen::Index r = n - 1;
    while (r > 0 && crank(r - 1) > end - cycles * cycle + 0.5 * step) --r;
    return r;
  }
  // "FOLDER/results.h5": the run's folder names it
  std::string name() const {
    const fs::path p = fs::absolute(path_);
    return (p.parent_path().filename() / p.filename()).string();
  }

 private:
  std::string listing() const {
    std::string s;
    for (std::size_t i = 0; i < d_.names.size() && i < 24; ++i) s += (i ? ", " : "") + d_.names[i];
    if (d_.names.size() > 24) s += ", ... (" + std::to_string(d_.names.size()) + " in all)";
    return s;
  }
  std::string path_;
  ResultsData d_;
  int crank_ = -1;
};

// Crank angle within the cycle [0, cycle), or time; and its axis label.
struct Axis {
  bool crank = false;
  std::string label;
};
inline Axis x_axis(const Record& rec, const std::string& x, bool in_cycle, double cycle) {
  if (x == "crank-angle" && !rec.has_crank())
    throw InputError(rec.name() +
                     ": --x crank-angle needs the crank-angle output grid (a crank_angle "
                     "channel); this run is on the time grid");
  if (x != "auto" && x != "time" && x != "crank-angle")
    throw InputError("--x '" + x + "': give auto, time or crank-angle");
  Axis a;
  a.crank = rec.has_crank() && x != "time";
  a.label = a.crank ? (in_cycle ? "crank angle in the " + num(cycle) + "-deg cycle [deg]"
                                : std::string("crank angle [deg]"))
                    : "time [s]";
  return a;
}

struct Figure {
  std::ostringstream gp, dat;
};

inline std::vector<std::string> draw(const fs::path& out, Figure& f) {
  const fs::path gp = fs::path(out).replace_extension(".gp");
  const fs::path dat = fs::path(out).replace_extension(".dat");
  {
    std::ofstream g(gp), d(dat);
    if (!g || !d)
      throw InputError(out.parent_path().string() + ": cannot write the figure's files");
    g << f.gp.str();
    d << f.dat.str();
  }
  std::error_code ec;
  fs::remove(out, ec);  // a stale figure must not pass for a new one
  if (!run_gnuplot(gp) || !fs::exists(out))
    throw InputError("gnuplot failed on " + gp.string() + " (run it by hand to see why)");
  return {out.string(), gp.string(), dat.string()};
}

inline std::string dat_name(const fs::path& out) {
  return gp_quote(fs::path(out).replace_extension(".dat").filename().string());
}

// The kinds drawn over frequency or speed (figures_spectra.cpp).
void plot_order_track(const Record& rec, const PlotOptions& o, const fs::path& out, Figure& f);
void plot_spectrum(const Record& rec, const PlotOptions& o, const fs::path& out, Figure& f);
void plot_erp(const Record& rec, const PlotOptions& o, const fs::path& out, Figure& f);

}  // namespace evas::figure_detail
