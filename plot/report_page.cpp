// `evas report` (report_page.h): the sections, their figures (plot_results,
// one call each) and tables, and the page (report_html.h); what the results
// file holds comes from report_run.h.
#include "plot/report_page.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "model/types.h"
#include "plot/figures.h"
#include "plot/gnuplot.h"
#include "plot/report_budget.h"
#include "plot/report_html.h"
#include "plot/report_run.h"
#include "post/cycle_difference.h"
#include "post/order_spectrum.h"

namespace evas {

namespace fs = std::filesystem;

namespace {

using namespace report;  // Run, read_run, kCycle, the formatting

std::string code(const std::string& s) { return "<code>" + report::escape(s) + "</code>"; }

// The figures of the report, drawn one by one into the report's folder.
class Drawer {
 public:
  Drawer(const Run& run, const fs::path& dir, ReportResult& out)
      : run_(run), dir_(dir), out_(out) {}
  // Draws `file` (a .png name); returns it for the page.
  std::string draw(const std::string& file, PlotOptions o) {
    for (const auto& f : plot_results(run_.path, o, dir_ / file)) out_.files.push_back(f);
    ++out_.figures;
    return file;
  }
  PlotOptions options(const std::string& kind) const {
    PlotOptions o;
    o.kind = kind;
    o.cycles = run_.cycles;
    o.cycle = kCycle;
    return o;
  }

