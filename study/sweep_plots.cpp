// The figures of `evas study sweep` (sweep.h): order cuts, waterfall and
// Campbell diagram, drawn by the code `evas plot` uses on sweep.h5
// (plot/sweep_figures.h), from the data the sweep writes there.
#include <cmath>

#include "plot/sweep_figures.h"
#include "study/report.h"
#include "study/sweep_detail.h"

namespace evas::study::detail {

namespace {

SweepFigureData figure_data(const SweepData& d, const SweepOptions& so) {
  SweepFigureData f;
  f.scene_name = d.res.info.scene_name;
  f.keys = d.res.keys;
  for (const SweepTask& t : d.res.tasks)
    f.tasks.push_back({t.point, t.case_index, t.values, t.rpm});
  f.names = d.names;
  f.units = d.units;
  f.orders = d.orders;
  f.amplitude = d.amplitude;
  f.natural = d.natural;
  for (const auto& a : d.assembled)
    f.assembled.push_back({a.rpm, a.mode.hz, a.mode.damping_ratio, a.mode.where, a.mode.label});
  f.cycles = so.cycles;
  f.max_order = so.max_order;
  return f;
}

}  // namespace

void plot_sweep(const Options& opt, SweepData& d, const SweepOptions& so, GnuplotProcess* started) {
  auto& files = d.res.info.files;
  const fs::path dir = d.res.info.out_dir;
  files.insert(files.begin(), {(dir / "sweep.csv").string(), (dir / "sweep.md").string(),
                               (dir / "sweep.h5").string()});
  const SweepFigureData f = figure_data(d, so);
  if (!has_spectra(f)) {
    say(opt, "evas study sweep: no order spectra (" +
                 std::string(d.crank_grid ? "no completed run holds the cycles asked for"
                                          : "the scene's output is not on the crank-angle grid") +
                 "): no order cuts, waterfall or Campbell diagram");
    return;
  }
  std::vector<Figure> figures = {
      {dir / "order_cuts.gp",
       order_cuts_script(f, d.figure_channels, so.orders, dir / "order_cuts.png"),
       dir / "order_cuts.png"},
      {dir / "waterfall.gp", waterfall_script(f, d.figure_channels.front(), dir / "waterfall.png"),
       dir / "waterfall.png"}};
  if (std::string c = campbell_script(f, dir / "campbell.png"); !c.empty())
    figures.push_back({dir / "campbell.gp", std::move(c), dir / "campbell.png"});
  plot_all(opt, figures, d.res.info, started);
}

}  // namespace evas::study::detail
