// evas_pressure: writes the synthetic cylinder-pressure curve that stands in
// for the paper's measured Fig. 10 (references.md section 3): one cylinder of
// a 4.1 L in-line four diesel at 3000 rpm, full load, peak 14 MPa.
//
//   cd /work/main && build/validation/evas_pressure [output.txt]
//   (default output: validation/data/cylinder_pressure_3000rpm.txt, relative to the repo root)
//
// With --map DIR --speeds N1,N2,... [--loads L1,L2,...]: the same cycle moved
// to every speed [rpm] and load (fraction of full load, default 1) by
// diesel_cycle_at (elements/gas_pressure.h: Woschni-Anisits scaling of the
// Wiebe durations, the 3000-rpm full-load heat release per cycle, boost
// rising with speed), one table per operating point and DIR/map.txt, the
// pressure map a piston-conrod element reads (`pressure_map:`,
// elements/pressure_map.h).
//
// Model: single zone, double Wiebe heat release, polytropic compression and
// expansion between inlet valve closing and exhaust valve opening; see
// elements/gas_pressure.h and docs/elements-piston-motor.md.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "elements/gas_pressure.h"

namespace {

std::vector<double> numbers(const std::string& list, const std::string& what) {
  std::vector<double> v;
  std::stringstream ss(list);
  for (std::string item; std::getline(ss, item, ',');) {
    char* end = nullptr;
    const double x = std::strtod(item.c_str(), &end);
    if (item.empty() || *end || !std::isfinite(x) || !(x > 0.0))
      throw evas::InputError(what + " '" + list + "': give positive numbers separated by commas");
    v.push_back(x);
  }
  if (v.empty()) throw evas::InputError(what + ": no value");
  return v;
}

std::string word(double x) {
  std::ostringstream os;
  os << x;
  return os.str();
}

// The map: one table per speed and load, and map.txt listing them.
int write_map(const std::string& dir, const std::vector<double>& speeds,
              const std::vector<double>& loads) {
  using namespace evas;
  DieselCycle ref;
  double ref_heat = 0.0;
  synthetic_diesel_cycle(ref, &ref_heat);  // the 3000-rpm full-load calibration
  std::filesystem::create_directories(dir);
  std::ostringstream map;
  map << "# Cylinder pressure of the validation engine per speed [rpm]"
      << (loads.size() > 1 ? " and load [fraction of full load]" : "")
      << ", written by evas_pressure --map\n"
      << "# (validation/pressure_main.cpp; elements/gas_pressure.h diesel_cycle_at)\n";
  for (double load : loads)
    for (double rpm : speeds) {
      const DieselCycle c = diesel_cycle_at(ref, 3000.0, ref_heat, rpm, load);
      const PressureTable t = synthetic_diesel_cycle(c);
      const std::string name = "p_" + word(rpm) + "rpm" +
                               (loads.size() > 1 ? "_load" + word(load) : std::string()) + ".txt";
      std::ostringstream info;
      info << "Synthetic diesel cylinder pressure at " << rpm << " rpm, load " << load
           << " (evas_pressure --map): heat release " << c.heat_release << " J, durations "
           << c.premixed_duration_deg << " / " << c.diffusion_duration_deg << " deg, m "
           << c.diffusion_m << ", boost " << c.p_intake / 1e5 << " bar; peak "
           << t.max_pressure() / 1e6 << " MPa. Absolute pressure; cycle angle 0 = firing TDC.";
      t.write(dir + "/" + name, info.str());
      map << rpm << " ";
      if (loads.size() > 1) map << load << " ";
      map << name << "\n";
      std::cout << name << ": " << rpm << " rpm, load " << load << ", peak "
                << t.max_pressure() / 1e6 << " MPa\n";
    }
  std::ofstream f(dir + "/map.txt");
  f << map.str();
  if (!f) throw InputError(dir + "/map.txt: cannot write");
  std::cout << "written " << dir << "/map.txt\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace evas;
  std::vector<std::string> args(argv + 1, argv + argc);
  if (!args.empty() && args[0] == "--map") {
    try {
      std::string dir, speeds, loads = "1";
      for (std::size_t i = 0; i + 1 < args.size(); i += 2) {
        if (args[i] == "--map")
          dir = args[i + 1];
        else if (args[i] == "--speeds")
          speeds = args[i + 1];
        else if (args[i] == "--loads")
          loads = args[i + 1];
        else
          throw InputError("unknown option " + args[i]);
      }
      if (args.size() % 2 != 0 || dir.empty() || speeds.empty())
        throw InputError("usage: evas_pressure --map DIR --speeds N1,N2,... [--loads L1,...]");
      return write_map(dir, numbers(speeds, "--speeds"), numbers(loads, "--loads"));
    } catch (const std::exception& e) {
      std::cerr << "evas_pressure: " << e.what() << "\n";
      return 1;
    }
  }
  // Default path relative to the repository root (run from there).
  const std::string out =
      argc > 1 ? argv[1] : std::string("validation/data/cylinder_pressure_3000rpm.txt");
  try {
    DieselCycle c;
    double Q = 0.0;
    const PressureTable t = synthetic_diesel_cycle(c, &Q);
    double peak = 0.0, at = 0.0;
    for (double a = 0.0; a < 720.0; a += 0.01) {
      const double p = t(a * M_PI / 180);
      if (p > peak) {
        peak = p;
        at = a;
      }
    }
    std::ostringstream info;
    info << "Synthetic diesel cylinder pressure, generated by evas_pressure "
            "(validation/pressure_main.cpp).\n"
         << "4.1 L in-line four, one cylinder: bore " << c.bore * 1e3 << " mm, stroke "
         << c.stroke * 1e3 << " mm, conrod " << c.conrod * 1e3 << " mm, compression ratio "
         << c.compression_ratio << "; 3000 rpm full load.\n"
         << "Single zone, double Wiebe (a " << c.wiebe_a << ", premixed " << c.premixed_fraction
         << " over " << c.premixed_duration_deg << " deg m " << c.premixed_m << ", diffusion over "
         << c.diffusion_duration_deg << " deg m " << c.diffusion_m << ", start " << c.soc_deg
         << " deg), polytropic n " << c.n_compression << " / " << c.n_expansion << ", IVC "
         << c.ivc_deg << " deg, EVO " << c.evo_deg << " deg, boost " << c.p_intake / 1e5
         << " bar, exhaust " << c.p_exhaust / 1e5 << " bar.\n"
         << "Net heat release " << Q << " J; peak " << peak / 1e6 << " MPa at " << at
         << " deg. Absolute pressure; cycle angle 0 = firing TDC.";
    t.write(out, info.str());
    std::cout << info.str() << "\nwritten " << out << " (" << t.angles_deg().size() << " rows)\n";
  } catch (const std::exception& e) {
    std::cerr << "evas_pressure: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
