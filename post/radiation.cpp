#include "post/radiation.h"

#include <cmath>
#include <limits>
#include <sstream>

#include "model/types.h"

namespace evas {

double piston_radiation_efficiency(double f_hz, double radius, double c) {
  constexpr double pi = 3.14159265358979323846;
  const double ka = 2.0 * pi * f_hz * radius / c;
  if (!(ka > 0.0)) return 0.0;
  const double x = 2.0 * ka;
  if (x < 0.05) {
    // 1 - 2 J1(x)/x = x^2/8 - x^4/192 + x^6/9216 - ... (the difference cancels)
    const double x2 = x * x;
    return x2 / 8.0 - x2 * x2 / 192.0 + x2 * x2 * x2 / 9216.0;
  }
  return 1.0 - std::cyl_bessel_j(1.0, x) / ka;
}

double a_weighting_db(double f_hz) {
  if (!(f_hz > 0.0)) return -std::numeric_limits<double>::infinity();
  const double f1 = 20.598997, f2 = 107.65265, f3 = 737.86223, f4 = 12194.217;
  const double f2_ = f_hz * f_hz;
  const double ra =
      f4 * f4 * f2_ * f2_ /
      ((f2_ + f1 * f1) * std::sqrt((f2_ + f2 * f2) * (f2_ + f3 * f3)) * (f2_ + f4 * f4));
  return 20.0 * std::log10(ra) + 2.0;
}

std::string RadiationModel::describe() const {
  std::ostringstream os;
  os << "baffled piston of radius " << radius << " m (c = " << c << " m/s)";
  return os.str();
}

RadiationModel parse_radiation_model(const std::string& text, const std::string& who) {
  const std::string p = "piston:";
  RadiationModel m;
  if (text.compare(0, p.size(), p) == 0) {
    const std::string r = text.substr(p.size());
    try {
      std::size_t used = 0;
      m.radius = std::stod(r, &used);
      if (used != r.size()) m.radius = -1.0;
    } catch (const std::exception&) {
      m.radius = -1.0;
    }
    if (m.radius > 0.0 && std::isfinite(m.radius)) return m;
    throw InputError(who + " '" + text + "': the piston's radius must be a number > 0 [m]");
  }
  throw InputError(who + " '" + text +
                   "': the model known is piston:RADIUS (a baffled circular piston of that "
                   "radius in m, e.g. piston:0.2; sqrt(area / pi) for a surface of that area)");
}

}  // namespace evas
