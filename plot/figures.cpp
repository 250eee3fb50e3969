// `evas plot` (figures.h): data and gnuplot script of each kind of figure.
#include "plot/figures.h"

#include <fnmatch.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "io/results.h"
#include "model/nearest_name.h"
#include "model/types.h"
#include "plot/gnuplot.h"
#include "plot/study_figures.h"
#include "plot/sweep_figures.h"
#include "post/erp_spectrum.h"
#include "post/order_spectrum.h"
#include "post/order_tracking.h"
#include "post/radiation.h"

namespace evas {

namespace fs = std::filesystem;

namespace {

std::string num(double x) {
  std::ostringstream os;
  os << std::setprecision(10) << x;
  return os.str();
}

std::string short_num(double x) {
  std::ostringstream os;
  os << std::setprecision(4) << x;
  return os.str();
}

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

// A channel's display unit and the factor from its SI unit (plot/gnuplot.h).
using Scale = DisplayScale;
Scale display(const std::string& unit) { return display_scale(unit); }

// The quantity a unit measures, for an axis label ("" when not known).
std::string quantity(const std::string& unit) {
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
Axis x_axis(const Record& rec, const std::string& x, bool in_cycle, double cycle) {
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

std::vector<std::string> draw(const fs::path& out, Figure& f) {
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

std::string dat_name(const fs::path& out) {
  return gp_quote(fs::path(out).replace_extension(".dat").filename().string());
}

void plot_channels(const Record& rec, const PlotOptions& o, const fs::path& out, Figure& f) {
  if (o.channels.empty())
    throw InputError("plot channels: give --channel NAME (repeatable, globs allowed)");
  const auto idx = rec.select(o.channels);
  const ResultsData& d = rec.data();
  const Axis ax = x_axis(rec, o.x, false, o.cycle);
  const Eigen::Index r0 = rec.first_row(o.cycles, o.cycle);
  std::vector<Scale> sc;
  std::string units;
  for (int i : idx) {
    sc.push_back(display(d.units[i]));
    if (units.find("[" + sc.back().unit + "]") == std::string::npos) {
      const std::string what = quantity(d.units[i]);
      units += (units.empty() ? "" : ", ") + (what.empty() ? "" : what + " ") + "[" +
               sc.back().unit + "]";
    }
  }
  // the last whole cycles against the angle in the cycle (0 .. 720 deg per
  // cycle drawn, as the film and polar figures), not the record's angle
  double offset = 0.0;
  std::string xlabel = ax.label;
  if (ax.crank && o.cycles > 0 && r0 < d.values.rows()) {
    offset = std::floor(rec.crank(r0) / o.cycle + 1e-9) * o.cycle;
    if (offset != 0.0)
      xlabel = "crank angle in the cycle [deg] (the record's " + short_num(offset) + " deg + x)";
  }
  for (Eigen::Index r = r0; r < d.values.rows(); ++r) {
    f.dat << num(ax.crank ? rec.crank(r) - offset : d.time[r]);
    for (std::size_t k = 0; k < idx.size(); ++k)
      f.dat << " " << num(sc[k].factor * d.values(r, idx[k]));
    f.dat << "\n";
  }
  f.gp << gp_terminal(out, 1000, 600) << "set title "
       << gp_quote(o.title.empty() ? rec.name() + ": channels" : o.title) << "\n"
       << "set xlabel " << gp_quote(xlabel) << "\nset ylabel " << gp_quote(units) << "\n"
       << "set grid\nset autoscale xfix\nset key outside right top\nplot ";
  for (std::size_t k = 0; k < idx.size(); ++k)
    f.gp << (k ? ", \\\n     " : "") << dat_name(out) << " using 1:" << k + 2
         << " with lines lw 1.5 title " << gp_quote(d.names[idx[k]] + " [" + sc[k].unit + "]");
  f.gp << "\n";
}

void plot_polar(const Record& rec, const PlotOptions& o, const fs::path& out, Figure& f) {
  const int fx = rec.bearing_channel(o.element, "fx"), fy = rec.bearing_channel(o.element, "fy");
  const int jx = rec.bearing_channel(o.element, "fx_journal"),
            jy = rec.bearing_channel(o.element, "fy_journal");
  const ResultsData& d = rec.data();
  const Eigen::Index r0 = rec.first_row(o.cycles, o.cycle);
  // block 0: the load on the shell (-f, bearing axes); block 1: on the journal
  // (journal axes); blocks 2, 3: their points every 90 deg of crank angle
  for (int block = 0; block < 2; ++block) {
    for (Eigen::Index r = r0; r < d.values.rows(); ++r) {
      const double x = block == 0 ? -d.values(r, fx) : d.values(r, jx);
      const double y = block == 0 ? -d.values(r, fy) : d.values(r, jy);
      f.dat << num(1e-3 * x) << " " << num(1e-3 * y) << "\n";
    }
    f.dat << "\n\n";
  }
  // labels: blocks 2 + 2 p (the first half of the cycle) and 3 + 2 p (the
  // second, offset the other way: in-line engines repeat their loads each
  // revolution) of panel p
  for (int block = 0; block < 2; ++block)
    for (int half = 0; half < 2; ++half) {
      if (rec.has_crank())
        for (Eigen::Index r = r0; r < d.values.rows(); ++r) {
          const double a = std::fmod(rec.crank(r), o.cycle);
          if (std::abs(std::remainder(a, 90.0)) > 1e-6 ||
              (a >= 0.5 * o.cycle - 1e-6) != (half == 1))
            continue;
          const double x = block == 0 ? -d.values(r, fx) : d.values(r, jx);
          const double y = block == 0 ? -d.values(r, fy) : d.values(r, jy);
          f.dat << num(1e-3 * x) << " " << num(1e-3 * y) << " " << std::lround(a) << "\n";
        }
      f.dat << "0 0 \"\"\n\n\n";  // never empty: the centre
    }
  const std::string span =
      rec.has_crank() && o.cycles > 0 ? ", last " + std::to_string(o.cycles) + " cycle(s)" : "";
  f.gp << gp_terminal(out, 1300, 650) << "set multiplot layout 1,2 title "
       << gp_quote(o.title.empty() ? "polar load diagram of " + o.element + " (" + rec.name() +
                                         span + "; labels: crank angle in the cycle [deg])"
                                   : o.title)
       << "\nset grid\nset xzeroaxis lt -1\nset yzeroaxis lt -1\nunset key\n";
  const char* titles[2] = {"load on the shell (from the journal), bearing axes",
                           "load on the journal (from the film), axes turning with the journal"};
  for (int block = 0; block < 2; ++block) {
    // equal scales unless the load swings 4 times more along one axis than the
    // other (an outer main bearing's loads are a narrow strip at equal scale)
    double wx = 0.0, wy = 0.0;
    for (Eigen::Index r = r0; r < d.values.rows(); ++r) {
      wx = std::max(wx, std::abs(block == 0 ? d.values(r, fx) : d.values(r, jx)));
      wy = std::max(wy, std::abs(block == 0 ? d.values(r, fy) : d.values(r, jy)));
    }
    const bool equal = !(wx > 4.0 * wy || wy > 4.0 * wx);
    const std::string dat = dat_name(out);
    f.gp << (equal ? "set size ratio -1\n" : "set size ratio 1\n") << "set title "
         << gp_quote(std::string(titles[block]) + (equal ? "" : " (x, y to different scales)"))
         << (block == 0
                 ? "\nset xlabel 'x, bearing axis x [kN]'\nset ylabel 'y, bearing axis y [kN]'\n"
                 : "\nset xlabel 'x, journal axis x [kN]'\nset ylabel 'y, journal axis y [kN]'\n")
         << "plot " << dat << " index " << block << " using 1:2 with lines lw 1.5 lc "
         << (block + 1);
    for (int half = 0; half < 2; ++half)
      f.gp << ", \\\n     " << dat << " index " << 2 + 2 * block + half
           << " using 1:2 with points pt 7 ps 0.8 lc rgb 'black', \\\n     " << dat << " index "
           << 2 + 2 * block + half << " using 1:2:3 with labels offset "
           << (half ? "-1.5,-0.8" : "1.5,0.8") << " tc rgb 'gray20'";
    f.gp << "\n";
  }
  f.gp << "unset multiplot\n";
}

void plot_orbit(const Record& rec, const PlotOptions& o, const fs::path& out, Figure& f) {
  const int ex = rec.bearing_channel(o.element, "ex"), ey = rec.bearing_channel(o.element, "ey");
  const int ep = rec.bearing_channel(o.element, "eps");
  const ResultsData& d = rec.data();
  const Eigen::Index r0 = rec.first_row(o.cycles, o.cycle);
  // the clearance from the channels themselves: c = |e| / eps
  std::vector<double> c;
  for (Eigen::Index r = 0; r < d.values.rows(); ++r)
    if (d.values(r, ep) > 1e-3)
      c.push_back(std::hypot(d.values(r, ex), d.values(r, ey)) / d.values(r, ep));
  if (c.empty())
    throw InputError(rec.name() + ": " + o.element +
                     ".eps stays below 1e-3: the clearance cannot be read from the orbit");
  std::nth_element(c.begin(), c.begin() + static_cast<long>(c.size() / 2), c.end());
  const double cl = 1e6 * c[c.size() / 2];
  for (Eigen::Index r = r0; r < d.values.rows(); ++r)
    f.dat << num(1e6 * d.values(r, ex)) << " " << num(1e6 * d.values(r, ey)) << "\n";
  f.dat << "\n\n";
  for (int k = 0; k <= 360; ++k)
    f.dat << num(cl * std::cos(k * M_PI / 180.0)) << " " << num(cl * std::sin(k * M_PI / 180.0))
          << "\n";
  const std::string span =
      rec.has_crank() && o.cycles > 0 ? ", last " + std::to_string(o.cycles) + " cycle(s)" : "";
  f.gp << gp_terminal(out, 800, 800) << "set title "
       << gp_quote(o.title.empty()
                       ? "journal orbit of " + o.element + " (" + rec.name() + span + ")"
                       : o.title)
       << "\nset size ratio -1\nset grid\nset xzeroaxis lt -1\nset yzeroaxis lt -1\n"
       << "set xlabel 'e_x, bearing axes [\u00b5m]'\nset ylabel 'e_y, bearing axes [\u00b5m]'\n"
       << "set key inside bottom right box opaque\n"
       << "plot " << dat_name(out) << " index 1 using 1:2 with lines lw 2 lc rgb 'gray40' title "
       << gp_quote("clearance circle, c = " + num(std::round(cl * 100) / 100) + " \u00b5m")
       << ", \\\n     " << dat_name(out)
       << " index 0 using 1:2 with lines lw 1.5 lc 1 title 'journal centre'\n";
}

void plot_film(const Record& rec, const PlotOptions& o, const fs::path& out, Figure& f) {
  const int h = rec.bearing_channel(o.element, "h_min"),
            p = rec.bearing_channel(o.element, "p_max");
  const ResultsData& d = rec.data();
  const Axis ax = x_axis(rec, o.x, o.cycles > 0, o.cycle);
  const Eigen::Index r0 = rec.first_row(o.cycles, o.cycle);
  double last = -1e300;
  for (Eigen::Index r = r0; r < d.values.rows(); ++r) {
    const double x =
        ax.crank ? (o.cycles > 0 ? std::fmod(rec.crank(r), o.cycle) : rec.crank(r)) : d.time[r];
    if (x < last) f.dat << "\n";  // a new cycle: a new line
    last = x;
    f.dat << num(x) << " " << num(1e6 * d.values(r, h)) << " " << num(1e-6 * d.values(r, p))
          << "\n";
  }
  f.gp << gp_terminal(out, 1000, 600) << "set title "
       << gp_quote(o.title.empty() ? "oil film of " + o.element + " (" + rec.name() + ")" : o.title)
       << "\nset xlabel " << gp_quote(ax.label)
       << "\nset ylabel 'minimum film thickness h_min [\u00b5m]'\nset y2label 'peak film pressure "
          "p_max "
          "[MPa]'\n"
       << "set ytics nomirror\nset y2tics\nset grid\nset key outside top center horizontal\n"
       << (ax.crank && o.cycles > 0 ? "set xrange [0:" + num(o.cycle) + "]\nset xtics 90\n" : "")
       << "plot " << dat_name(out)
       << " using 1:2 axes x1y1 with lines lw 1.5 lc 1 title 'h_min [\u00b5m]', \\\n     "
       << dat_name(out) << " using 1:3 axes x1y2 with lines lw 1.5 lc 2 title 'p_max [MPa]'\n";
}

void plot_order(const Record& rec, const PlotOptions& o, const fs::path& out, Figure& f) {
  if (o.channels.size() != 1) throw InputError("plot order: give one --channel NAME");
  const int c = rec.require(o.channels[0], "");
  if (!rec.has_crank())
    throw InputError(
        rec.name() +
        ": an order spectrum needs the crank-angle output grid (a crank_angle channel); "
        "plot the spectrum over time with: evas plot spectrum");
  const ResultsData& d = rec.data();
  std::vector<double> th(static_cast<std::size_t>(d.values.rows())), y(th.size());
  for (Eigen::Index r = 0; r < d.values.rows(); ++r) {
    th[static_cast<std::size_t>(r)] = rec.crank(r);
    y[static_cast<std::size_t>(r)] = d.values(r, c);
  }
  const OrderSpectrum s = order_spectrum(th, y, o.cycles, o.cycle, o.max_order);
  // the cycles pooled: at one speed, or a run-up's (then say so)
  std::string pooled;
  {
    const std::size_t used = static_cast<std::size_t>(s.cycles) *
                             static_cast<std::size_t>(std::lround(o.cycle / (th[1] - th[0])));
    const std::size_t first = th.size() - std::min(used, th.size());
    const std::vector<double> tt(d.time.begin() + static_cast<long>(first), d.time.end());
    const std::vector<double> ta(th.begin() + static_cast<long>(first), th.end());
    if (s.cycles >= 2 && speed_spread(tt, ta, o.cycle) > 0.02) {
      std::vector<double> zero(ta.size(), 0.0);
      const OrderTrack tr = order_tracking(tt, ta, zero, {}, o.cycle);
      const auto [lo, hi] = std::minmax_element(tr.rpm.begin(), tr.rpm.end());
      pooled = "; the cycles pooled run from " + short_num(*lo) + " to " + short_num(*hi) +
               " rpm (a run-up: evas plot order-track draws each order against speed)";
      std::cerr << "evas plot order: warning: " << rec.name() << pooled.substr(1) << "\n";
    }
  }
  const Scale sc = display(d.units[c]);
  for (std::size_t k = 0; k < s.order.size(); ++k)
    f.dat << num(s.order[k]) << " " << num(sc.factor * s.amplitude[k]) << "\n";
  f.gp << gp_terminal(out, 1000, 600) << "set title "
       << gp_quote(o.title.empty() ? "order spectrum of " + d.names[c] + " (" + rec.name() +
                                         "): " + cycles_used(s, o.cycle) + pooled
                                   : o.title)
       << "\nset xlabel 'engine order [-]'\nset ylabel " << gp_quote("amplitude [" + sc.unit + "]")
       << "\nset grid\nset xtics 1\nset mxtics 2\nset xrange [-0.25:" << num(o.max_order + 0.25)
       << "]\nset yrange [0:*]\nunset key\nplot " << dat_name(out)
       << " using 1:2 with impulses lw 6 lc 1\n";
}

// Order tracking of a run-up (post/order_tracking.h): each order's amplitude
// per 720-deg cycle against the cycle's mean speed.
void plot_order_track(const Record& rec, const PlotOptions& o, const fs::path& out, Figure& f) {
  if (o.channels.empty()) throw InputError("plot order-track: give --channel NAME (repeatable)");
  if (!rec.has_crank())
    throw InputError(rec.name() +
                     ": order tracking needs the crank-angle output grid (a crank_angle channel)");
  const ResultsData& d = rec.data();
  std::vector<int> cols;
  for (const auto& name : o.channels) cols.push_back(rec.require(name, ""));
  std::vector<double> th;
  for (Eigen::Index r = 0; r < d.values.rows(); ++r) th.push_back(rec.crank(r));
  const std::vector<double> orders =
      o.orders.empty() ? std::vector<double>{1.0, 2.0, 4.0, 6.0} : o.orders;
  const Scale sc = display(d.units[static_cast<std::size_t>(cols[0])]);
  for (int c : cols)
    if (d.units[static_cast<std::size_t>(c)] != d.units[static_cast<std::size_t>(cols[0])])
      throw InputError("plot order-track: the channels have different units (" +
                       d.names[static_cast<std::size_t>(cols[0])] + ": " +
                       d.units[static_cast<std::size_t>(cols[0])] + ", " +
                       d.names[static_cast<std::size_t>(c)] + ": " +
                       d.units[static_cast<std::size_t>(c)] + ")");
  // powers' cycle means (ERP) as levels: they span decades
  const bool levels =
      d.units[static_cast<std::size_t>(cols[0])] == "W" && orders.size() == 1 && orders[0] == 0.0;
  double change = 0.0;
  std::size_t cycles = 0;
  std::vector<std::string> titles;
  for (int c : cols) {
    std::vector<double> y;
    for (Eigen::Index r = 0; r < d.values.rows(); ++r) y.push_back(d.values(r, c));
    const OrderTrack tr = order_tracking(d.time, th, y, orders, o.cycle);
    cycles = tr.rpm.size();
    for (double x : tr.change) change = std::max(change, std::abs(x));
    for (std::size_t j = 0; j < orders.size(); ++j) {
      for (std::size_t k = 0; k < tr.rpm.size(); ++k) {
        const double a = tr.amplitude[k][j];
        f.dat << num(tr.rpm[k]) << " "
              << (levels ? (a > 0.0 ? num(10.0 * std::log10(a / 1e-12)) : std::string("NaN"))
                         : num(sc.factor * a))
              << "\n";
      }
      f.dat << "\n\n";
      const std::string what =
          orders[j] == 0.0 ? "mean (order 0)" : "order " + short_num(orders[j]);
      titles.push_back(cols.size() > 1 ? d.names[static_cast<std::size_t>(c)] + " " + what : what);
    }
  }
  const std::string who = cols.size() == 1 ? d.names[static_cast<std::size_t>(cols[0])]
                                           : std::to_string(cols.size()) + " channels";
  f.gp << gp_terminal(out, 1000, 600) << "set title "
       << gp_quote(o.title.empty()
                       ? "order tracking of " + who + " (" + rec.name() +
                             "): " + std::to_string(cycles) + " cycles of " + short_num(o.cycle) +
                             " deg, speed change within a cycle up to " +
                             short_num(100.0 * change) + " %"
                       : o.title)
       << "\nset xlabel 'crank speed [rpm] (mean of each cycle)'\nset ylabel "
       << gp_quote(levels ? "mean over the cycle, level [dB re 1 pW]"
                          : "amplitude [" + sc.unit + "]")
       << "\nset grid\n"
       << (levels ? "" : "set yrange [0:*]\n") << "set key outside bottom center horizontal\nplot ";
  for (std::size_t j = 0; j < titles.size(); ++j)
    f.gp << (j ? ", " : "") << dat_name(out) << " index " << j
         << " using 1:2 with linespoints lw 2 pt 7 ps 0.6 lc " << j + 1 << " title "
         << gp_quote(titles[j]);
  f.gp << "\n";
}

void plot_spectrum(const Record& rec, const PlotOptions& o, const fs::path& out, Figure& f) {
  if (o.channels.size() != 1) throw InputError("plot spectrum: give one --channel NAME");
  const int c = rec.require(o.channels[0], "");
  const ResultsData& d = rec.data();
  std::vector<double> y(static_cast<std::size_t>(d.values.rows()));
  for (Eigen::Index r = 0; r < d.values.rows(); ++r)
    y[static_cast<std::size_t>(r)] = d.values(r, c);
  const TimeSpectrum s = time_spectrum(d.time, y, o.spectrum);
  const Scale sc = display(d.units[c]);
  double top = 0.0;
  for (std::size_t k = 0; k < s.frequency.size(); ++k) {
    if (o.max_frequency > 0.0 && s.frequency[k] > o.max_frequency) break;
    if (k == 0) continue;  // the mean is removed
    f.dat << num(s.frequency[k]) << " " << num(sc.factor * s.amplitude[k]) << "\n";
    top = std::max(top, sc.factor * s.amplitude[k]);
  }
  if (s.frequency.size() < 2 || (o.max_frequency > 0.0 && o.max_frequency < s.frequency[1]))
    throw InputError("--max-frequency " + num(o.max_frequency) +
                     " Hz is below the first bin (df = " + num(s.df) + " Hz)");
  if (!(top > 0.0))
    throw InputError(rec.name() + ": " + d.names[c] + " is constant over the window");
  f.gp << gp_terminal(out, 1000, 600) << "set title "
       << gp_quote(o.title.empty()
                       ? "spectrum of " + d.names[c] + " (" + rec.name() +
                             ", t = " + short_num(s.t0) + " .. " + short_num(s.t1) + " s, " +
                             o.spectrum.window + " window, df = " + short_num(s.df) + " Hz)"
                       : o.title)
       << "\nset xlabel 'frequency [Hz]'\nset ylabel " << gp_quote("amplitude [" + sc.unit + "]")
       << "\nset logscale y\nset yrange [" << num(top * 1e-5) << ":" << num(top * 2) << "]\n"
       << "set grid\nunset key\nplot " << dat_name(out) << " using 1:2 with lines lw 1.2 lc 1\n";
}

// ERP of a surface output: the tonal power per bin and the third-octave band
// powers, as levels [dB re 1 pW] (post/erp_spectrum.h).
void plot_erp(const Record& rec, const PlotOptions& o, const fs::path& out, Figure& f) {
  if (o.channels.size() != 1)
    throw InputError("plot erp: give one --channel NAME, the surface output's name");
  const std::string& name = o.channels[0];
  const ResultsData& d = rec.data();
  const std::vector<std::vector<double>> comps = erp_components(d.names, d.values, name);
  if (comps.empty()) rec.require(name + ".c0", " (the ERP components of a surface output)");
  std::vector<ErpBand> bands;
  const ErpSpectrum s = erp_spectrum(d.time, comps, o.spectrum, &bands);
  const double fmax = o.max_frequency > 0.0 ? o.max_frequency : s.frequency.back();
  double top = 0.0;
  for (std::size_t k = 1; k < s.frequency.size() && s.frequency[k] <= fmax; ++k)
    if (s.power[k] > 0.0) {
      f.dat << num(s.frequency[k]) << " " << num(erp_level(s.power[k])) << "\n";
      top = std::max(top, erp_level(s.power[k]));
    }
  if (!(top != 0.0)) throw InputError(rec.name() + ": " + name + " radiates no power");
  f.dat << "\n\n";  // second data block: the bands as steps
  auto steps = [&](const std::vector<ErpBand>& bl, bool a_weighted) {
    bool any = false;
    for (const ErpBand& b : bl)
      if (b.bins > 0 && b.power > 0.0 && b.lower <= fmax) {
        const double l = erp_level(b.power) + (a_weighted ? a_weighting_db(b.centre) : 0.0);
        f.dat << num(b.lower) << " " << num(l) << "\n";
        f.dat << num(b.upper) << " " << num(l) << "\n\n";
        top = std::max(top, l);
        any = true;
      }
    if (!any) f.dat << "nan nan\n";  // an empty block would end the file for gnuplot
  };
  steps(bands, false);
  // the elastic part (components NAME.e<k>), unweighted and A-weighted
  const std::vector<std::vector<double>> ecomps = erp_components(d.names, d.values, name, "e");
  std::vector<ErpBand> ebands;
  ErpSpectrum e;
  if (!ecomps.empty()) {
    e = erp_spectrum(d.time, ecomps, o.spectrum, &ebands);
    f.dat << "\n";
    steps(ebands, false);
    f.dat << "\n";
    steps(ebands, true);
  }
  std::string mean = "mean " + short_num(erp_level(s.mean)) + " dB";
  if (!ecomps.empty() && e.mean > 0.0) mean += ", elastic " + short_num(erp_level(e.mean)) + " dB";
  f.gp << gp_terminal(out, 1000, 600) << "set title "
       << gp_quote(o.title.empty()
                       ? "ERP of " + name + " (" + rec.name() + ", t = " + short_num(s.t0) +
                             " .. " + short_num(s.t1) + " s, " + o.spectrum.window +
                             " window, df = " + short_num(s.df) + " Hz; " + mean + ")"
                       : o.title)
       << "\nset xlabel 'frequency [Hz]'\nset ylabel 'ERP level [dB re 1 pW; dB(A) re 1 pW]'\n"
       << "set logscale x\nset xrange [" << num(std::max(s.df, 10.0)) << ":" << num(fmax)
       << "]\nset yrange [" << num(top - 80.0) << ":" << num(top + 5.0) << "]\n"
       << "set grid\nset key outside bottom center horizontal\nplot " << dat_name(out)
       << " index 0 using 1:2 with impulses lw 1.5 lc rgb '#a0a0a0' title 'per bin (tonal power)', "
       << dat_name(out) << " index 1 using 1:2 with lines lw 2.5 lc 1 title 'third-octave bands'";
  if (!ecomps.empty())
    f.gp << ", " << dat_name(out)
         << " index 2 using 1:2 with lines lw 2.5 lc 2 title 'elastic part (rigid-body motion "
            "left out)', "
         << dat_name(out)
         << " index 3 using 1:2 with lines lw 2 dt 2 lc 3 title 'elastic part, "
            "A-weighted [dB(A)]'";
  f.gp << "\n";
}

// waterfall, campbell, order-cuts of a sweep file (plot/sweep_figures.h).
std::vector<std::string> plot_sweep_file(const std::string& path, const PlotOptions& o,
                                         const fs::path& out) {
  const SweepFigureData d = read_sweep_figures(
      path, "plot " + o.kind + ": a " + (o.kind == "order-cuts" ? "set of order cuts" : o.kind) +
                " is drawn from a sweep over operating points");
  if (!has_spectra(d))
    throw InputError(path +
                     ": the sweep holds no order spectra (no completed run on the "
                     "crank-angle grid with the cycles asked for)");
  std::vector<int> chans;
  for (const auto& c : o.channels) chans.push_back(sweep_channel(d, c, path));
  if (o.kind == "campbell" && !chans.empty())
    throw InputError("plot campbell: --channel does not apply (the diagram has no channel)");
  if (chans.empty()) chans.push_back(0);
  if (o.kind == "waterfall" && chans.size() != 1)
    throw InputError("plot waterfall: give one --channel NAME");
  Figure f;
  if (o.kind == "waterfall") {
    f.gp << waterfall_script(d, chans.front(), out);
  } else if (o.kind == "campbell") {
    const std::string c = campbell_script(d, out);
    if (c.empty()) throw InputError(path + ": no task of the sweep has a crank speed");
    f.gp << c;
  } else {
    const std::vector<double> orders = o.orders.empty() ? std::vector<double>{1, 2, 4} : o.orders;
    for (double x : orders)
      if (std::none_of(d.orders.begin(), d.orders.end(),
                       [&](double y) { return std::abs(x - y) < 1e-9; }))
        throw InputError("--order " + num(x) + ": the sweep's spectra hold orders 0.5 .. " +
                         num(d.orders.empty() ? 0.0 : d.orders.back()) + " in steps of 0.5");
    f.gp << order_cuts_script(d, chans, orders, out);
  }
  std::error_code ec;
  if (out.has_parent_path()) fs::create_directories(out.parent_path(), ec);
  return draw(out, f);
}

}  // namespace

const std::vector<std::pair<std::string, std::string>>& plot_kinds() {
  static const std::vector<std::pair<std::string, std::string>> k = {
      {"channels", "channels (--channel, globs) against crank angle or time"},
      {"polar",
       "polar load diagram of a journal bearing (--element), on the shell and the journal"},
      {"orbit", "journal orbit inside the clearance circle (--element)"},
      {"film", "minimum film thickness and peak pressure against crank angle (--element)"},
      {"order", "order spectrum of a channel (--channel) over whole cycles"},
      {"order-track",
       "order tracking of a run-up: amplitude of orders (--order) of a channel (--channel) "
       "per cycle against speed"},
      {"spectrum", "amplitude spectrum of a channel (--channel) over frequency"},
      {"erp",
       "equivalent radiated power of a surface output (--channel NAME): per bin and "
       "in third-octave bands"},
      {"waterfall", "order spectra of a channel (--channel) against the swept value (sweep.h5)"},
      {"campbell", "natural frequencies against speed with the engine orders (sweep.h5)"},
      {"order-cuts",
       "amplitude of orders (--order) of channels (--channel) against the swept "
       "value (sweep.h5)"},
      {"work-precision",
       "error against wall time and residual evaluations of a work-precision "
       "study (study.h5)"}};
  return k;
}

std::vector<std::string> plot_results(const std::string& results, const PlotOptions& o,
                                      const fs::path& out) {
  bool known = false;
  std::string names;
  for (const auto& [k, what] : plot_kinds()) {
    known = known || k == o.kind;
    names += (names.empty() ? "" : ", ") + k;
  }
  if (!known) throw InputError("plot: unknown kind '" + o.kind + "' (known: " + names + ")");
  const std::string ext = out.extension().string();
  if (ext != ".png" && ext != ".svg")
    throw InputError("--out " + out.string() + ": give a file name ending in .png or .svg");
  const bool by_element = o.kind == "polar" || o.kind == "orbit" || o.kind == "film";
  if (by_element && o.element.empty())
    throw InputError("plot " + o.kind + ": give --element NAME (a journal bearing)");
  if (!by_element && !o.element.empty())
    throw InputError("plot " + o.kind + ": --element applies to polar, orbit and film");
  if (!have_gnuplot())
    throw InputError("plot: gnuplot is not installed (apt-get install gnuplot-nox)");
  if (o.kind == "waterfall" || o.kind == "campbell" || o.kind == "order-cuts")
    return plot_sweep_file(results, o, out);
  if (o.kind == "work-precision") {
    if (!o.channels.empty())
      throw InputError(
          "plot work-precision: --channel does not apply (the study's error "
          "covers the channels it was run with)");
    Figure f;
    f.gp << work_precision_script(read_work_precision(results), out);
    if (f.gp.str().empty())
      throw InputError(results + ": no case of the study completed with an error > 0");
    std::error_code ec;
    if (out.has_parent_path()) fs::create_directories(out.parent_path(), ec);
    return draw(out, f);
  }
  const Record rec(results);
  Figure f;
  if (o.kind == "channels") plot_channels(rec, o, out, f);
  if (o.kind == "polar") plot_polar(rec, o, out, f);
  if (o.kind == "orbit") plot_orbit(rec, o, out, f);
  if (o.kind == "film") plot_film(rec, o, out, f);
  if (o.kind == "order") plot_order(rec, o, out, f);
  if (o.kind == "order-track") plot_order_track(rec, o, out, f);
  if (o.kind == "spectrum") plot_spectrum(rec, o, out, f);
  if (o.kind == "erp") plot_erp(rec, o, out, f);
  std::error_code ec;
  if (out.has_parent_path()) fs::create_directories(out.parent_path(), ec);
  return draw(out, f);
}

}  // namespace evas
