// evas bearing: the static answer of one journal bearing for any film model
// (elements/bearing_static.h), as a table or JSON.
#include <algorithm>
#include <boost/program_options.hpp>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>

#include "apps/bearing_orbit_command.h"
#include "apps/commands.h"
#include "apps/finite_number.h"
#include "elements/bearing_static.h"
#include "elements/registry.h"
#include "model/types.h"

namespace evas::cli {

namespace {

std::string num(double x) { return finite_number(x, "evas bearing: a result is not finite"); }

std::string matrix_json(const Eigen::Matrix2d& m) {
  return "[[" + num(m(0, 0)) + ", " + num(m(0, 1)) + "], [" + num(m(1, 0)) + ", " + num(m(1, 1)) +
         "]]";
}

void print_json(const BearingOperatingPoint& r, const std::string& film, const std::string& feed) {
  std::cout << "{\n  \"film\": \"" << film << "\",\n  \"feed\": \"" << feed
            << "\",\n  \"load\": " << num(r.load)
            << ",\n  \"eccentricity\": " << num(r.eccentricity)
            << ",\n  \"attitude_deg\": " << num(r.attitude_deg)
            << ",\n  \"sommerfeld\": " << num(r.sommerfeld)
            << ",\n  \"friction_variable\": " << num(r.friction_variable)
            << ",\n  \"friction_torque\": " << num(r.friction_torque)
            << ",\n  \"power_loss\": " << num(r.power_loss)
            << ",\n  \"min_film\": " << num(r.min_film)
            << ",\n  \"max_pressure\": " << num(r.max_pressure)
            << ",\n  \"max_pressure_angle_deg\": " << num(r.max_pressure_angle_deg)
            << ",\n  \"side_flow\": " << (r.side_flow ? num(*r.side_flow) : "null")
            << ",\n  \"feed_flow\": " << (r.feed_flow ? num(*r.feed_flow) : "null")
            << ",\n  \"film_fraction_min\": "
            << (r.film_fraction_min ? num(*r.film_fraction_min) : "null")
            << ",\n  \"K\": " << matrix_json(r.K) << ",\n  \"C\": " << matrix_json(r.C) << "\n}\n";
}

void print_table(const BearingOperatingPoint& r, const std::string& film) {
  auto row = [](const char* name, const std::string& v, const char* unit) {
    std::cout << "  " << std::left << std::setw(26) << name << std::right << std::setw(16) << v
              << "  " << unit << "\n";
  };
  std::cout << "journal bearing, film '" << film << "' (x along the load):\n";
  row("load", num(r.load), "N");
  row("eccentricity ratio", num(r.eccentricity), "-");
  row("attitude angle", num(r.attitude_deg), "deg");
  row("Sommerfeld number S", num(r.sommerfeld), "-");
  row("friction variable (R/c) f", num(r.friction_variable), "-");
  row("friction torque", num(r.friction_torque), "N m");
  row("power loss", num(r.power_loss), "W");
  row("minimum film", num(r.min_film), "m");
  row("maximum pressure", num(r.max_pressure), film == "finite" ? "Pa (estimate)" : "Pa");
  row("  at angle from the load", num(r.max_pressure_angle_deg), "deg");
  row("side flow", r.side_flow ? num(*r.side_flow) : "n/a", "m^3/s");
  if (r.feed_flow) row("flow from the feed", num(*r.feed_flow), "m^3/s");
  if (r.film_fraction_min) row("smallest film fraction", num(*r.film_fraction_min), "-");
  const char* k[4] = {"Kxx", "Kxy", "Kyx", "Kyy"};
  const char* c[4] = {"Cxx", "Cxy", "Cyx", "Cyy"};
  for (int i = 0; i < 4; ++i) row(k[i], num(r.K(i / 2, i % 2)), "N/m");
  for (int i = 0; i < 4; ++i) row(c[i], num(r.C(i / 2, i % 2)), "N s/m");
}

}  // namespace

int cmd_bearing(const std::vector<std::string>& args) {
  po::options_description opts(
      "usage: evas bearing --radius R --width B --clearance C --viscosity ETA --speed RPM\n"
      "                    (--load W | --eccentricity EPS | --load-cycle FILE [--out DIR])\n"
      "                    [--film short|finite|reynolds]\n"
      "                    [--cavitation swift-stieber|none|mass-conserving]\n"
      "                    [--grid-phi N] [--grid-axial N]\n"
      "                    [--feed none|axial-grooves|oil-holes|circumferential-groove]\n"
      "                    [--feed-angle DEG] [--feed-count N] [--feed-arc DEG]\n"
      "                    [--feed-width M] [--feed-diameter M]\n"
      "                    [--supply-pressure PA] [--json]\n\n"
      "The static answer of one journal bearing (the journal spinning at RPM under a steady\n"
      "load W, or at the eccentricity ratio EPS): eccentricity, attitude angle, Sommerfeld\n"
      "number S = (R/c)^2 eta N / P, friction variable (R/c) f, friction torque and power,\n"
      "maximum pressure and its angle, side flow, and the linearized stiffness K = -df/de\n"
      "and damping C = -df/d(de/dt) of the film force f on the journal, with x along the\n"
      "load. The film is the journal-bearing element's (the same code as at run time;\n"
      "parameters named as the element's). Grooves (film reynolds) sit at angles from the\n"
      "load, in the direction of rotation. docs/elements-journal-bearing.md, \"Film models\".\n\n"
      "With --load-cycle FILE (CSV: angle_deg,fx,fy; the load on the journal over one period\n"
      "of the crank angle, bearing frame) the journal's orbit instead: the journal massless,\n"
      "the film's force balancing the load at every instant (Booker's mobility idea with the\n"
      "element's film), cycles repeated until the orbit settles; DIR/orbit.csv, orbit.png.\n"
      "docs/elements-journal-bearing.md, \"Orbit under a load cycle\".\n\n"
      "options");
  double radius = 0, width = 0, clearance = 0, viscosity = 0, speed = 0;
  std::string film = "short", cavitation = "swift-stieber";
  const JournalBearingParams defaults;
  std::string feed = defaults.feed;
  double feed_angle = defaults.feed_angle, feed_arc = defaults.feed_arc,
         feed_width = defaults.feed_width, feed_diameter = defaults.feed_diameter,
         supply_pressure = defaults.supply_pressure;
  int feed_count = defaults.feed_count;
  int grid_phi = JournalBearingParams{}.grid_phi, grid_axial = JournalBearingParams{}.grid_axial;
  opts.add_options()("help,h", "show this help")("radius", po::value<double>(&radius),
                                                 "journal radius R [m]")(
      "width", po::value<double>(&width), "bearing width B [m]")(
      "clearance", po::value<double>(&clearance), "radial clearance c [m]")(
      "viscosity", po::value<double>(&viscosity), "dynamic viscosity eta [Pa s]")(
      "speed", po::value<double>(&speed), "journal speed [rpm]")("load", po::value<double>(),
                                                                 "steady load on the journal [N]")(
      "eccentricity", po::value<double>(), "eccentricity ratio e/c instead of the load")(
      "film", po::value<std::string>(&film)->default_value(film), "short | finite | reynolds")(
      "cavitation", po::value<std::string>(&cavitation)->default_value(cavitation),
      "film reynolds: swift-stieber | none | mass-conserving (needs a feed)")(
      "grid-phi", po::value<int>(&grid_phi)->default_value(grid_phi),
      "film reynolds: cells around the circumference")(
      "grid-axial", po::value<int>(&grid_axial)->default_value(grid_axial),
      "film reynolds: cells on the half width")(
      "feed", po::value<std::string>(&feed)->default_value(feed),
      "film reynolds: none | axial-grooves | oil-holes | circumferential-groove")(
      "feed-angle", po::value<double>(&feed_angle)->default_value(feed_angle),
      "axial grooves, oil holes: the first one's centre from the load [deg]")(
      "feed-count", po::value<int>(&feed_count)->default_value(feed_count),
      "axial grooves, oil holes: how many, evenly spaced")(
      "feed-diameter", po::value<double>(&feed_diameter)->default_value(feed_diameter),
      "oil holes: their diameter [m]")("feed-arc",
                                       po::value<double>(&feed_arc)->default_value(feed_arc),
                                       "axial grooves: arc of each [deg]")(
      "feed-width", po::value<double>(&feed_width)->default_value(feed_width),
      "circumferential groove: its width [m]")(
      "supply-pressure", po::value<double>(&supply_pressure)->default_value(supply_pressure),
      "oil pressure in the grooves [Pa]")("json", "print JSON instead of the table")(
      "load-cycle", po::value<std::string>(), "orbit under this load cycle (CSV angle_deg,fx,fy)")(
      "out", po::value<std::string>()->default_value("out/bearing-orbit"),
      "load cycle: folder for orbit.csv and orbit.png")(
      "cycles", po::value<int>()->default_value(OrbitOptions{}.max_cycles),
      "load cycle: the most cycles run (at least 2)")(
      "samples", po::value<int>()->default_value(OrbitOptions{}.samples),
      "load cycle: orbit points per cycle")(
      "settle-tol", po::value<double>()->default_value(OrbitOptions{}.settle_tol),
      "load cycle: settled when no orbit point moves more than this x c over a cycle")(
      "no-plot", "load cycle: do not run gnuplot (orbit.gp is still written)");
  po::variables_map vm;
  if (parse_args(args, opts, {}, vm)) return 0;
  for (const char* o : {"radius", "width", "clearance", "viscosity", "speed"})
    if (!vm.count(o)) throw InputError(std::string("missing --") + o);
  if (vm.count("load") + vm.count("eccentricity") + vm.count("load-cycle") != 1)
    throw InputError("give exactly one of --load, --eccentricity and --load-cycle");
  for (const char* o : {"out", "cycles", "samples", "settle-tol", "no-plot"})
    if (!vm[o].defaulted() && vm.count(o) && !vm.count("load-cycle"))
      throw InputError(std::string("--") + o + " goes with --load-cycle");
  if (!(speed > 0.0)) throw InputError("--speed " + num(speed) + ": must be above 0 rpm");
  const ElementType& t = element_type("journal-bearing");
  ParamValues v;
  v.numbers["radius"] = {radius};
  v.numbers["width"] = {width};
  v.numbers["clearance"] = {clearance};
  v.numbers["viscosity"] = {viscosity};
  v.numbers["grid_phi"] = {static_cast<double>(grid_phi)};
  v.numbers["grid_axial"] = {static_cast<double>(grid_axial)};
  v.texts["film"] = film;
  v.texts["cavitation"] = cavitation;
  v.numbers["feed_angle"] = {feed_angle};
  v.numbers["feed_count"] = {static_cast<double>(feed_count)};
  v.numbers["feed_arc"] = {feed_arc};
  v.numbers["feed_width"] = {feed_width};
  v.numbers["feed_diameter"] = {feed_diameter};
  v.numbers["supply_pressure"] = {supply_pressure};
  v.texts["feed"] = feed;
  const std::string where = "the bearing's options";
  for (const ParamSpec& s : t.params) {
    auto n = v.numbers.find(s.key);
    if (n != v.numbers.end()) check_param(s, n->second, where);
    auto x = v.texts.find(s.key);
    if (x != v.texts.end() && !s.choices.empty() &&
        std::find(s.choices.begin(), s.choices.end(), x->second) == s.choices.end()) {
      std::string list;
      for (const std::string& c : s.choices) list += (list.empty() ? "" : ", ") + c;
      throw InputError("--" + s.key + " '" + x->second + "' is not one of " + list);
    }
  }
  if (!(viscosity > 0.0)) throw InputError("--viscosity must be above 0 Pa s");
  if (!(clearance < radius)) throw InputError("--clearance must be smaller than --radius");
  complete_params(t, v, where);
  const std::unique_ptr<Element> el = t.make("bearing", {0, 1}, v);
  const auto& b = dynamic_cast<const JournalBearing&>(*el);
  const double om = speed * 2.0 * M_PI / 60.0;
  if (vm.count("load-cycle")) {
    OrbitCommand cmd;
    cmd.load_file = vm["load-cycle"].as<std::string>();
    cmd.out_dir = vm["out"].as<std::string>();
    cmd.options.max_cycles = vm["cycles"].as<int>();
    cmd.options.samples = vm["samples"].as<int>();
    cmd.options.settle_tol = vm["settle-tol"].as<double>();
    cmd.json = vm.count("json") > 0;
    cmd.plot = vm.count("no-plot") == 0;
    return bearing_orbit_command(b, om, film, cmd);
  }
  const BearingOperatingPoint r =
      vm.count("load") ? bearing_at_load(b, om, vm["load"].as<double>())
                       : bearing_at_eccentricity(b, om, vm["eccentricity"].as<double>());
  if (vm.count("json"))
    print_json(r, film, feed);
  else
    print_table(r, feed == "none" ? film : film + "', feed '" + feed);
  return 0;
}

}  // namespace evas::cli