 private:
  const Run& run_;
  fs::path dir_;
  ReportResult& out_;
};

// Whether the record's last two 720-deg cycles agree (post/cycle_difference.h,
// the measure of evas run's summary), in words for the summary table.
std::string settled_text(const Run& run) {
  const Eigen::Index n = run.rows();
  if (n < 2) return "not known (one row)";
  const double step =
      (run.at(n - 1, run.crank) - run.at(0, run.crank)) / static_cast<double>(n - 1);
  std::string why;
  const long per = rows_per_period(true, step, 0.0, kCycle, why);
  if (per <= 0) return "not known: " + why;
  if (n < 2 * per)
    return "not known: the record holds fewer than two cycles of 720 deg to compare (one "
           "periodic cycle of evas periodic is steady by construction)";
  std::vector<Channel> ch;
  for (std::size_t c = 0; c < run.d.names.size(); ++c)
    ch.push_back({run.d.names[c], c < run.d.units.size() ? run.d.units[c] : ""});
  const long w = static_cast<long>(ch.size());
  std::vector<double> last(static_cast<std::size_t>(per * w)), prev(last.size());
  for (long r = 0; r < per; ++r)
    for (long c = 0; c < w; ++c) {
      last[static_cast<std::size_t>(r * w + c)] = run.d.values(n - per + r, c);
      prev[static_cast<std::size_t>(r * w + c)] = run.d.values(n - 2 * per + r, c);
    }
  const Settledness s = compare_cycles(ch, last.data(), prev.data(), per, w);
  return std::string(s.max_difference <= 1e-3 ? "yes" : "no") + ": the last two cycles differ by " +
         general(s.max_difference, 3) + " in " + s.worst_channel +
         " (tolerance 1e-3; evas periodic gives the steady cycle)";
}

void summary_section(const Run& run, report::Page& page) {
  page.heading(2, "Run summary", "summary");
  const ResultsData& d = run.d;
  const Eigen::Index n = run.rows();
  const double th0 = run.at(0, run.crank), th1 = run.at(n - 1, run.crank);
  const double step = n > 1 ? (th1 - th0) / static_cast<double>(n - 1) : 0.0;
  const double t0 = d.time[static_cast<std::size_t>(run.r0)], t1 = d.time.back();
  const double rpm =
      t1 > t0 ? (th1 - run.at(run.r0, run.crank)) / (t1 - t0) / 6.0 : 0.0;  // deg/s -> rpm
  std::vector<std::vector<std::string>> rows = {
      {"scene", scene_name(run)},
      {"results file", run.path},
      {"status", d.status.empty() ? "unknown" : d.status},
      {"integrator", d.integrator},
      {"output grid", d.grid + ", " + general(step, 4) + " deg per row"},
      {"rows", std::to_string(n)},
      {"time span", general(d.time.front()) + " .. " + general(d.time.back()) + " s"},
      {"crank angle", general(th0) + " .. " + general(th1) + " deg, " +
                          std::to_string(run.whole_cycles) + " whole cycle(s) of 720 deg"},
      {"mean speed over the analysed cycles", fixed(rpm, 1) + " rpm"},
      {"speed over the record",
       run.runup() ? "a run-up (or run-down): " + fixed(run.rpm_first, 0) +
                         " rpm in the first "
                         "whole cycle, " +
                         fixed(run.rpm_last, 0) +
                         " rpm in the last; the orders are tracked against speed below"
                   : "constant (the whole cycles' mean speeds within " +
                         general(100.0 * run.speed_spread, 2) + " %)"},
      {"analysed", run.span_text() + ", from t = " + general(t0) + " s"},
      {"channels", std::to_string(d.names.size())},
      {"journal bearings", listing(run.bearings)}};
  rows.push_back({"settled", settled_text(run)});
  for (auto& r : summary_rows(run.path)) rows.push_back(r);
  page.table({"item", "value"}, rows);
  if (!d.status.empty() && d.status != "completed")
    page.paragraph("The run did not complete (status " + code(d.status) +
                       "): the report shows the rows the file holds.",
                   "note");
  const auto st = stats_rows(run.path);
  if (st.empty())
    page.paragraph("The file holds no integrator statistics (the run did not finish).", "note");
  else
    page.table({"statistic", "value", "unit", "meaning"}, st, "Integrator statistics");
}

// Peaks of each bearing over the analysed rows.
void bearing_table(const Run& run, report::Page& page) {
  std::vector<std::vector<std::string>> rows;
  for (const auto& b : run.bearings) {
    const int fx = run.find(b + ".fx"), fy = run.find(b + ".fy"), h = run.find(b + ".h_min"),
              p = run.find(b + ".p_max"), e = run.find(b + ".eps"),
              fp = run.find(b + ".friction_power");
    double fmax = 0.0, hmin = 1e300, pmax = 0.0, emax = 0.0, fpsum = 0.0;
    double a_f = 0.0, a_h = 0.0;
    for (Eigen::Index r = run.r0; r < run.rows(); ++r) {
      const double f = std::hypot(run.at(r, fx), run.at(r, fy));
      if (f > fmax) fmax = f, a_f = run.angle(r);
      if (run.at(r, h) < hmin) hmin = run.at(r, h), a_h = run.angle(r);
      pmax = std::max(pmax, run.at(r, p));
      emax = std::max(emax, run.at(r, e));
      if (fp >= 0) fpsum += run.at(r, fp);
    }
    const double rows_n = static_cast<double>(run.rows() - run.r0);
    rows.push_back({b, fixed(1e-3 * fmax, 2), fixed(a_f, 0), fixed(1e6 * hmin, 2), fixed(a_h, 0),
                    fixed(1e-6 * pmax, 1), fixed(emax, 3),
                    fp >= 0 ? fixed(fpsum / rows_n, 1) : "-"});
  }
  page.table({"bearing", "max load [kN]", "at [deg]", "min film h_min [\u00b5m]", "at [deg]",
              "max peak pressure [MPa]", "max eccentricity ratio", "mean friction power [W]"},
             rows, "Peaks over " + run.span_text() + " (crank angle in the 720-deg cycle)");
}

void bearings_section(const Run& run, Drawer& draw, report::Page& page, ReportResult& out) {
  page.heading(2, "Journal bearings", "bearings");
  if (run.bearings.empty()) {
    page.paragraph(
        "This results file has no journal-bearing channels (an element with " + code("fx") + ", " +
            code("eps") + ", " + code("h_min") + ", " + code("p_max") +
            ", ... channels). Add the output request " + code("{element: NAME}") +
            " of each journal-bearing element to the scene's " + code("output.channels") + ".",
        "note");
    out.notes.push_back("no journal bearing: no bearing figures, loads or order spectra");
    return;
  }
  bearing_table(run, page);
  for (const auto& b : run.bearings) {
    page.heading(3, "Bearing " + b, "bearing-" + file_word(b));
    page.begin_row();
    PlotOptions o = draw.options("polar");
    o.element = b;
    page.figure(draw.draw("polar_" + file_word(b) + ".png", o), "polar load diagram of " + b,
                "Polar load diagram of " + b + " over " + run.span_text() +
                    ": left the load on the shell (-fx, -fy) in the bearing's axes, right the "
                    "load on the journal in axes turning with it; dots every 90 deg of crank "
                    "angle [kN]. The bearing's axes are those of the element's first marker "
                    "(on the validation engine's bores x lies along the "
                    "cylinders' axis, and y across the engine: fx is the vertical load, fy "
                    "the horizontal one); a panel whose load swings 4 times more along one "
                    "axis than the other is drawn to different scales, as its title says.");
    o.kind = "orbit";
    page.figure(draw.draw("orbit_" + file_word(b) + ".png", o), "journal orbit of " + b,
                "Orbit of the journal centre of " + b +
                    " (ex, ey in the bearing's axes) "
                    "inside the clearance circle, over " +
                    run.span_text() + " [\u00b5m].");
    page.end_row();
    o.kind = "film";
    page.figure(draw.draw("film_" + file_word(b) + ".png", o), "oil film of " + b,
                "Minimum film thickness h_min [\u00b5m] and peak film pressure p_max [MPa] of " +
                    b + " against crank angle in the cycle, " + run.span_text() + ".");
  }
}

// The largest orders of each bearing's load over the analysed cycles.
void order_table(const Run& run, report::Page& page, ReportResult& out) {
  std::vector<double> theta;
  for (Eigen::Index r = 0; r < run.rows(); ++r) theta.push_back(run.at(r, run.crank));
  std::vector<std::vector<double>> ys;
  std::vector<std::string> names;
  for (const auto& b : run.bearings)
    for (const char* c : {".fx", ".fy"}) {
      const int k = run.find(b + c);
      std::vector<double> y;
      for (Eigen::Index r = 0; r < run.rows(); ++r) y.push_back(run.at(r, k));
      ys.push_back(std::move(y));
      names.push_back(b + c);
    }
  std::vector<const std::vector<double>*> yp;
  for (const auto& y : ys) yp.push_back(&y);
  const std::vector<OrderSpectrum> s = order_spectra(theta, yp, run.cycles, kCycle, 12.0);
  constexpr std::size_t kLargest = 5;
  std::vector<std::vector<std::string>> rows;
  for (std::size_t i = 0; i < s.size(); ++i) {
    std::vector<std::size_t> k;
    for (std::size_t j = 0; j < s[i].order.size(); ++j)
      if (s[i].order[j] > 0.0) k.push_back(j);
    std::sort(k.begin(), k.end(),
              [&](std::size_t a, std::size_t b) { return s[i].amplitude[a] > s[i].amplitude[b]; });
    std::vector<std::string> row = {names[i], fixed(1e-3 * s[i].amplitude[0], 2)};
    for (std::size_t j = 0; j < kLargest; ++j)
      row.push_back(j < k.size() ? general(s[i].order[k[j]], 3) + ": " +
                                       fixed(1e-3 * s[i].amplitude[k[j]], 2)
                                 : "-");
    rows.push_back(row);
  }
  std::vector<std::string> head = {"channel", "mean (order 0) [kN]"};
  for (std::size_t j = 1; j <= kLargest; ++j)
    head.push_back(std::to_string(j) +
                   (j == 1   ? "st"
                    : j == 2 ? "nd"
                    : j == 3 ? "rd"
                             : "th") +
                   " largest, order: kN");
  page.table(head, rows,
             "The largest engine orders (up to 12) of each bearing's load over " +
                 std::to_string(s.empty() ? 0 : s[0].cycles) + " whole cycle(s) [kN]");
  (void)out;
}

void loads_section(const Run& run, Drawer& draw, report::Page& page, ReportResult& out) {
  if (run.bearings.empty()) return;
  page.heading(2, "Bearing loads against crank angle", "loads");
  for (const char* c : {"fx", "fy"}) {
    PlotOptions o = draw.options("channels");
    for (const auto& b : run.bearings) o.channels.push_back(b + "." + c);
    o.title = std::string(c) + " of every journal bearing: force on the journal in bearing axes";
    page.figure(draw.draw(std::string("loads_") + c + ".png", o), std::string("bearing loads ") + c,
                std::string(c) +
                    " of every journal bearing (the force on the journal in the "
                    "bearing's axes; the load on the shell is its negative) "
                    "against crank angle, " +
                    run.span_text() + " [kN].");
  }
  page.heading(2, "Order spectra of the bearing loads", "orders");
  if (run.whole_cycles < 1) {
    page.paragraph("The record covers less than one 720-deg cycle: no order spectrum.", "note");
    out.notes.push_back("record shorter than one cycle: no order spectra");
    return;
  }
  try {
    order_table(run, page, out);
  } catch (const InputError& e) {
    page.paragraph("No order spectra: " + report::escape(e.what()), "note");
    out.notes.push_back(std::string("no order spectra: ") + e.what());
    return;
  }
  if (run.runup()) {
    page.paragraph(
        "The speed changes over the record (" + fixed(run.rpm_first, 0) + " to " +
        fixed(run.rpm_last, 0) +
        " rpm): the table above is the last cycle's alone, and the figures below track each "
        "order per 720-deg cycle against the cycle's mean speed (" +
        code("evas plot order-track") +
        "; the title gives the largest change of speed "
        "within one cycle, which smears a resonance crossed during it).");
    for (const auto& b : run.bearings) {
      page.begin_row();
      for (const char* c : {"fx", "fy"}) {
        PlotOptions o = draw.options("order-track");
        o.channels = {b + "." + c};
        o.orders = {1.0, 2.0, 4.0, 6.0};
        page.figure(draw.draw("order_track_" + file_word(b) + "_" + c + ".png", o),
                    "order tracking of " + b + "." + c,
                    "Orders 1, 2, 4 and 6 of " + b + "." + c +
                        " per cycle against the cycle's mean speed [kN].");
      }
      page.end_row();
    }
    return;
  }
  for (const auto& b : run.bearings) {
    page.begin_row();
    for (const char* c : {"fx", "fy"}) {
      PlotOptions o = draw.options("order");
      o.channels = {b + "." + c};
      page.figure(draw.draw("order_" + file_word(b) + "_" + c + ".png", o),
                  "order spectrum of " + b + "." + c,
                  "Order spectrum of " + b + "." + c + " over " +
                      (run.cycles > 0 ? run.span_text() : "every whole cycle") +
                      ": amplitude per engine order [kN].");
    }
    page.end_row();
  }
}

void friction_section(const Run& run, Drawer& draw, report::Page& page, ReportResult& out) {
  std::vector<std::string> ch;
  for (const auto& b : run.bearings)
    if (run.find(b + ".friction_power") >= 0) ch.push_back(b + ".friction_power");
  page.heading(2, "Friction power", "friction");
  if (ch.empty()) {
    page.paragraph("No friction_power channel of a journal bearing in this file.", "note");
    out.notes.push_back("no friction power channels");
    return;
  }
  double total = 0.0;
  for (const auto& c : ch) {
    const int k = run.find(c);
    double s = 0.0;
    for (Eigen::Index r = run.r0; r < run.rows(); ++r) s += run.at(r, k);
    total += s / static_cast<double>(run.rows() - run.r0);
  }
  page.paragraph("Mean friction power of the " + std::to_string(ch.size()) +
                 " journal bearing(s) together over " + run.span_text() + ": <strong>" +
                 fixed(total, 1) + " W</strong> (each bearing's mean: the table above).");
  PlotOptions o = draw.options("channels");
  o.channels = ch;
  o.title = "friction power of the journal bearings";
  page.figure(draw.draw("friction_power.png", o), "friction power",
              "The power each journal bearing's film takes from the journal's spin against "
              "crank angle, " +
                  run.span_text() + " [W].");
}

void torsion_section(const Run& run, Drawer& draw, report::Page& page, ReportResult& out) {
  page.heading(2, "Crankshaft torsion", "torsion");
  const auto twists = run.ending(".twist");
  if (twists.empty()) {
    page.paragraph("No torsion channels (" + code("NAME.twist") +
                       ") in this file: the output request " + code("{torsion: [A, B]}") +
                       " (two markers on the crankshaft) gives them.",
                   "note");
    out.notes.push_back("no crankshaft torsion channels");
    return;
  }
  for (const auto& t : twists) {
    const std::string name = t.substr(0, t.size() - 6);
    // a torsion request ({torsion: [A, B]}) has the angles of its markers; an
    // element's twist (a motor's shaft to its dynamometer) stands alone
    const bool request = run.find(name + ".angle_a") >= 0 && run.find(name + ".angle_b") >= 0;
    PlotOptions o = draw.options("channels");
    o.channels = request ? std::vector<std::string>{name + ".angle_a", name + ".angle_b", t}
                         : std::vector<std::string>{t};
    o.title = request ? "torsion " + name + ": angles of a and b relative to the LOF, twist b - a"
                      : "twist of element " + name;
    page.begin_row();
    page.figure(draw.draw("torsion_" + file_word(name) + ".png", o), "torsion " + name,
                (request ? "Torsion request " + name +
                               ": the rotation of its markers a and b about the spin axis "
                               "relative to the LOF, and the twist b - a"
                         : "The twist of element " + name + " (its channel " + t +
                               ", e.g. a motor's shaft to the dynamometer)") +
                    ", against crank angle, " + run.span_text() + " [mrad].");
    if (run.whole_cycles >= 1) {
      PlotOptions s = draw.options("order");
      s.channels = {t};
      page.figure(draw.draw("order_" + file_word(name) + "_twist.png", s), "order spectrum of " + t,
                  "Order spectrum of the twist " + t + ": amplitude per engine order [mrad].");
    }
    page.end_row();
  }
}

void surface_section(const Run& run, Drawer& draw, report::Page& page, ReportResult& out) {
  page.heading(2, "Block surface velocity", "surface");
  const std::vector<std::pair<std::string, std::string>> kinds = {
      {".vn_rms", "RMS over the surface of the normal velocity"},
      {".vn_mean", "mean over the surface of the normal velocity"},
      {".erp",
       "equivalent radiated power (with its elastic part, the body's deformation, and its "
       "rigid-body part, e.g. the rocking on the mounts)"}};
  bool any = false;
  for (const auto& [tail, what] : kinds) {
    auto ch = run.ending(tail);
    if (ch.empty()) continue;
    if (tail == ".erp") {  // each surface's parts beside its total
      std::vector<std::string> all;
      for (const auto& c : ch) {
        all.push_back(c);
        for (const char* part : {"_elastic", "_rigid"})
          if (run.find(c + part) >= 0) all.push_back(c + part);
      }
      ch = all;
    }
    any = true;
    std::vector<std::vector<std::string>> rows;
    for (const auto& c : ch) {
      const int k = run.find(c);
      double mean = 0.0, peak = 0.0;
      for (Eigen::Index r = run.r0; r < run.rows(); ++r) {
        mean += run.at(r, k);
        peak = std::max(peak, std::abs(run.at(r, k)));
      }
      mean /= static_cast<double>(run.rows() - run.r0);
      const std::string unit = run.d.units[static_cast<std::size_t>(k)];
      rows.push_back({c, general(mean, 4), general(peak, 4), unit});
    }
    PlotOptions o = draw.options("channels");
    o.channels = ch;
    o.title = what;
    page.figure(
        draw.draw("surface_" + file_word(tail.substr(1)) + ".png", o), what,
        "The " + what + " (channels *" + tail + ") against crank angle, " + run.span_text() + ".");
    page.table({"channel", "mean", "largest |value|", "unit"}, rows,
               "The " + what + " over " + run.span_text());
  }
  // the ERP spectrum of each surface output whose components are in the file
  for (const auto& e : run.ending(".erp")) {
    const std::string name = e.substr(0, e.size() - 4);
    if (run.find(name + ".c0") < 0) continue;
    if (run.runup()) {
      // a spectrum over time needs a uniform time grid: the run-up's ERP per
      // cycle against speed instead
      PlotOptions o = draw.options("order-track");
      o.channels = {e};
      for (const char* part : {".erp_elastic", ".erp_rigid"})
        if (run.find(name + part) >= 0) o.channels.push_back(name + part);
      o.orders = {0.0};
      const std::string what = "equivalent radiated power of " + name + " against speed";
      page.figure(draw.draw("erp_track_" + file_word(name) + ".png", o), what,
                  "The mean ERP of " + name +
                      " over each 720-deg cycle against the cycle's mean speed [W]: the whole, "
                      "the elastic part (the block's deformation) and the rigid-body part (its "
                      "motion on the mounts). A spectrum over time needs a constant speed (the "
                      "crank-angle grid of a run-up is not uniform in time).");
      continue;
    }
    PlotOptions o = draw.options("erp");
    o.channels = {name};
    o.spectrum.t0 = run.d.time[static_cast<std::size_t>(run.r0)];
    const std::string what = "equivalent radiated power spectrum of " + name;
    page.figure(draw.draw("erp_spectrum_" + file_word(name) + ".png", o), what,
                "The " + what + " over " + run.span_text() +
                    ": the power of each frequency bin (tonal) and of each third-octave band, "
                    "in dB re 1 pW, and the bands of the elastic part (the body's deformation: "
                    "the rigid-body motion, which radiates little at these frequencies, left "
                    "out), unweighted and A-weighted (IEC 61672-1) (Hann window; evas spectrum "
                    "--erp " +
                    name +
                    " --bands third-octave prints the bands; --radiation piston:R weights the "
                    "elastic part by a baffled piston's radiation efficiency).");
  }
  if (!any) {
    page.paragraph("This results file has no surface-velocity channels (names ending in " +
                       code(".vn_rms") + ", " + code(".vn_mean") + " or " + code(".erp") +
                       "). Add the output request " +
                       code("{surface: SET, body: BODY, name: NAME}") +
                       " (a node set on the block's outer surface) to the scene's " +
                       code("output.channels") + " to get them.",
                   "note");
    out.notes.push_back("no block surface-velocity channels (output request {surface: ...})");
  }
}

// The list of the files a report wrote, beside its page: with --overwrite the
// next report removes exactly these before it draws, so that no figure of the
// earlier report stays in the folder unlinked (a section the new run does not
// have), and nothing else in the folder is touched.
constexpr const char* kManifest = "report-files.txt";

void remove_earlier_report(const fs::path& dir) {
  std::ifstream f(dir / kManifest);
  std::string name;
  std::error_code ec;
  while (std::getline(f, name))
    // names as the report writes them: plain files in the folder itself
    if (!name.empty() && name.find('/') == std::string::npos && name != "." && name != "..")
      if (fs::is_regular_file(dir / name, ec)) fs::remove(dir / name, ec);
  f.close();
  fs::remove(dir / kManifest, ec);
}

void write_manifest(const fs::path& dir, ReportResult& out) {
  const fs::path tmp = dir / (std::string(kManifest) + ".part");
  {
    std::ofstream f(tmp, std::ios::binary);
    for (const std::string& file : out.files) f << fs::path(file).filename().string() << "\n";
    f.close();
    if (!f) throw InputError(tmp.string() + ": cannot write the report's file list");
  }
  std::error_code ec;
  fs::rename(tmp, dir / kManifest, ec);
  if (ec) throw InputError((dir / kManifest).string() + ": cannot write: " + ec.message());
  out.files.push_back((dir / kManifest).string());
}

}  // namespace

ReportResult write_report(const std::string& results, const fs::path& dir, const ReportOptions& o) {
  if (!fs::exists(results)) throw InputError(results + ": no such results file");
  if (fs::is_directory(results))
    throw InputError(results + ": a folder, not a results file (give FOLDER/results.h5)");
  if (fs::exists(dir) && !fs::is_directory(dir))
    throw InputError("--out " + dir.string() +
                     ": is a file, not a folder (the report is a folder: index.html and its "
                     "figures)");
  ReportResult out;
  out.index = dir / "index.html";
  if (fs::exists(out.index) && !o.overwrite)
    throw InputError(out.index.string() +
                     ": a report is there already; give --overwrite to replace it, or another "
                     "--out");
  if (o.cycles < -1) throw InputError("--cycles must be >= 0");
  if (!have_gnuplot())
    throw InputError("report: gnuplot is not installed (apt-get install gnuplot-nox)");
  const Run run = read_run(results, o.cycles);
  out.cycles = run.span_text() + " of " + std::to_string(run.whole_cycles) + " whole";
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw InputError("--out " + dir.string() + ": cannot create the folder: " + ec.message());
  fs::remove(out.index, ec);  // a failure below must not leave the old page over new figures
  remove_earlier_report(dir);

  report::Page page(o.title.empty() ? "Engine report: " + scene_name(run) : o.title);
  page.paragraph("Written by " + code("evas report") + " from " + code(run.path) +
                 ". Click a figure for its full size; each figure's gnuplot script and data "
                 "are beside it in this folder.");
  Drawer draw(run, dir, out);
  summary_section(run, page);
  budget_section(run.path, page);
  bearings_section(run, draw, page, out);
  loads_section(run, draw, page, out);
  if (!run.bearings.empty()) friction_section(run, draw, page, out);
  torsion_section(run, draw, page, out);
  surface_section(run, draw, page, out);

  const fs::path tmp = dir / "index.html.part";
  {
    std::ofstream f(tmp, std::ios::binary);
    f << page.html();
    f.close();
    if (!f) throw InputError(tmp.string() + ": cannot write the report page");
  }
  out.files.push_back(out.index.string());
  write_manifest(dir, out);
  fs::rename(tmp, out.index, ec);
  if (ec) throw InputError(out.index.string() + ": cannot write the report page: " + ec.message());
  return out;
}

}  // namespace evas
