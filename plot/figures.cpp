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
#include "plot/figure_record.h"
#include "plot/gnuplot.h"
#include "plot/study_figures.h"
#include "plot/sweep_figures.h"
#include "post/erp_spectrum.h"
#include "post/order_spectrum.h"
#include "post/order_tracking.h"
#include "post/radiation.h"

namespace evas {

namespace fs = std::filesystem;

using namespace figure_detail;

namespace {

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
