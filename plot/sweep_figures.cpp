#include "plot/sweep_figures.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "io/hdf5_util.h"
#include "model/types.h"
#include "plot/gnuplot.h"
#include "plot/study_file.h"

namespace evas {

namespace fs = std::filesystem;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The figures' x axis: the mean speed when the speed changes over the grid,
// else the first key's number. Curves: the points of the first case grouped by
// the values of the other keys.
struct Axis {
  std::string label;
  std::vector<double> x;                           // per task
  std::map<std::string, std::vector<int>> groups;  // group label -> tasks, grid order
  std::vector<std::string> order;                  // group labels in order of first appearance
};

Axis figure_axis(const SweepFigureData& d) {
  Axis a;
  double lo = INFINITY, hi = -INFINITY;
  for (const auto& t : d.tasks)
    if (std::isfinite(t.rpm)) {
      lo = std::min(lo, t.rpm);
      hi = std::max(hi, t.rpm);
    }
  const bool by_speed = std::isfinite(lo) && hi - lo > 1e-6 * std::max(1.0, std::abs(hi));
  a.label = by_speed ? "mean crank speed [rpm]" : d.keys.front();
  for (std::size_t k = 0; k < d.tasks.size(); ++k) {
    const SweepFigureData::Task& t = d.tasks[k];
    double x = by_speed ? t.rpm : kNaN;
    if (!by_speed) {
      char* end = nullptr;
      x = std::strtod(t.values.front().c_str(), &end);
      if (t.values.front().empty() || *end) x = t.point;
    }
    a.x.push_back(x);
    if (t.case_index != 0) continue;
    std::string grp;  // the first key is the axis (or the speed it sets)
    for (std::size_t j = 1; j < d.keys.size(); ++j)
      grp += (grp.empty() ? "" : ", ") + d.keys[j] + "=" + t.values[j];
    if (!a.groups.count(grp)) a.order.push_back(grp);
    a.groups[grp].push_back(static_cast<int>(k));
  }
  return a;
}

std::size_t order_index(const SweepFigureData& d, double o) {
  for (std::size_t j = 0; j < d.orders.size(); ++j)
    if (std::abs(d.orders[j] - o) < 1e-9) return j;
  return d.orders.size();
}

}  // namespace

bool has_spectra(const SweepFigureData& d) {
  for (const auto& a : d.amplitude)
    if (!a.empty()) return true;
  return false;
}

int sweep_channel(const SweepFigureData& d, const std::string& name, const std::string& file) {
  for (std::size_t i = 0; i < d.names.size(); ++i)
    if (d.names[i] == name) return static_cast<int>(i);
  std::string have;
  for (const auto& n : d.names) have += (have.empty() ? "" : ", ") + n;
  throw InputError(file + ": the sweep has no order spectra of '" + name +
                   "' (channels with spectra: " + (have.empty() ? "none" : have) + ")");
}

