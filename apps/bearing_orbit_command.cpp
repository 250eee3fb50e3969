// `evas bearing --load-cycle FILE`: see bearing_orbit_command.h.
#include "apps/bearing_orbit_command.h"

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "apps/finite_number.h"
#include "io/load_cycle.h"
#include "model/types.h"
#include "plot/gnuplot.h"
#include "study/report.h"

namespace evas::cli {

namespace fs = std::filesystem;

namespace {

std::string orbit_number(double x) {
  return finite_number(x, "evas bearing: an orbit value is not finite");
}

// The last cycle's points, angle_deg the crank angle in the load cycle's own
// range (first row's angle to one period later), time_s = crank angle / speed.
std::string orbit_csv(const BearingOrbit& o, double period_deg) {
  std::ostringstream os;
  os << "angle_deg,time_s,x_m,y_m,eccentricity,min_film_m,max_pressure_Pa,load_x_N,load_y_N\n";
  const double shift = (o.cycles - 1) * period_deg;
  for (const OrbitPoint& p : o.cycle)
    os << orbit_number(p.angle_deg - shift) << "," << orbit_number(p.time) << ","
       << orbit_number(p.e.x()) << "," << orbit_number(p.e.y()) << ","
       << orbit_number(p.eccentricity) << "," << orbit_number(p.min_film) << ","
       << orbit_number(p.max_pressure) << "," << orbit_number(p.load.x()) << ","
       << orbit_number(p.load.y()) << "\n";
  return os.str();
}

// The orbit in the clearance circle (x/c, y/c) and the film's smallest
// thickness over the cycle's crank angle.
std::string orbit_script(const fs::path& png, const std::string& title, double c) {
  std::ostringstream gp;
  gp << gp_terminal(png, 1100, 520) << "set datafile separator ','\n"
     << "set multiplot layout 1,2 title " << gp_quote(title) << "\n"
     << "set size ratio -1\nset xrange [-1.05:1.05]\nset yrange [-1.05:1.05]\n"
     << "set xlabel 'x / c (bearing frame)'\nset ylabel 'y / c'\nset grid\n"
     << "set object 1 circle at 0,0 size 1 fc rgb 'black' fs empty border lw 1\n"
     << "set key below\n"
     << "plot 'orbit.csv' using ($3/" << c << "):($4/" << c
     << ") with lines lw 2 title 'journal centre (last cycle)'\n"
     << "unset object 1\nset size noratio\nset autoscale\nset key below\n"
     << "set xlabel 'crank angle [deg]'\nset ylabel 'minimum film thickness [um]'\n"
     << "plot 'orbit.csv' using 1:($6*1e6) with lines lw 2 title 'c - |e|'\n"
     << "unset multiplot\n";
  return gp.str();
}

}  // namespace

int bearing_orbit_command(const JournalBearing& b, double om, const std::string& film,
                          const OrbitCommand& cmd) {
  const LoadCycle load = read_load_cycle(cmd.load_file);
  const fs::path dir = cmd.out_dir;
  const BearingOrbit o = bearing_orbit(b, om, load, cmd.options);
  fs::create_directories(dir);
  study::write_file_atomic(dir / "orbit.csv", orbit_csv(o, load.period_deg()));
  const double c = b.params().clearance;
  std::ostringstream title;
  title << "journal orbit, film '" << film << "', " << std::setprecision(5) << om * 30.0 / M_PI
        << " rpm: cycle " << o.cycles << (o.settled ? " (settled" : " (not settled") << ", moved "
        << std::setprecision(2) << o.change << " c over it)";
  study::write_file_atomic(dir / "orbit.gp", orbit_script(dir / "orbit.png", title.str(), c));
  if (!o.failure.empty()) {  // the points reached are written; the run failed
    std::cerr << "evas bearing: the orbit broke off in cycle " << o.cycles << ": " << o.failure
              << "\n  orbit up to there: " << (dir / "orbit.csv").string() << "\n";
    return 2;
  }
  bool drawn = false;
  if (cmd.plot && have_gnuplot()) {
    drawn = draw_figure(dir / "orbit.gp", dir / "orbit.png");
    if (!drawn) {
      std::cerr << "evas bearing: warning: gnuplot failed on " << (dir / "orbit.gp").string()
                << ": orbit.png not written\n";
    }
  }
  // the cycle's extremes
  const OrbitPoint* thin = &o.cycle.front();
  const OrbitPoint* peak = &o.cycle.front();
  for (const OrbitPoint& p : o.cycle) {
    if (p.min_film < thin->min_film) thin = &p;
    if (p.max_pressure > peak->max_pressure) peak = &p;
  }
  const double period = load.period_deg();
  auto cycle_angle = [&](double deg) { return deg - (o.cycles - 1) * period; };
  if (cmd.json) {
    std::cout << "{\n  \"film\": \"" << film << "\",\n  \"cycles\": " << o.cycles
              << ",\n  \"settled\": " << (o.settled ? "true" : "false")
              << ",\n  \"change\": " << orbit_number(o.change)
              << ",\n  \"max_eccentricity\": " << orbit_number(thin->eccentricity)
              << ",\n  \"min_film\": " << orbit_number(thin->min_film)
              << ",\n  \"min_film_angle_deg\": " << orbit_number(cycle_angle(thin->angle_deg))
              << ",\n  \"max_pressure\": " << orbit_number(peak->max_pressure)
              << ",\n  \"max_pressure_angle_deg\": " << orbit_number(cycle_angle(peak->angle_deg))
              << ",\n  \"steps\": " << o.steps << ",\n  \"rejected_steps\": " << o.rejected
              << ",\n  \"film_solves\": " << o.film_solves << "\n}\n";
  } else {
    auto row = [](const char* name, const std::string& v, const char* unit) {
      std::cout << "  " << std::left << std::setw(30) << name << std::right << std::setw(16) << v
                << "  " << unit << "\n";
    };
    std::cout << "journal orbit, film '" << film << "', load cycle " << cmd.load_file << " ("
              << orbit_number(period) << " deg):\n";
    row("cycles run", std::to_string(o.cycles), "");
    row("settled", o.settled ? "yes" : "no", "");
    row("orbit moved over the last cycle", orbit_number(o.change), "x c");
    row("largest eccentricity ratio", orbit_number(thin->eccentricity), "-");
    row("minimum film", orbit_number(thin->min_film), "m");
    row("  at crank angle", orbit_number(cycle_angle(thin->angle_deg)), "deg");
    row("largest peak pressure", orbit_number(peak->max_pressure),
        film == "finite" ? "Pa (estimate)" : "Pa");
    row("  at crank angle", orbit_number(cycle_angle(peak->angle_deg)), "deg");
    row("steps (rejected)", std::to_string(o.steps) + " (" + std::to_string(o.rejected) + ")", "");
    row("film solves", std::to_string(o.film_solves), "");
    std::cout << "  orbit: " << (dir / "orbit.csv").string() << "\n";
    if (drawn) std::cout << "  figure: " << (dir / "orbit.png").string() << "\n";
  }
  return 0;
}

}  // namespace evas::cli
