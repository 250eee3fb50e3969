// The figures of `evas study sweep` (sweep.h): order cuts, waterfall and
// Campbell diagram, drawn by gnuplot from the data written to sweep.h5.
#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "study/report.h"
#include "study/sweep_detail.h"

namespace evas::study::detail {

namespace {

// The figures' x axis: the mean speed when the speed changes over the grid,
// else the first key's number. Curves: the points of the first case grouped by
// the values of the other keys.
struct Axis {
  std::string label;
  std::vector<double> x;                           // per task
  std::map<std::string, std::vector<int>> groups;  // group label -> tasks, grid order
  std::vector<std::string> order;                  // group labels in order of first appearance
};

Axis figure_axis(const SweepData& d) {
  const SweepResult& res = d.res;
  Axis a;
  double lo = INFINITY, hi = -INFINITY;
  for (const auto& t : res.tasks)
    if (std::isfinite(t.rpm)) {
      lo = std::min(lo, t.rpm);
      hi = std::max(hi, t.rpm);
    }
  const bool by_speed = std::isfinite(lo) && hi - lo > 1e-6 * std::max(1.0, std::abs(hi));
  a.label = by_speed ? "mean crank speed [rpm]" : res.keys.front();
  for (std::size_t k = 0; k < res.tasks.size(); ++k) {
    const SweepTask& t = res.tasks[k];
    double x = by_speed ? t.rpm : kNaN;
    if (!by_speed) {
      char* end = nullptr;
      x = std::strtod(t.values.front().c_str(), &end);
      if (t.values.front().empty() || *end) x = t.point;
    }
    a.x.push_back(x);
    if (t.case_index != 0) continue;
    std::string g;  // the first key is the axis (or the speed it sets)
    for (std::size_t j = 1; j < res.keys.size(); ++j)
      g += (g.empty() ? "" : ", ") + res.keys[j] + "=" + t.values[j];
    if (!a.groups.count(g)) a.order.push_back(g);
    a.groups[g].push_back(static_cast<int>(k));
  }
  return a;
}

std::size_t order_index(const SweepData& d, double o) {
  for (std::size_t j = 0; j < d.orders.size(); ++j)
    if (std::abs(d.orders[j] - o) < 1e-9) return j;
  return d.orders.size();
}

Figure plot_order_cuts(SweepData& d, const SweepOptions& so, const Axis& a) {
  std::vector<int> chans = d.figure_channels;
  if (chans.size() > 4) chans.resize(4);
  const fs::path png = fs::path(d.res.info.out_dir) / "order_cuts.png";
  std::ostringstream gp;
  gp << "# order cuts of " << d.res.info.scene_name << " (evas study sweep)\n"
     << gp_terminal(png, 1100, 380 * static_cast<int>((chans.size() + 1) / 2) + 60);
  int block = 0;
  std::vector<std::string> plots;  // per panel
  for (int c : chans) {
    std::ostringstream pl;
    for (std::size_t g = 0; g < a.order.size(); ++g)
      for (double o : so.orders) {
        const std::size_t j = order_index(d, o);
        gp << "$C" << block << " << EOD\n";
        for (int k : a.groups.at(a.order[g])) {
          const auto& amp = d.amplitude[static_cast<std::size_t>(k)];
          if (amp.empty() || j >= d.orders.size() || !std::isfinite(amp[c][j])) continue;
          gp << gnum(a.x[static_cast<std::size_t>(k)], 10) << " " << gnum(amp[c][j], 10) << "\n";
        }
        gp << "EOD\n";
        pl << (pl.tellp() > 0 ? ", " : "plot ") << "$C" << block
           << " using 1:2 with linespoints pt 7 title "
           << gp_quote("order " + gnum(o, 4) + (a.order[g].empty() ? "" : " (" + a.order[g] + ")"));
        ++block;
      }
    plots.push_back(pl.str());
  }
  const int cols = chans.size() > 1 ? 2 : 1;
  gp << "set multiplot layout " << (chans.size() + 1) / 2 << "," << cols << " title "
     << gp_quote("order cuts: " + d.res.info.scene_name +
                 " (amplitude of each order over the last " + std::to_string(so.cycles) +
                 " cycle(s))")
     << "\nset grid\nset key top left\nset xlabel " << gp_quote(a.label) << "\n";
  for (std::size_t i = 0; i < chans.size(); ++i) {
    const int c = chans[i];
    gp << "set title " << gp_quote(d.names[static_cast<std::size_t>(c)]) << "\nset ylabel "
       << gp_quote("amplitude [" + d.units[static_cast<std::size_t>(c)] + "]") << "\n"
       << plots[i] << "\n";
  }
  gp << "unset multiplot\n";
  return {fs::path(d.res.info.out_dir) / "order_cuts.gp", gp.str(), png};
}

Figure plot_waterfall(SweepData& d, const Axis& a) {
  const int c = d.figure_channels.front();
  const auto& tasks = a.groups.at(a.order.front());
  const fs::path png = fs::path(d.res.info.out_dir) / "waterfall.png";
  std::ostringstream gp;
  gp << "# waterfall of " << d.res.info.scene_name << " (evas study sweep)\n"
     << gp_terminal(png, 1000, 700) << "$W << EOD\n";
  for (int k : tasks) {
    const auto& amp = d.amplitude[static_cast<std::size_t>(k)];
    if (amp.empty()) continue;
    for (std::size_t j = 0; j < d.orders.size(); ++j)
      if (std::isfinite(amp[c][j]))
        gp << gnum(d.orders[j], 6) << " " << gnum(a.x[static_cast<std::size_t>(k)], 10) << " "
           << gnum(amp[c][j], 10) << "\n";
    gp << "\n\n";  // one spectrum per block
  }
  gp << "EOD\n"
     << "set title "
     << gp_quote("waterfall: " + d.names[static_cast<std::size_t>(c)] + ", " +
                 d.res.info.scene_name +
                 (a.order.front().empty() ? "" : " (" + a.order.front() + ")"))
     << "\nset xlabel 'engine order'\nset ylabel " << gp_quote(a.label)
     << " rotate parallel\nset zlabel "
     << gp_quote("amplitude [" + d.units[static_cast<std::size_t>(c)] + "]")
     << " rotate parallel\nset view 55, 35\nset grid\nset xyplane at 0\nset palette "
        "rgbformulae 33,13,10\nset cblabel "
     << gp_quote("amplitude [" + d.units[static_cast<std::size_t>(c)] + "]")
     << "\nsplot $W using 1:2:3 with impulses lw 3 lc palette notitle, "
        "$W using 1:2:3 with lines lc rgb 'gray40' notitle\n";
  return {fs::path(d.res.info.out_dir) / "waterfall.gp", gp.str(), png};
}

// None (empty script) when no task has a speed.
Figure plot_campbell(SweepData& d, const SweepOptions& so) {
  double top = 0.0;
  std::vector<double> speeds;
  for (const auto& t : d.res.tasks)
    if (std::isfinite(t.rpm) && t.case_index == 0) {
      top = std::max(top, t.rpm);
      speeds.push_back(t.rpm);
    }
  if (!(top > 0.0)) return {};
  const double xmax = 1.1 * top, ymax = so.max_order * xmax / 60.0;
  const fs::path png = fs::path(d.res.info.out_dir) / "campbell.png";
  std::ostringstream gp;
  gp << "# Campbell diagram of " << d.res.info.scene_name << " (evas study sweep)\n"
     << gp_terminal(png, 1000, 700) << "set title "
     << gp_quote("Campbell diagram: " + d.res.info.scene_name +
                 " (natural frequencies against engine orders)")
     << "\nset xlabel 'crank speed [rpm]'\nset ylabel 'frequency [Hz]'\nset xrange [0:"
     << gnum(xmax, 8) << "]\nset yrange [0:" << gnum(ymax, 8)
     << "]\nset grid\n"
     // every curve is a straight line: two samples draw it exactly (gnuplot's
     // default of 100 per curve is most of the figure's drawing time)
     << "set samples 2\nset key outside right top\n";
  for (double o = 0.5; o <= so.max_order + 1e-9; o += 0.5) {
    const double y_end = o * xmax / 60.0;
    const double xl = y_end > ymax ? ymax * 60.0 / o : xmax;
    if (std::abs(o - std::round(o)) < 1e-9)
      gp << "set label " << gp_quote(gnum(o, 3)) << " at " << gnum(xl, 8) << ","
         << gnum(o * xl / 60.0, 8) << " offset -1.2,0.6 tc rgb 'gray30'\n";
  }
  for (double s : speeds)
    gp << "set arrow from " << gnum(s, 8) << ",0 to " << gnum(s, 8) << "," << gnum(ymax, 8)
       << " nohead lc rgb 'gray75' dt 3\n";
  gp << "plot ";
  bool first = true;
  auto sep = [&] {
    if (!first) gp << ", \\\n     ";
    first = false;
  };
  for (double o = 0.5; o <= so.max_order + 1e-9; o += 0.5) {
    const bool whole = std::abs(o - std::round(o)) < 1e-9;
    sep();
    gp << gnum(o, 3) << "*x/60 with lines lc rgb " << (whole ? "'gray30'" : "'gray70'")
       << (whole ? " dt 1" : " dt 2") << " " << (o == 0.5 ? "title 'engine orders'" : "notitle");
  }
  std::map<std::string, int> shown;  // one legend entry per body and kind
  int colour = 1;
  std::map<std::string, int> colours;
  for (const auto& n : d.natural) {
    if (!(n.hz > 0.0) || n.hz > ymax) continue;
    const std::string who =
        n.kind == "mount" ? "mount modes (rigid engine)" : n.body + " " + n.kind + " modes";
    if (!colours.count(who)) colours[who] = colour++;
    sep();
    gp << gnum(n.hz, 8) << " with lines lw 2 lc " << colours[who] << " "
       << (shown[who]++ ? std::string("notitle") : "title " + gp_quote(who));
  }
  gp << "\n";
  return {fs::path(d.res.info.out_dir) / "campbell.gp", gp.str(), png};
}

}  // namespace

void plot_sweep(const Options& opt, SweepData& d, const SweepOptions& so) {
  auto& files = d.res.info.files;
  const fs::path dir = d.res.info.out_dir;
  files.insert(files.begin(), {(dir / "sweep.csv").string(), (dir / "sweep.md").string(),
                               (dir / "sweep.h5").string()});
  bool any = false;
  for (const auto& a : d.amplitude) any = any || !a.empty();
  if (!any) {
    say(opt, "evas study sweep: no order spectra (" +
                 std::string(d.crank_grid ? "no completed run holds the cycles asked for"
                                          : "the scene's output is not on the crank-angle grid") +
                 "): no order cuts, waterfall or Campbell diagram");
    return;
  }
  const Axis a = figure_axis(d);
  std::vector<Figure> figures = {plot_order_cuts(d, so, a), plot_waterfall(d, a)};
  if (Figure c = plot_campbell(d, so); !c.text.empty()) figures.push_back(std::move(c));
  plot_all(opt, figures, d.res.info);
}

}  // namespace evas::study::detail