SweepFigureData read_sweep_figures(const std::string& path, const std::string& why) {
  SweepFigureData d;
  h5::Quiet quiet;
  try {
    h5::Handle f = h5::open_file(path);
    expect_study_file(f, path, "sweep", why, "a sweep file",
                      "`evas study sweep` writes sweep.h5 into its folder");
    d.scene_name = h5::read_string_attribute(f, "scene_name");
    d.cycles = static_cast<int>(h5::read_int_attribute(f, "cycles_per_spectrum"));
    std::vector<hsize_t> dims;
    d.keys = h5::read_strings(f, "/grid/keys");
    std::vector<std::vector<std::string>> values;  // per key, per point
    for (std::size_t j = 0; j < d.keys.size(); ++j)
      values.push_back(h5::read_strings(f, "/grid/value" + std::to_string(j)));
    const std::vector<long long> point = h5::read_int64s(f, "/tasks/point", dims);
    const std::vector<long long> cs = h5::read_int64s(f, "/tasks/case", dims);
    const std::vector<double> rpm = h5::read_doubles(f, "/tasks/mean_rpm", dims);
    if (cs.size() != point.size() || rpm.size() != point.size())
      throw h5::Failure("the /tasks datasets differ in length");
    for (std::size_t k = 0; k < point.size(); ++k) {
      SweepFigureData::Task t;
      t.point = static_cast<int>(point[k]);
      t.case_index = static_cast<int>(cs[k]);
      t.rpm = rpm[k];
      for (const auto& v : values) {
        if (t.point < 0 || static_cast<std::size_t>(t.point) >= v.size())
          throw h5::Failure("task " + std::to_string(k) + " names point " +
                            std::to_string(t.point) + ", which the grid does not have");
        t.values.push_back(v[static_cast<std::size_t>(t.point)]);
      }
      d.tasks.push_back(std::move(t));
    }
    d.names = h5::read_strings(f, "/channels/names");
    d.units = h5::read_strings(f, "/channels/units");
    d.orders = h5::read_doubles(f, "/orders/order", dims);
    const std::vector<double> amp = h5::read_doubles(f, "/orders/amplitude", dims);
    const std::size_t nt = d.tasks.size(), nc = d.names.size(), no = d.orders.size();
    if (amp.size() != nt * nc * no)
      throw h5::Failure("/orders/amplitude does not hold tasks x channels x orders values");
    for (std::size_t k = 0; k < nt; ++k) {
      std::vector<std::vector<double>> a(nc, std::vector<double>(no));
      bool any = false;
      for (std::size_t c = 0; c < nc; ++c)
        for (std::size_t o = 0; o < no; ++o) {
          a[c][o] = amp[(k * nc + c) * no + o];
          any = any || std::isfinite(a[c][o]);
        }
      d.amplitude.push_back(any ? std::move(a) : std::vector<std::vector<double>>{});
    }
    if (!d.orders.empty()) d.max_order = d.orders.back();
    const std::vector<double> hz = h5::read_doubles(f, "/campbell/frequency", dims);
    const auto body = h5::read_strings(f, "/campbell/body");
    const auto kinds = h5::read_strings(f, "/campbell/kind");
    const auto dir = h5::read_strings(f, "/campbell/direction");
    if (body.size() != hz.size() || kinds.size() != hz.size() || dir.size() != hz.size())
      throw h5::Failure("the /campbell datasets differ in length");
    for (std::size_t i = 0; i < hz.size(); ++i) {
      NaturalFrequency n;
      n.hz = hz[i];
      n.body = body[i];
      n.kind = kinds[i];
      n.direction = dir[i];
      d.natural.push_back(n);
    }
    if (h5::exists(f, "/assembled/frequency")) {  // sweeps before it have none
      const std::vector<double> rpm = h5::read_doubles(f, "/assembled/speed", dims);
      const std::vector<double> ahz = h5::read_doubles(f, "/assembled/frequency", dims);
      const std::vector<double> zeta = h5::read_doubles(f, "/assembled/damping_ratio", dims);
      const auto where = h5::read_strings(f, "/assembled/where");
      const auto label = h5::read_strings(f, "/assembled/label");
      if (rpm.size() != ahz.size() || zeta.size() != ahz.size() || where.size() != ahz.size() ||
          label.size() != ahz.size())
        throw h5::Failure("the /assembled datasets differ in length");
      for (std::size_t i = 0; i < ahz.size(); ++i)
        d.assembled.push_back({rpm[i], ahz[i], zeta[i], where[i], label[i]});
    }
  } catch (const h5::Failure& e) {
    throw InputError(path + ": " + e.what());
  }
  return d;
}

std::string order_cuts_script(const SweepFigureData& d, const std::vector<int>& channels,
                              const std::vector<double>& orders, const fs::path& out) {
  std::vector<int> chans = channels;
  if (chans.size() > 4) chans.resize(4);
  const Axis a = figure_axis(d);
  std::ostringstream gp;
  gp << "# order cuts of " << d.scene_name << " (evas study sweep)\n"
     << gp_terminal(out, 1100, 380 * static_cast<int>((chans.size() + 1) / 2) + 60);
  int block = 0;
  std::vector<std::string> plots;  // per panel
  for (int c : chans) {
    std::ostringstream pl;
    for (std::size_t grp = 0; grp < a.order.size(); ++grp)
      for (double o : orders) {
        const std::size_t j = order_index(d, o);
        gp << "$C" << block << " << EOD\n";
        for (int k : a.groups.at(a.order[grp])) {
          const auto& amp = d.amplitude[static_cast<std::size_t>(k)];
          if (amp.empty() || j >= d.orders.size() || !std::isfinite(amp[c][j])) continue;
          gp << gp_num(a.x[static_cast<std::size_t>(k)], 10) << " "
             << gp_num(display_scale(d.units[c]).factor * amp[c][j], 10) << "\n";
        }
        gp << "EOD\n";
        pl << (pl.tellp() > 0 ? ", " : "plot ") << "$C" << block
           << " using 1:2 with linespoints pt 7 title "
           << gp_quote("order " + gp_num(o, 4) +
                       (a.order[grp].empty() ? "" : " (" + a.order[grp] + ")"));
        ++block;
      }
    plots.push_back(pl.str());
  }
  const int cols = chans.size() > 1 ? 2 : 1;
  gp << "set multiplot layout " << (chans.size() + 1) / 2 << "," << cols << " title "
     << gp_quote("order cuts: " + d.scene_name + " (amplitude of each order over the last " +
                 std::to_string(d.cycles) + " cycle(s))")
     << "\nset grid\nset key outside right top\nset xlabel " << gp_quote(a.label) << "\n";
  for (std::size_t i = 0; i < chans.size(); ++i) {
    const auto c = static_cast<std::size_t>(chans[i]);
    gp << "set title " << gp_quote(d.names[c]) << "\nset ylabel "
       << gp_quote("amplitude [" + display_scale(d.units[c]).unit + "]") << "\n"
       << plots[i] << "\n";
  }
  gp << "unset multiplot\n";
  return gp.str();
}

