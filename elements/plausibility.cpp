// Plausible ranges and the unit slips that explain values outside them
// (plausibility.h).
#include "elements/plausibility.h"

#include <cmath>
#include <sstream>

#include "model/types.h"

namespace evas {

namespace {

using Q = Quantity;

// Plausible ranges for the engines evas is made for: from a motorcycle single
// to a truck engine, idle to 15000 rpm. The bearing figures follow the usual
// design rules for engine plain bearings (clearance ratio c/R of about 0.5 to
// 2 per mille, oil of 2 to 100 mPa s at running temperature; e.g. Khonsari &
// Booser, Applied Tribology, 2nd ed., Wiley 2008, ch. 8), the mount figures
// rubber engine mounts (1e4 to 1e7 N/m per direction).
std::vector<PlausibleRange> make_table() {
  return {
      {"journal-bearing", "radius", Q::Length, 0.005, 0.5, false, false, false,
       "a journal bearing's journal radius"},
      {"journal-bearing", "width", Q::Length, 0.003, 0.5, false, false, false,
       "a journal bearing's width"},
      {"journal-bearing", "clearance", Q::Length, 2e-6, 5e-4, false, false, false,
       "a journal bearing's radial clearance"},
      {"journal-bearing", "viscosity", Q::Viscosity, 5e-4, 1.0, true, false, false,
       "engine oil's dynamic viscosity"},
      {"journal-bearing", "journal_speed", Q::Speed, 0.0, 1600.0, true, false, true,
       "a journal's spin"},
      {"piston-conrod", "crank_radius", Q::Length, 0.005, 2.0, false, false, false,
       "a crank radius (half the stroke)"},
      {"piston-conrod", "conrod_length", Q::Length, 0.02, 6.0, false, false, false,
       "a connecting rod's length"},
      {"piston-conrod", "bore", Q::Length, 0.015, 1.0, false, false, false, "a cylinder bore"},
      {"piston-conrod", "piston_mass", Q::Mass, 0.01, 5000.0, true, false, false,
       "a piston's mass"},
      {"piston-conrod", "conrod_reciprocating_mass", Q::Mass, 0.005, 5000.0, true, false, false,
       "a connecting rod's reciprocating mass"},
      {"piston-conrod", "conrod_rotating_mass", Q::Mass, 0.005, 5000.0, true, false, false,
       "a connecting rod's rotating mass"},
      {"piston-conrod", "speed", Q::Speed, 1.0, 1600.0, true, false, false,
       "a crank's speed (10 to 15000 rpm)"},
      {"piston-conrod", "crankcase_pressure", Q::Pressure, 2e4, 5e5, true, false, false,
       "a crankcase's absolute pressure"},
      {"motor", "speed", Q::Speed, 1.0, 1600.0, true, false, true,
       "a crank's speed (10 to 15000 rpm)"},
      {"engine-mount", "k_x", Q::Stiffness, 1e3, 1e10, true, true, false,
       "an engine mount's stiffness"},
      {"engine-mount", "k_y", Q::Stiffness, 1e3, 1e10, true, true, false,
       "an engine mount's stiffness"},
      {"engine-mount", "k_z", Q::Stiffness, 1e3, 1e10, true, true, false,
       "an engine mount's stiffness"},
      {"engine-mount", "damping", Q::Damping, 1.0, 1e6, true, false, false,
       "an engine mount's damping"},
      {"thrust-bearing", "gap", Q::Length, 1e-6, 2e-3, true, false, false,
       "a thrust bearing's axial play"},
      {"belt", "tension", Q::Force, 10.0, 5e4, true, false, false, "a belt's static tension"},
      {"belt", "radii", Q::Length, 0.01, 1.0, false, false, true, "a pulley's radius"},
      {"lof", "speed", Q::Speed, 1.0, 1600.0, true, false, true,
       "a crank's speed (10 to 15000 rpm)"},
      {"generate", "length", Q::Length, 0.01, 20.0, false, false, false, "a body's length"},
      {"generate", "width", Q::Length, 0.002, 5.0, false, false, false, "a body's width"},
      {"generate", "youngs", Q::Modulus, 1e8, 1e12, false, false, false,
       "a structural material's Young's modulus (steel 2.1e11 Pa)"},
      {"generate", "area", Q::Area, 1e-8, 1.0, false, false, false, "a bar's cross-section"},
      {"generate", "density", Q::Density, 500.0, 25000.0, false, false, false,
       "a structural material's density (steel 7850 kg/m^3)"},
  };
}

struct Slip {
  const char* unit;
  double factor;  ///< SI value of 1 unit
};

// What the messages say of a quantity: its SI unit, the rule ("lengths are in
// metres") and the units a value of it is likely typed in by mistake.
struct UnitFacts {
  const char* unit;
  const char* rule;
  std::vector<Slip> slips;
};

const UnitFacts& facts(Quantity q) {
  static const std::vector<UnitFacts> table = {
      // in the order of enum class Quantity
      {"m", "lengths are in metres", {{"mm", 1e-3}, {"um", 1e-6}, {"cm", 1e-2}}},
      {"rad/s", "speeds are in rad/s", {{"rpm", 2.0 * M_PI / 60.0}}},
      {"Pa", "pressures are in Pa", {{"bar", 1e5}, {"MPa", 1e6}, {"kPa", 1e3}}},
      {"Pa s", "viscosities are in Pa s", {{"mPa s (cP)", 1e-3}}},
      {"kg", "masses are in kg", {{"g", 1e-3}, {"t", 1e3}}},
      {"N/m", "stiffnesses are in N/m", {{"N/mm", 1e3}, {"kN/mm", 1e6}}},
      {"N s/m", "damping is in N s/m", {{"N s/mm", 1e3}}},
      {"N", "forces are in N", {{"kN", 1e3}}},
      {"Pa", "moduli are in Pa", {{"MPa (N/mm^2)", 1e6}, {"GPa", 1e9}}},
      {"kg/m^3", "densities are in kg/m^3", {{"g/cm^3", 1e3}, {"t/mm^3", 1e12}}},
      {"m^2", "areas are in m^2", {{"mm^2", 1e-6}, {"cm^2", 1e-4}}},
  };
  return table.at(static_cast<std::size_t>(q));
}

const char* si_unit(Quantity q) { return facts(q).unit; }
const char* unit_rule(Quantity q) { return facts(q).rule; }
const std::vector<Slip>& slips(Quantity q) { return facts(q).slips; }

bool in_range(const PlausibleRange& r, double x) {
  const double a = r.magnitude ? std::abs(x) : x;
  if (r.zero_ok && a == 0.0) return true;
  return a >= r.lo && a <= r.hi;
}

std::string num(double x) {
  std::ostringstream os;
  os << x;
  return os.str();
}

}  // namespace

const std::vector<PlausibleRange>& plausible_ranges() {
  static const std::vector<PlausibleRange> table = make_table();
  return table;
}

const PlausibleRange* plausible_range(const std::string& type, const std::string& key) {
  for (const auto& r : plausible_ranges())
    if (r.type == type && r.key == key) return &r;
  return nullptr;
}

std::string plausible_text(const PlausibleRange& r) {
  std::string s = (r.magnitude ? "magnitude " : "") + num(r.lo) + " .. " + num(r.hi) + " " +
                  si_unit(r.quantity);
  if (r.zero_ok) s += ", or 0";
  if (r.first_only) s += " (linear term)";
  return s;
}

// The unit slip that brings `x` into the range, nearest its middle on a
// logarithmic scale, or null.
const Slip* best_slip(const PlausibleRange& r, double x, const std::vector<Slip>& candidates) {
  const Slip* best = nullptr;
  double best_d = 0.0;
  const double mid = 0.5 * (std::log(r.lo > 0.0 ? r.lo : 1e-300) + std::log(r.hi));
  for (const Slip& s : candidates) {
    const double y = std::abs(x * s.factor);
    if (y == 0.0 || !in_range(r, x * s.factor)) continue;
    const double d = std::abs(std::log(y) - mid);
    if (!best || d < best_d) {
      best = &s;
      best_d = d;
    }
  }
  return best;
}

std::string plausibility_warning(const PlausibleRange& r, double x) {
  if (in_range(r, x)) return "";
  std::string w = r.key + " = " + num(x) + " " + si_unit(r.quantity) +
                  " is outside the plausible range of " + r.what + ", " + plausible_text(r) + ": " +
                  unit_rule(r.quantity);
  if (const Slip* s = best_slip(r, x, slips(r.quantity)))
    return w + " (" + num(x) + " " + s->unit + " would be " + num(x * s->factor) + " " +
           si_unit(r.quantity) + ")";
  return w + " (no common unit slip explains it: check the value)";
}

void check_plausible(const ElementType& type, const ParamValues& values, const std::string& where,
                     std::vector<std::string>& warnings) {
  for (const auto& p : type.params) {
    const PlausibleRange* r = plausible_range(type.type, p.key);
    if (!r || !values.given(p.key) || !values.numbers.count(p.key)) continue;
    const std::vector<double>& x = values.numbers.at(p.key);
    for (std::size_t i = 0; i < x.size() && (i == 0 || !r->first_only); ++i)
      if (std::string w = plausibility_warning(*r, x[i]); !w.empty()) {
        warnings.push_back(where + ": " + w);
        break;
      }
  }
  if (type.type == "piston-conrod" && values.given("piston_mass")) {
    // pistons weigh about 0.1 to 20 times the cube of their bore in tonnes
    // (0.35 kg at 86 mm, 1.6 kg at 106 mm, tonnes at 1 m): a piston mass outside
    // that band for its bore is most likely in grams
    const double m = values.scalar("piston_mass"), B = values.scalar("bore");
    const double ratio = m / (B * B * B);
    if (m > 0.0 && (ratio < kMinPistonDensity || ratio > kMaxPistonDensity)) {
      std::string w = "piston_mass " + num(m) + " kg for a bore of " + num(B) + " m is " +
                      num(ratio) + " kg per cubic bore (pistons: " + num(kMinPistonDensity) +
                      " .. " + num(kMaxPistonDensity) + ")";
      if (const double g = m * 1e-3;
          g / (B * B * B) >= kMinPistonDensity && g / (B * B * B) <= kMaxPistonDensity)
        w += ": masses are in kg (" + num(m) + " g would be " + num(g) + " kg)";
      warnings.push_back(where + ": " + w);
    }
  }
  if (type.type == "journal-bearing") {
    const double R = values.scalar("radius"), c = values.scalar("clearance");
    if (c >= R) {
      std::string msg = "clearance " + num(c) + " m is not smaller than the journal radius " +
                        num(R) +
                        " m: the journal cannot sit in its bearing; clearances are in metres";
      if (const Slip* s = best_slip(*plausible_range(type.type, "clearance"), c, slips(Q::Length)))
        msg += " (" + num(c) + " " + s->unit + " is " + num(c * s->factor) + " m)";
      throw InputError(where + ": " + msg);
    }
    if (c > 0.02 * R)
      warnings.push_back(where + ": clearance " + num(c) + " m is " + num(100.0 * c / R) +
                         " % of the journal radius " + num(R) +
                         " m; engine bearings have clearance ratios c/R of about 0.05 to 0.2 %");
  }
}

namespace {

// "" or why a part of this mass and box is implausible.
std::string part_implausible(double mass, const Vec3& extent) {
  const double size = extent.maxCoeff();
  const double box = extent.x() * extent.y() * extent.z();
  if (!(size >= kMinPartSize && size <= kMaxPartSize))
    return "its largest side is " + num(size) + " m (an engine part: " + num(kMinPartSize) +
           " .. " + num(kMaxPartSize) + " m)";
  if (box > 0.0) {
    const double rho = mass / box;
    if (!(rho >= kMinBoxDensity && rho <= kMaxBoxDensity))
      return "its mean density over the box is " + num(rho) +
             " kg/m^3 (a metal part: " + num(kMinBoxDensity) + " .. " + num(kMaxBoxDensity) + ")";
  }
  return "";
}

}  // namespace

std::string mesh_units_warning(double mass, const Vec3& extent, const MeshUnits& used,
                               const std::vector<MeshUnits>& others) {
  const std::string why = part_implausible(mass, extent);
  if (why.empty()) return "";
  auto box = [](const Vec3& e) { return num(e.x()) + " x " + num(e.y()) + " x " + num(e.z()); };
  std::string w = "read as " + used.name + ", the body has a mass of " + num(mass) +
                  " kg and a bounding box of " + box(extent) + " m: " + why;
  for (const MeshUnits& u : others) {
    if (u.name == used.name) continue;
    const double m = mass / used.mass * u.mass;
    const Vec3 e = extent / used.length * u.length;
    if (part_implausible(m, e).empty())
      return w + "; the files are likely in " + u.name + " (then a " + num(m) + " kg part of " +
             box(e) + " m): check --units";
  }
  return w + "; no other unit system explains it: check the mesh and the material data";
}

std::string peak_pressure_warning(double peak, const std::string& table) {
  if (peak >= kMinPeakPressure && peak <= kMaxPeakPressure) return "";
  const PlausibleRange r{"",    "",    Q::Pressure, kMinPeakPressure, kMaxPeakPressure, false,
                         false, false, ""};
  std::string w = "the cylinder pressure " + table + " peaks at " + num(peak) +
                  " Pa, outside the plausible " + num(kMinPeakPressure) + " .. " +
                  num(kMaxPeakPressure) + " Pa of a cylinder (5 to 400 bar): pressures are in Pa";
  if (const Slip* s = best_slip(r, peak, slips(Q::Pressure)))
    return w + " (a table in " + s->unit + " would peak at " + num(peak * s->factor) + " Pa)";
  return w;
}

}  // namespace evas
