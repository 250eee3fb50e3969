// Plausible ranges of element parameters and scene quantities: one table,
// separate from the hard validity ranges of the element registry (registry.h).
// A value outside its validity range cannot be run; a value outside its
// plausible range can, but is most likely a unit slip (millimetres typed for
// metres, rpm for rad/s, bar for Pa, centipoise for Pa s). Such a value draws a
// warning that names the value, the plausible range and the conversion that
// would bring it into range; where the run cannot mean anything (a clearance
// as large as the journal, a firing engine at rest) it is an error instead.
// `evas elements` prints the plausible ranges from this table.
#pragma once

#include <string>
#include <vector>

#include "elements/registry.h"

namespace evas {

/// What a parameter measures: decides the unit slips a warning suggests.
enum class Quantity {
  Length,
  Speed,
  Pressure,
  Viscosity,
  Mass,
  Stiffness,
  Damping,
  Force,
  Modulus,  ///< Pa, typed in MPa (N/mm^2) or GPa
  Density,  ///< kg/m^3, typed in g/cm^3 or t/mm^3
  Area      ///< m^2, typed in mm^2 or cm^2
};

struct PlausibleRange {
  std::string
      type;         ///< element type, "lof" for a spin LOF's speed, "generate" for a generated body
  std::string key;  ///< parameter
  Quantity quantity;
  double lo, hi;            ///< plausible magnitude range in SI units
  bool zero_ok = false;     ///< 0 is plausible too (a term switched off)
  bool first_only = false;  ///< only the first component (a polynomial's linear term)
  bool magnitude = false;   ///< the range bounds |x| (signed speeds)
  std::string what;         ///< "a journal bearing's radial clearance"
};

/// The table, in element order.
const std::vector<PlausibleRange>& plausible_ranges();
/// The entry for `type`.`key`, or nullptr.
const PlausibleRange* plausible_range(const std::string& type, const std::string& key);
/// "lo .. hi unit" of an entry, as `evas elements` prints it.
std::string plausible_text(const PlausibleRange& r);

/// "" when `x` lies in the entry's range, else a warning: the value, the
/// range and the unit slip that would explain it, e.g. "clearance = 40 m is
/// outside the plausible 2e-06 .. 0.0005 m of a journal bearing's radial
/// clearance: lengths are in metres (40 um would be 4e-05 m)".
std::string plausibility_warning(const PlausibleRange& r, double x);

/// The checks of one element's values: range warnings of every parameter in
/// the table (appended to `warnings`, each prefixed by `where`), then the
/// checks across parameters, which throw InputError naming `where` when the
/// combination cannot mean anything (a clearance not smaller than the radius).
void check_plausible(const ElementType& type, const ParamValues& values, const std::string& where,
                     std::vector<std::string>& warnings);

/// A part's mean density over its bounding box: from a hollow aluminium
/// casting filling a tenth of its box to solid steel (kg/m^3).
constexpr double kMinBoxDensity = 50.0, kMaxBoxDensity = 2e4;
/// A part's largest bounding-box side (m).
constexpr double kMinPartSize = 0.005, kMaxPartSize = 20.0;

/// One unit system a mesh may be written in: metres and kilograms per file unit.
struct MeshUnits {
  std::string name;
  double length, mass;
};

/// "" when a body of `mass` kg whose bounding box has sides `extent` (m), read
/// in `used`, has a plausible size and mean density; else a warning naming the
/// mass, the box, the density, and the unit system among `others` under which
/// the same files give a plausible part ("the mesh is likely in mm-t-s: a
/// 0.52 kg part 0.2 x 0.1 x 0.08 m").
std::string mesh_units_warning(double mass, const Vec3& extent, const MeshUnits& used,
                               const std::vector<MeshUnits>& others);

/// A piston's mass per cubic bore (kg/m^3): from a light car piston to a
/// heavy diesel one.
constexpr double kMinPistonDensity = 100.0, kMaxPistonDensity = 2e4;

/// A firing cylinder's peak pressure (Pa): from a motored cylinder to the
/// highest-loaded diesel. The check reads the table's peak, absolute or gauge.
constexpr double kMinPeakPressure = 5e5, kMaxPeakPressure = 4e7;

/// "" or a warning on a cylinder pressure table whose peak lies outside
/// kMinPeakPressure .. kMaxPeakPressure, naming the unit slip (bar, MPa).
std::string peak_pressure_warning(double peak, const std::string& table);

/// Steps above which a fixed-step run draws a warning before it starts.
constexpr double kMaxPlausibleSteps = 1e8;

}  // namespace evas