std::string waterfall_script(const SweepFigureData& d, int channel, const fs::path& out) {
  const auto c = static_cast<std::size_t>(channel);
  const Axis a = figure_axis(d);
  const auto& tasks = a.groups.at(a.order.front());
  std::ostringstream gp;
  gp << "# waterfall of " << d.scene_name << " (evas study sweep)\n"
     << gp_terminal(out, 1000, 700) << "$W << EOD\n";
  for (int k : tasks) {
    const auto& amp = d.amplitude[static_cast<std::size_t>(k)];
    if (amp.empty()) continue;
    for (std::size_t j = 0; j < d.orders.size(); ++j)
      if (std::isfinite(amp[c][j]))
        gp << gp_num(d.orders[j], 6) << " " << gp_num(a.x[static_cast<std::size_t>(k)], 10) << " "
           << gp_num(display_scale(d.units[c]).factor * amp[c][j], 10) << "\n";
    gp << "\n\n";  // one spectrum per block
  }
  gp << "EOD\n"
     << "set title "
     << gp_quote("waterfall: " + d.names[c] + ", " + d.scene_name +
                 (a.order.front().empty() ? "" : " (" + a.order.front() + ")"))
     << "\nset xlabel 'engine order'\nset ylabel " << gp_quote(a.label)
     << " rotate parallel\nset zlabel "
     << gp_quote("amplitude [" + display_scale(d.units[c]).unit + "]")
     << " rotate parallel\nset view 55, 35\nset grid\nset xyplane at 0\nset palette "
        "rgbformulae 33,13,10\nset colorbox vertical user origin 0.86, 0.2 size 0.025, 0.6\n"
        "set rmargin at screen 0.8\nset cblabel "
     << gp_quote("amplitude [" + display_scale(d.units[c]).unit + "]") << " offset 1,0"
     << "\nsplot $W using 1:2:3 with impulses lw 3 lc palette notitle, "
        "$W using 1:2:3 with lines lc rgb 'gray40' notitle\n";
  return gp.str();
}

