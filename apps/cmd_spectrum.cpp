// evas spectrum RESULTS.h5 --channel NAME: order spectrum of a channel of a run
// on the crank-angle grid (post/order_spectrum.h), or with --time its spectrum
// over time: amplitude and PSD with a named window, optionally Welch-averaged
// segments and third-octave bands (post/time_spectrum.h).
#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>

#include "apps/commands.h"
#include "io/results.h"
#include "model/nearest_name.h"
#include "model/types.h"
#include "post/erp_spectrum.h"
#include "post/order_spectrum.h"
#include "post/order_tracking.h"
#include "post/radiation.h"
#include "post/time_spectrum.h"

namespace evas::cli {

namespace {

std::ofstream open_csv(const std::string& path) {
  std::ofstream f(path);
  if (!f) throw InputError(path + ": cannot write");
  f << std::setprecision(12);
  return f;
}

void order_mode(const ResultsData& d, const std::string& path, int ic, int cycles, double cycle,
                double max_order, const std::string& csv) {
  int ia = -1;
  for (std::size_t i = 0; i < d.names.size(); ++i)
    if (d.names[i] == "crank_angle") ia = static_cast<int>(i);
  if (ia < 0)
    throw InputError(path +
                     ": no crank_angle channel (run the scene with output grid crank-angle, or "
                     "give --time for a spectrum over time)");
  std::vector<double> th(d.values.rows()), y(d.values.rows());
  for (Eigen::Index r = 0; r < d.values.rows(); ++r) {
    th[r] = d.values(r, ia);
    y[r] = d.values(r, ic);
  }
  const OrderSpectrum s = order_spectrum(th, y, cycles, cycle, max_order);
  std::cout << "order spectrum of " << d.names[ic] << " [" << d.units[ic] << "] over "
            << cycles_used(s, cycle) << "\n  order     amplitude     phase [rad]\n";
  for (std::size_t k = 0; k < s.order.size(); ++k)
    std::cout << std::setw(7) << s.order[k] << std::setw(14) << std::setprecision(6)
              << s.amplitude[k] << std::setw(14) << s.phase[k] << "\n";
  if (!csv.empty()) {
    std::ofstream f = open_csv(csv);
    f << "order,amplitude[" << d.units[ic] << "],phase[rad]\n";
    for (std::size_t k = 0; k < s.order.size(); ++k)
      f << s.order[k] << "," << s.amplitude[k] << "," << s.phase[k] << "\n";
  }
}

// The options with --segment S [s] turned into samples.
TimeSpectrumOptions with_segment(const ResultsData& d, const TimeSpectrumOptions& o,
                                 double segment_s) {
  TimeSpectrumOptions opt = o;
  if (segment_s > 0.0) {
    if (d.time.size() < 2) throw InputError("--segment: the record has fewer than 2 samples");
    const double dt = (d.time.back() - d.time.front()) / static_cast<double>(d.time.size() - 1);
    opt.segment = std::lround(segment_s / dt);
    if (opt.segment < 4)
      throw InputError("--segment " + std::to_string(segment_s) +
                       " s is shorter than 4 samples (dt = " + std::to_string(dt) + " s)");
  }
  return opt;
}

std::vector<double> column(const ResultsData& d, int ic) {
  std::vector<double> y(static_cast<std::size_t>(d.values.rows()));
  for (Eigen::Index r = 0; r < d.values.rows(); ++r)
    y[static_cast<std::size_t>(r)] = d.values(r, ic);
  return y;
}

// A level [dB re 1 pW], or "" for no power.
std::string level_text(double p) {
  if (!(p > 0.0)) return "";
  std::ostringstream os;
  os << std::fixed << std::setprecision(1) << erp_level(p);
  return os.str();
}

// "" or ",X" for a level of power p (dB), for the CSV.
std::string level_field(double p) { return "," + level_text(p); }

// p times the A weighting at f.
double a_weighted(double p, double f) { return p * std::pow(10.0, a_weighting_db(f) / 10.0); }

// --erp NAME: the ERP spectrum of surface output NAME from its components NAME.c<k>,
// and of its elastic part from NAME.e<k> where the file has them.
void erp_mode(const ResultsData& d, const std::string& path, const std::string& name,
              const TimeSpectrumOptions& o, double segment_s, double max_f,
              const std::string& bands, const std::string& csv, const RadiationModel* rad) {
  const std::vector<std::vector<double>> comps = erp_components(d.names, d.values, name);
  if (comps.empty()) {
    std::string known;
    for (const std::string& n : d.names)
      if (n.size() > 4 && n.compare(n.size() - 4, 4, ".erp") == 0)
        known += (known.empty() ? "" : ", ") + n.substr(0, n.size() - 4);
    throw InputError(path + ": no surface output '" + name + "' (no channels " + name +
                     ".c0, ...; surface outputs in the file: " +
                     (known.empty() ? "none: add {surface: SET, body: B, name: N} to the "
                                      "scene's output channels"
                                    : known) +
                     ")");
  }
  const std::vector<std::vector<double>> ecomps = erp_components(d.names, d.values, name, "e");
  const bool el = !ecomps.empty();
  if (rad && !el)
    throw InputError(
        path +
        ": --radiation weights the elastic part of the ERP, and the file has "
        "no elastic components " +
        name + ".e0, ... (a file from before the elastic part was written: run the scene again)");
  const TimeSpectrumOptions opt = with_segment(d, o, segment_s);
  std::vector<ErpBand> bl, ebl;
  const ErpSpectrum s = erp_spectrum(d.time, comps, opt, bands.empty() ? nullptr : &bl);
  ErpSpectrum e;
  if (el) e = erp_spectrum(d.time, ecomps, opt, bands.empty() ? nullptr : &ebl);
  std::cout << "equivalent radiated power of " << name << ", t = " << s.t0 << " .. " << s.t1
            << " s, " << o.window << " window, " << s.segments << " segment(s) of " << s.samples
            << " samples, df = " << s.df << " Hz; mean ERP " << s.mean << " W ("
            << level_text(s.mean) << " dB re 1 pW)\n";
  // the totals of the weighted elastic part, over the bins or bands listed
  double e_a = 0.0, r_w = 0.0, r_a = 0.0;
  if (el) {
    std::cout << "  elastic part (the body's deformation; the rigid-body motion left out): mean "
              << e.mean << " W (" << level_text(e.mean) << " dB re 1 pW)\n";
    if (rad)
      std::cout << "  radiation efficiency sigma(f) of a " << rad->describe()
                << " applied to the elastic part: radiated = sigma * ERP_elastic\n";
  }
  std::ofstream f;
  if (!csv.empty()) f = open_csv(csv);
  const std::string el_head = el ? ",erp_elastic[W],level_elastic[dB re 1 pW],"
                                   "level_elastic_A[dB(A) re 1 pW]"
                                 : "";
  const std::string rad_head =
      rad ? ",sigma,radiated[W],level_radiated[dB re 1 pW],level_radiated_A[dB(A) re 1 pW]" : "";
  auto el_cols = [&](double pe, double fc, bool print) {
    if (!el) return;
    const double pa = a_weighted(pe, fc);
    e_a += pa;
    if (print)
      std::cout << std::setw(13) << std::setprecision(6) << pe << std::setw(10) << level_text(pe)
                << std::setw(10) << level_text(pa);
    if (f) f << "," << pe << level_field(pe) << level_field(pa);
    if (!rad) return;
    const double sg = rad->sigma(fc), pr = sg * pe, pra = a_weighted(pr, fc);
    r_w += pr;
    r_a += pra;
    if (print)
      std::cout << std::setw(10) << std::setprecision(4) << sg << std::setw(13)
                << std::setprecision(6) << pr << std::setw(10) << level_text(pr) << std::setw(10)
                << level_text(pra);
    if (f) f << "," << sg << "," << pr << level_field(pr) << level_field(pra);
  };
  const std::string el_print = el ? "   elastic [W]  level     dB(A)" : "";
  const std::string rad_print = rad ? "     sigma  radiated [W]  level     dB(A)" : "";
  if (!bands.empty()) {
    std::cout << "  third-octave band [Hz]            ERP [W]   level [dB]   bins" << el_print
              << rad_print << "\n";
    if (f)
      f << "centre[Hz],lower[Hz],upper[Hz],erp[W],level[dB re 1 pW],bins" << el_head << rad_head
        << "\n";
    for (std::size_t j = 0; j < bl.size(); ++j) {
      const ErpBand& b = bl[j];
      std::cout << std::setw(10) << std::setprecision(5) << b.centre << "  (" << std::setw(8)
                << b.lower << " .. " << std::setw(8) << b.upper << ")  " << std::setw(13)
                << std::setprecision(6) << b.power << std::setw(12) << level_text(b.power)
                << std::setw(7) << b.bins;
      if (f)
        f << b.centre << "," << b.lower << "," << b.upper << "," << b.power << ","
          << level_text(b.power) << "," << b.bins;
      el_cols(j < ebl.size() ? ebl[j].power : 0.0, b.centre, true);
      std::cout << "\n";
      if (f) f << "\n";
    }
  } else {
    std::cout << "  frequency [Hz]   ERP [W]   level [dB]   density [W/Hz]" << el_print << rad_print
              << "\n";
    if (f)
      f << "frequency[Hz],erp[W],level[dB re 1 pW],density[W/Hz]" << el_head << rad_head << "\n";
    for (std::size_t k = 0; k < s.frequency.size(); ++k) {
      if (max_f > 0.0 && s.frequency[k] > max_f) break;
      std::cout << std::setw(16) << std::setprecision(6) << s.frequency[k] << std::setw(12)
                << s.power[k] << std::setw(10) << level_text(s.power[k]) << std::setw(16)
                << s.density[k];
      if (f)
        f << s.frequency[k] << "," << s.power[k] << "," << level_text(s.power[k]) << ","
          << s.density[k];
      el_cols(k < e.power.size() ? e.power[k] : 0.0, s.frequency[k], true);
      std::cout << "\n";
      if (f) f << "\n";
    }
  }
  if (el) {
    std::cout << "  elastic part, sum of the " << (bands.empty() ? "bins" : "bands")
              << " listed, A-weighted: " << e_a << " W (" << level_text(e_a) << " dB(A) re 1 pW)\n";
    if (rad)
      std::cout << "  radiated (sigma * elastic), sum of the " << (bands.empty() ? "bins" : "bands")
                << " listed: " << r_w << " W (" << level_text(r_w) << " dB re 1 pW), A-weighted "
                << r_a << " W (" << level_text(r_a) << " dB(A) re 1 pW)\n";
  }
}

void time_mode(const ResultsData& d, int ic, const TimeSpectrumOptions& o, double segment_s,
               double max_f, const std::string& bands, const std::string& csv) {
  const std::vector<double> y = column(d, ic);
  const TimeSpectrum s = time_spectrum(d.time, y, with_segment(d, o, segment_s));
  const std::string& unit = d.units[ic];
  const std::string u = unit.empty() ? "1" : unit;
  std::cout << "spectrum over time of " << d.names[ic] << " [" << u << "], t = " << s.t0 << " .. "
            << s.t1 << " s, " << o.window << " window, " << s.segments << " segment(s) of "
            << s.samples << " samples, df = " << s.df << " Hz, noise bandwidth " << s.enbw
            << " Hz\n";
  if (!bands.empty()) {
    std::cout << "  third-octave band [Hz]            rms [" << u << "]   bins\n";
    for (const Band& b : third_octave_bands(s)) {
      std::cout << std::setw(10) << std::setprecision(5) << b.centre << "  (" << std::setw(8)
                << b.lower << " .. " << std::setw(8) << b.upper << ")  " << std::setw(13)
                << std::setprecision(6) << b.rms << std::setw(7) << b.bins;
      std::cout << (b.bins == 0 ? "   no bin: longer --segment or window\n" : "\n");
    }
  } else {
    std::cout << "  frequency [Hz]   amplitude [" << u << "]   PSD [" << u << "^2/Hz]\n";
    for (std::size_t k = 0; k < s.frequency.size(); ++k) {
      if (max_f > 0.0 && s.frequency[k] > max_f) break;
      std::cout << std::setw(16) << std::setprecision(6) << s.frequency[k] << std::setw(16)
                << s.amplitude[k] << std::setw(18) << s.psd[k] << "\n";
    }
  }
  if (!csv.empty()) {
    std::ofstream f = open_csv(csv);
    if (!bands.empty()) {
      f << "centre[Hz],lower[Hz],upper[Hz],rms[" << u << "],bins\n";
      for (const Band& b : third_octave_bands(s))
        f << b.centre << "," << b.lower << "," << b.upper << "," << b.rms << "," << b.bins << "\n";
    } else {
      f << "frequency[Hz],amplitude[" << u << "],psd[" << u << "^2/Hz]\n";
      for (std::size_t k = 0; k < s.frequency.size(); ++k) {
        if (max_f > 0.0 && s.frequency[k] > max_f) break;
        f << s.frequency[k] << "," << s.amplitude[k] << "," << s.psd[k] << "\n";
      }
    }
  }
}

}  // namespace

int cmd_spectrum(const std::vector<std::string>& args) {
  int cycles = 1;
  double cycle = 720.0, max_order = 12.0, segment = 0.0, max_f = 0.0;
  TimeSpectrumOptions t;
  std::string bands;
  po::options_description opts(
      "usage: evas spectrum RESULTS.h5 --channel NAME [--cycles N] [--csv FILE]\n"
      "       evas spectrum RESULTS.h5 --channel NAME --time [--window W] [--from T0]\n"
      "                     [--to T1] [--segment S] [--overlap F] [--bands third-octave]\n"
      "       evas spectrum RESULTS.h5 --erp NAME [the --time options]\n\n"
      "Order spectrum of one output channel over whole engine cycles taken from the end\n"
      "of the record: by default the last one (as evas report, evas plot order and a\n"
      "sweep's spectra take it), --cycles N the last N, --cycles 0 every whole cycle (a\n"
      "run from rest: its start-up included). It prints which cycles it used. A\n"
      "record of one steady cycle: evas periodic. The run must use the crank-angle output grid\n"
      "(its results carry the channel crank_angle). Orders are harmonics of the crank\n"
      "rotation in steps of 360/cycle (0.5 for a four-stroke cycle).\n\n"
      "With --time: the spectrum over time of the samples in [--from, --to] (a uniform\n"
      "time grid), single-sided, in the channel's unit: the peak amplitude (a sinusoid of\n"
      "amplitude a at a bin frequency reads a under every window) and the power spectral\n"
      "density [unit^2/Hz]; each segment's mean is removed before the window. --segment S\n"
      "averages overlapping segments of S seconds (Welch); --bands third-octave sums the\n"
      "PSD into third-octave bands (IEC 61260-1 base-10 mid-band frequencies) and prints\n"
      "each band's RMS value.\n\n"
      "With --erp NAME (a spectrum over time): the equivalent radiated power of the\n"
      "surface output NAME ({surface: SET, ...}), from its components NAME.c<k>: per bin\n"
      "the power [W] of a harmonic there and the density [W/Hz], or per third-octave\n"
      "band the power [W]; levels in dB re 1 pW. Beside it the elastic part (NAME.e<k>:\n"
      "the body's deformation, its rigid-body motion, e.g. rocking on the mounts, left\n"
      "out) unweighted and A-weighted (IEC 61672-1), and with --radiation piston:R the\n"
      "radiation efficiency sigma(f) of a baffled piston of radius R [m] and the\n"
      "radiated power sigma * ERP_elastic.\n\n"
      "options");
  opts.add_options()("help,h", "show this help")("channel", po::value<std::string>(),
                                                 "channel name, e.g. main1.fy")(
      "cycles", po::value<int>(&cycles),
      "the last N whole cycles analysed (default 1; 0: every whole cycle of the record)")(
      "cycle", po::value<double>(&cycle)->default_value(720.0), "cycle length [deg]")(
      "max-order", po::value<double>(&max_order)->default_value(12.0), "highest order listed")(
      "time", "spectrum over time instead of over engine orders")(
      "erp", po::value<std::string>(),
      "equivalent radiated power of a surface output, over time (implies --time)")(
      "window", po::value<std::string>(&t.window)->default_value("hann"),
      "--time: rectangular, hann or flattop (flattop: amplitudes between bins)")(
      "from", po::value<double>(&t.t0), "--time: first time used [s] (default: the start)")(
      "to", po::value<double>(&t.t1), "--time: last time used [s] (default: the end)")(
      "segment", po::value<double>(&segment),
      "--time: segment length [s] for averaging (default: the whole window, one segment)")(
      "overlap", po::value<double>(&t.overlap)->default_value(0.5),
      "--time: overlap of the segments, in [0, 1)")("max-frequency", po::value<double>(&max_f),
                                                    "--time: highest frequency listed [Hz]")(
      "bands", po::value<std::string>(&bands), "--time: third-octave (band RMS values)")(
      "radiation", po::value<std::string>(),
      "--erp: radiation efficiency applied to the elastic ERP: piston:RADIUS (baffled "
      "circular piston, RADIUS in m; sqrt(area / pi) of the surface)")(
      "csv", po::value<std::string>(),
      "write the table to this file (order,amplitude,phase or frequency,amplitude,psd "
      "or the bands)");
  po::variables_map vm;
  if (parse_args(args, opts, {"results"}, vm)) return 0;
  if (!vm.count("results") || (vm.count("channel") + vm.count("erp")) != 1) {
    std::cerr << "evas spectrum: need RESULTS.h5 and either --channel NAME or --erp NAME\n"
              << opts << "\n";
    return 1;
  }
  const bool over_time = vm.count("time") > 0 || vm.count("erp") > 0;
  for (const char* k : {"from", "to", "segment", "max-frequency", "bands"})
    if (vm.count(k) && !over_time)
      throw InputError(std::string("--") + k + " applies to a spectrum over time: add --time");
  for (const char* k : {"window", "overlap"})
    if (!vm[k].defaulted() && !over_time)
      throw InputError(std::string("--") + k + " applies to a spectrum over time: add --time");
  if (over_time && vm.count("cycles"))
    throw InputError("--cycles applies to the order spectrum: leave out --time");
  if (vm.count("cycles") && cycles < 0)
    throw InputError("--cycles " + std::to_string(cycles) +
                     ": give a number of cycles >= 1 (0 for every whole cycle)");
  if (!(cycle > 0.0 && cycle <= 1e6))
    throw InputError("--cycle must be > 0 and <= 1e6 deg (720 for a four-stroke engine)");
  if (!(max_order >= 0.0 && max_order <= 1e6))
    throw InputError("--max-order must be >= 0 and <= 1e6");
  if (vm.count("segment") && !(segment > 0.0 && std::isfinite(segment)))
    throw InputError("--segment must be a positive number of seconds");
  if (vm.count("max-frequency") && !(max_f > 0.0))
    throw InputError("--max-frequency must be > 0 Hz");
  {
    const auto& w = spectrum_windows();
    if (std::find(w.begin(), w.end(), t.window) == w.end())
      throw InputError("--window '" + t.window +
                       "': the windows known are rectangular, hann, flattop");
  }
  if (vm.count("radiation") && !vm.count("erp"))
    throw InputError("--radiation applies to --erp NAME (the radiated power of a surface)");
  std::optional<RadiationModel> rad;
  if (vm.count("radiation"))
    rad = parse_radiation_model(vm["radiation"].as<std::string>(), "--radiation");
  if (vm.count("bands") && bands != "third-octave")
    throw InputError("--bands '" + bands + "': the bands known are third-octave");
  const std::string path = vm["results"].as<std::string>();
  // a spectrum over time of a run-up: refused, naming what to use instead
  auto refuse_runup = [&](const ResultsData& d) {
    const auto it = std::find(d.names.begin(), d.names.end(), "crank_angle");
    if (it == d.names.end()) return;
    const std::vector<double> th = column(d, static_cast<int>(it - d.names.begin()));
    const std::string runup = runup_text(d.time, th);
    if (!runup.empty())
      throw InputError(path + ": a run-up (" + runup +
                       "): a spectrum over time needs a constant speed (a run-up's crank-angle "
                       "grid is not uniform in time); evas plot order-track draws each order "
                       "against speed, evas spectrum --channel NAME (no --time) one cycle's "
                       "orders");
  };
  if (vm.count("erp")) {
    const ResultsData d = read_results(path);
    refuse_runup(d);
    erp_mode(d, path, vm["erp"].as<std::string>(), t, segment, max_f, bands,
             vm.count("csv") ? vm["csv"].as<std::string>() : "", rad ? &*rad : nullptr);
    return 0;
  }
  const std::string name = vm["channel"].as<std::string>();
  const ResultsData d = read_results(path);
  int ic = -1;
  for (std::size_t i = 0; i < d.names.size(); ++i)
    if (d.names[i] == name) ic = static_cast<int>(i);
  if (ic < 0)
    throw InputError(path + ": no channel '" + name + "' (" + nearest_text(name, d.names) + ")");
  const std::string csv = vm.count("csv") ? vm["csv"].as<std::string>() : "";
  if (over_time) {
    refuse_runup(d);
    time_mode(d, ic, t, segment, max_f, bands, csv);
  } else {
    order_mode(d, path, ic, cycles, cycle, max_order, csv);
  }
  return 0;
}

}  // namespace evas::cli
