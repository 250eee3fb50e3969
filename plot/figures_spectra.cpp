// `evas plot` kinds over frequency and speed: order tracking of a run-up,
// the spectrum over time and the ERP spectrum (figures.h).
#include <cmath>
#include <iostream>

#include "plot/figure_record.h"
#include "post/erp_spectrum.h"
#include "post/order_spectrum.h"
#include "post/order_tracking.h"
#include "post/radiation.h"
#include "post/time_spectrum.h"

namespace evas::figure_detail {

namespace {

// A spectrum over time of a run-up: refused with what to draw instead (its
// crank-angle grid is not uniform in time; the orders are tracked per cycle).
void refuse_runup(const Record& rec, const std::string& kind) {
  if (!rec.has_crank()) return;
  const ResultsData& d = rec.data();
  std::vector<double> th;
  for (Eigen::Index r = 0; r < d.values.rows(); ++r) th.push_back(rec.crank(r));
  const std::string runup = runup_text(d.time, th);
  if (runup.empty()) return;
  throw InputError(rec.name() + ": a run-up (" + runup + "): plot " + kind +
                   " takes a spectrum over time, which needs a constant speed (a run-up's "
                   "crank-angle grid is not uniform in time); evas plot order-track draws each "
                   "order against speed (--channel, --order), evas report draws the run-up's page");
}

}  // namespace

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
  refuse_runup(rec, "spectrum");
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
  refuse_runup(rec, "erp");
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

}  // namespace evas::figure_detail