std::string campbell_script(const SweepFigureData& d, const fs::path& out) {
  double top = 0.0;
  std::vector<double> speeds;
  for (const auto& t : d.tasks)
    if (std::isfinite(t.rpm) && t.case_index == 0) {
      top = std::max(top, t.rpm);
      speeds.push_back(t.rpm);
    }
  if (!(top > 0.0)) return "";
  const double xmax = 1.1 * top, ymax = d.max_order * xmax / 60.0;
  // the assembled modes drawn: lightly damped ones (a resonance a spectrum shows)
  constexpr double kZetaDrawn = 0.3;
  std::vector<const SweepFigureData::Mode*> drawn;
  int overdamped = 0;
  double ymin = 0.5 * xmax / 60.0;  // order 0.5 at the top speed
  for (const auto& m : d.assembled) {
    if (!(m.hz > 0.0) || m.hz > ymax) continue;
    if (m.damping_ratio > kZetaDrawn) {
      ++overdamped;
      continue;
    }
    drawn.push_back(&m);
    ymin = std::min(ymin, m.hz);
  }
  for (const auto& n : d.natural)
    if (n.hz > 0.0) ymin = std::min(ymin, n.hz);
  ymin = std::pow(10.0, std::floor(std::log10(std::max(ymin, 0.1) * 0.8)));
  const bool assembled = !d.assembled.empty();
  std::ostringstream gp;
  gp << "# Campbell diagram of " << d.scene_name << " (evas study sweep)\n"
     << gp_terminal(out, 1000, 700) << "set title "
     << gp_quote("Campbell diagram: " + d.scene_name +
                 (assembled ? " (modes of the assembled engine, linearized over each point's "
                              "steady cycle)"
                            : " (the bodies' own modes and the rigid engine on its mounts)"))
     << "\nset xlabel 'crank speed [rpm]'\nset ylabel 'frequency [Hz] (log scale)'\nset xrange [0:"
     << gp_num(xmax, 8) << "]\nset yrange [" << gp_num(ymin, 8) << ":" << gp_num(ymax, 8)
     << "]\nset logscale y\nset grid xtics ytics mytics\n"
     // the order lines are curves on the log axis: a few dozen samples draw them
     << "set samples 60\nset key outside bottom center horizontal\n";
  for (double o = 1.0; o <= d.max_order + 1e-9; o += 1.0) {
    if (o > 6.0 && std::fmod(o, 2.0) != 0.0) continue;  // the high orders crowd on a log axis
    const double y_end = o * xmax / 60.0;
    const double xl = y_end > ymax ? ymax * 60.0 / o : xmax;
    gp << "set label " << gp_quote(gp_num(o, 3)) << " at " << gp_num(xl, 8) << ","
       << gp_num(o * xl / 60.0, 8) << " offset -1.2,0.6 tc rgb 'gray30'\n";
  }
  for (double s : speeds)
    gp << "set arrow from " << gp_num(s, 8) << "," << gp_num(ymin, 8) << " to " << gp_num(s, 8)
       << "," << gp_num(ymax, 8) << " nohead lc rgb 'gray75' dt 3\n";
  // the assembled modes as data blocks, one per kind
  const std::vector<std::pair<std::string, std::string>> kinds = {
      {"mount", "mount (rigid engine on its mounts)"},
      {"driveline", "driveline (crank rotation, couplings)"},
      {"body", "body (elastic, crank in its bearings)"}};
  std::vector<std::pair<std::string, std::string>> blocks;  // (name, title)
  for (const auto& [where, title] : kinds) {
    std::ostringstream b;
    int n = 0;
    for (const auto* m : drawn)
      if (m->where == where) {
        b << gp_num(m->rpm, 8) << " " << gp_num(m->hz, 8) << "\n";
        ++n;
      }
    if (n == 0) continue;
    const std::string name = "$M" + std::to_string(blocks.size());
    gp << name << " << EOD\n" << b.str() << "EOD\n";
    blocks.push_back({name, title});
  }
  gp << "plot ";
  bool first = true;
  auto sep = [&] {
    if (!first) gp << ", \\\n     ";
    first = false;
  };
  for (double o = 0.5; o <= d.max_order + 1e-9; o += 0.5) {
    const bool whole = std::abs(o - std::round(o)) < 1e-9;
    sep();
    gp << "(x > 0 ? " << gp_num(o, 3) << "*x/60 : 1/0) with lines lc rgb "
       << (whole ? "'gray30'" : "'gray70'") << (whole ? " dt 1" : " dt 2") << " "
       << (o == 0.5 ? "title 'engine orders'" : "notitle");
  }
  if (assembled) {
    const char* colour[] = {"'#1f77b4'", "'#d62728'", "'#2ca02c'", "'#9467bd'"};
    const char* point[] = {"7", "5", "9", "11"};
    for (std::size_t i = 0; i < blocks.size(); ++i) {
      sep();
      gp << blocks[i].first << " using 1:2 with points pt " << point[i % 4] << " ps 1.3 lc rgb "
         << colour[i % 4] << " title " << gp_quote(blocks[i].second);
    }
    if (overdamped > 0) {
      sep();
      gp << "NaN with points lc rgb 'white' title "
         << gp_quote(std::to_string(overdamped) + " modes with damping ratio > " +
                     gp_num(kZetaDrawn, 2) + " not drawn (campbell.csv has them)");
    }
  } else {
    std::map<std::string, int> shown;  // one legend entry per body and kind
    int colour = 1;
    std::map<std::string, int> colours;
    for (const auto& n : d.natural) {
      if (!(n.hz > 0.0) || n.hz > ymax) continue;
      const std::string who =
          n.kind == "mount" ? "mount modes (rigid engine)" : n.body + " " + n.kind + " modes";
      if (!colours.count(who)) colours[who] = colour++;
      sep();
      gp << gp_num(n.hz, 8) << " with lines lw 2 lc " << colours[who] << " "
         << (shown[who]++ ? std::string("notitle") : "title " + gp_quote(who));
    }
  }
  gp << "\n";
  return gp.str();
}

}  // namespace evas
