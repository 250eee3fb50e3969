#include "elements/gas_pressure.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace evas {

namespace {

constexpr double kPeriodDeg = 720.0;
constexpr double kAtmosphere = 101325.0;  // [Pa], lowest gauge pressure (vacuum)
constexpr double kDegPerRad = 180.0 / M_PI;

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r\n");
  return s.substr(b, e - b + 1);
}

std::string fmt(double x) {
  std::ostringstream os;
  os << std::setprecision(10) << x;
  return os.str();
}

// Location of point k for messages: "file:line" when lines are known, else
// "where: point k".
struct Locator {
  const std::string& where;
  const std::vector<int>* lines;
  std::string operator()(std::size_t k) const {
    if (lines) return where + ":" + std::to_string((*lines)[k]);
    return where + ": point " + std::to_string(k + 1);
  }
};

// Checks a table and drops a closing duplicate row at first + 720 deg.
void validate(std::vector<double>& a, std::vector<double>& p, std::vector<int>* lines,
              const std::string& where, double max_gap) {
  Locator at{where, lines};
  if (a.size() != p.size())
    throw InputError(where + ": " + std::to_string(a.size()) + " angles but " +
                     std::to_string(p.size()) + " pressures");
  for (std::size_t k = 0; k < a.size(); ++k) {
    if (!std::isfinite(a[k])) throw InputError(at(k) + ": crank angle is not finite");
    if (!std::isfinite(p[k])) throw InputError(at(k) + ": pressure is not finite");
    if (std::abs(p[k]) > PressureTable::kMaxPressure)
      throw InputError(at(k) + ": pressure " + fmt(p[k]) + " Pa is beyond the limit of " +
                       fmt(PressureTable::kMaxPressure) +
                       " Pa (1e5 bar) for a cylinder pressure: wrong unit or corrupt table?");
  }
  if (a.size() >= 2 && std::abs(a.back() - (a.front() + kPeriodDeg)) < 1e-9) {
    // Optional closing row repeating the first point one period later.
    const double tol = 1e-6 * std::max(1.0, std::abs(p.front()));
    if (std::abs(p.back() - p.front()) > tol)
      throw InputError(at(a.size() - 1) + ": closing row at " + fmt(a.back()) +
                       " deg has pressure " + fmt(p.back()) + " Pa, but the cycle is periodic " +
                       "and the first row (" + fmt(a.front()) + " deg) has " + fmt(p.front()) +
                       " Pa");
    a.pop_back();
    p.pop_back();
    if (lines) lines->pop_back();
  }
  if (a.front() < 0.0)
    throw InputError(at(0) + ": crank angle " + fmt(a.front()) +
                     " deg is negative; the table must cover [0, 720) deg (0 = firing TDC)");
  for (std::size_t k = 1; k < a.size(); ++k) {
    if (!(a[k] > a[k - 1]))
      throw InputError(at(k) + ": crank angle " + fmt(a[k]) +
                       " deg is not greater than the previous one (" + fmt(a[k - 1]) +
                       " deg): angles must increase strictly");
    if (a[k] >= kPeriodDeg)
      throw InputError(at(k) + ": crank angle " + fmt(a[k]) +
                       " deg is not below 720 deg; the table must cover [0, 720) deg");
    if (a[k] - a[k - 1] > max_gap)
      throw InputError(at(k) + ": gap of " + fmt(a[k] - a[k - 1]) + " deg between " +
                       fmt(a[k - 1]) + " and " + fmt(a[k]) + " deg exceeds the largest " +
                       "accepted spacing of " + fmt(max_gap) + " deg");
  }
  if (a.front() >= kPeriodDeg)
    throw InputError(at(0) + ": crank angle " + fmt(a.front()) +
                     " deg is not below 720 deg; the table must cover [0, 720) deg");
  if (a.size() < 4)
    throw InputError(where +
                     ": a pressure table needs at least 4 points over the 720 deg cycle, "
                     "got " +
                     std::to_string(a.size()));
  const double wrap = a.front() + kPeriodDeg - a.back();
  if (wrap > max_gap)
    throw InputError(where + ": the table does not cover the whole cycle: gap of " + fmt(wrap) +
                     " deg from the last angle (" + fmt(a.back()) + " deg) round to the first (" +
                     fmt(a.front()) + " deg + 720) exceeds the largest accepted spacing of " +
                     fmt(max_gap) + " deg");
}

}  // namespace

PressureTable::PressureTable(std::vector<double> angle_deg, std::vector<double> p_Pa,
                             const std::string& where, double max_gap_deg)
    : angle_(std::move(angle_deg)), p_(std::move(p_Pa)) {
  validate(angle_, p_, nullptr, where, max_gap_deg);
  build();
}

PressureTable PressureTable::read(const std::string& path, double max_gap_deg) {
  // Size and kind before reading: a device or pipe (/dev/zero) never ends.
  std::error_code ec;
  const auto st = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(st))
    throw InputError(path + ": cannot open the pressure table (no such file)");
  if (!std::filesystem::is_regular_file(st))
    throw InputError(path + ": the pressure table is not a regular file (a folder, device or " +
                     "pipe); give a text file");
  const auto bytes = std::filesystem::file_size(path, ec);
  if (!ec && bytes > static_cast<std::uintmax_t>(kMaxFileBytes))
    throw InputError(path + ": the pressure table is " + std::to_string(bytes) +
                     " bytes, more than the limit of " + std::to_string(kMaxFileBytes) +
                     " bytes (64 MiB)");
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the pressure table");
  double scale = 0.0;  // Pa per file unit; 0 until the unit header is seen
  bool gauge = false;  // "# unit: bar gauge": relative to the atmosphere
  std::string unit;    // as written, for messages
  std::vector<double> a, p;
  std::vector<int> lines;
  std::string line;
  int no = 0;
  while (std::getline(in, line)) {
    ++no;
    // the place for a message, formed only when one is thrown (a table has
    // thousands of rows)
    const auto here = [&] { return path + ":" + std::to_string(no); };
    const auto hash = line.find('#');
    if (hash != std::string::npos) {
      const std::string comment = trim(line.substr(hash + 1));
      const std::string lc = lower(comment);
      if (lc.rfind("unit", 0) == 0) {
        auto colon = comment.find(':');
        if (colon == std::string::npos) colon = comment.find('=');
        if (colon == std::string::npos)
          throw InputError(here() + ": unit header must read '# unit: bar' (or kPa, MPa, Pa)");
        std::string u = lower(trim(comment.substr(colon + 1)));
        if (!a.empty())
          throw InputError(here() + ": the unit header must come before the first data row");
        for (const std::string& g : {std::string(" gauge"), std::string(" (gauge)")})
          if (u.size() > g.size() && u.compare(u.size() - g.size(), g.size(), g) == 0) {
            gauge = true;
            u = trim(u.substr(0, u.size() - g.size()));
          }
        unit = trim(comment.substr(colon + 1)).substr(0, u.size());  // without "gauge"
        if (u == "bar")
          scale = 1e5;
        else if (u == "kpa")
          scale = 1e3;
        else if (u == "mpa")
          scale = 1e6;
        else if (u == "pa")
          scale = 1.0;
        else
          throw InputError(here() + ": unknown pressure unit '" + trim(comment.substr(colon + 1)) +
                           "' (expected bar, kPa, MPa or Pa, optionally followed by 'gauge')");
      }
      line = line.substr(0, hash);
    }
    for (char& c : line)
      if (c == ',' || c == ';' || c == '\t' || c == '\r') c = ' ';
    // fields: runs of characters other than spaces (the separators above are spaces now)
    std::string tok[2];
    std::size_t nfields = 0;
    for (std::size_t i = 0; i < line.size();) {
      if (std::isspace(static_cast<unsigned char>(line[i]))) {
        ++i;
        continue;
      }
      std::size_t j = i;
      while (j < line.size() && !std::isspace(static_cast<unsigned char>(line[j]))) ++j;
      if (nfields < 2) tok[nfields].assign(line, i, j - i);
      ++nfields;
      i = j;
    }
    if (nfields == 0) continue;
    if (nfields != 2)
      throw InputError(here() + ": expected two numbers 'crank_angle_deg pressure', got " +
                       std::to_string(nfields) + " fields: '" + trim(line) + "'");
    double v[2];
    for (int i = 0; i < 2; ++i) {
      const char* s = tok[i].c_str();
      char* end = nullptr;
      errno = 0;
      v[i] = std::strtod(s, &end);
      if (end == s || *end != '\0')
        throw InputError(here() + ": '" + tok[i] + "' is not a number (" +
                         (i == 0 ? "crank angle" : "pressure") + ")");
      if (!std::isfinite(v[i]))
        throw InputError(here() + ": " + (i == 0 ? "crank angle" : "pressure") + " '" + tok[i] +
                         "' is not finite");
    }
    if (scale == 0.0)
      throw InputError(here() +
                       ": data before the unit header; start the file with '# unit: bar' "
                       "(or kPa, MPa, Pa)");
    const double pa = v[1] * scale;
    if (std::abs(pa) > kMaxPressure)
      throw InputError(here() + ": pressure " + tok[1] + " " + unit + " (" + fmt(pa) +
                       " Pa) is beyond the limit of " + fmt(kMaxPressure) +
                       " Pa (1e5 bar) for a cylinder pressure: wrong unit or corrupt table?");
    if (!gauge && pa < 0.0)
      throw InputError(here() + ": pressure " + tok[1] + " " + unit +
                       " is negative, but the table holds absolute pressures (write '# unit: " +
                       unit + " gauge' for pressures relative to the atmosphere)");
    if (gauge && pa < -kAtmosphere)
      throw InputError(here() + ": gauge pressure " + tok[1] + " " + unit +
                       " is below vacuum (-1 atm = -101325 Pa): the absolute pressure would be "
                       "negative");
    a.push_back(v[0]);
    p.push_back(pa);
    lines.push_back(no);
  }
  if (a.empty()) throw InputError(path + ": no data rows in the pressure table");
  PressureTable t;
  t.angle_ = std::move(a);
  t.p_ = std::move(p);
  validate(t.angle_, t.p_, &lines, path, max_gap_deg);
  t.build();
  return t;
}

void PressureTable::build() {
  const std::size_t n = angle_.size();
  // A table of equal spacing (to 1e-9 of a step) is entered by division, not
  // by bisection (operator(); the same interval either way).
  step_ = n >= 2 ? (angle_[n - 1] - angle_[0]) / static_cast<double>(n - 1) : 0.0;
  for (std::size_t k = 1; k < n && step_ > 0.0; ++k)
    if (std::abs(angle_[k] - angle_[k - 1] - step_) > 1e-9 * step_) step_ = 0.0;
  // Periodic PCHIP slopes (Fritsch-Butland weighted harmonic mean; zero at
  // local extrema and where neighbouring secants change sign).
  slope_.assign(n, 0.0);
  auto h = [&](std::size_t k) {  // spacing from knot k to k+1 (wrapping)
    return k + 1 < n ? angle_[k + 1] - angle_[k] : angle_[0] + kPeriodDeg - angle_[n - 1];
  };
  auto secant = [&](std::size_t k) { return (p_[(k + 1) % n] - p_[k]) / h(k); };
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t km = (k + n - 1) % n;
    const double h0 = h(km), h1 = h(k), d0 = secant(km), d1 = secant(k);
    if (d0 * d1 <= 0.0) continue;
    const double w1 = 2.0 * h1 + h0, w2 = h1 + 2.0 * h0;
    slope_[k] = (w1 + w2) / (w1 / d0 + w2 / d1);
  }
}

double PressureTable::operator()(double theta, double* dp_dtheta) const {
  const std::size_t n = angle_.size();
  double x = std::fmod(theta * kDegPerRad - angle_[0], kPeriodDeg);
  if (x < 0.0) x += kPeriodDeg;
  x += angle_[0];
  std::size_t k;
  if (step_ > 0.0) {  // uniform table: the interval from the angle, then made exact
    const double g = std::floor((x - angle_[0]) / step_);
    k = g <= 0.0 ? 0 : std::min(static_cast<std::size_t>(g), n - 1);
    while (k + 1 < n && angle_[k + 1] <= x) ++k;
    while (k > 0 && angle_[k] > x) --k;
  } else {
    k = std::upper_bound(angle_.begin(), angle_.end(), x) - angle_.begin();
    k = k == 0 ? 0 : k - 1;
  }
  const std::size_t k1 = (k + 1) % n;
  const double x0 = angle_[k];
  const double h = k + 1 < n ? angle_[k + 1] - x0 : angle_[0] + kPeriodDeg - x0;
  const double t = (x - x0) / h;
  const double t2 = t * t, t3 = t2 * t;
  const double p0 = p_[k], p1 = p_[k1], m0 = slope_[k] * h, m1 = slope_[k1] * h;
  const double val = (2 * t3 - 3 * t2 + 1) * p0 + (t3 - 2 * t2 + t) * m0 + (-2 * t3 + 3 * t2) * p1 +
                     (t3 - t2) * m1;
  if (dp_dtheta) {
    const double dt = (6 * t2 - 6 * t) * p0 + (3 * t2 - 4 * t + 1) * m0 + (-6 * t2 + 6 * t) * p1 +
                      (3 * t2 - 2 * t) * m1;
    *dp_dtheta = dt / h * kDegPerRad;  // per deg -> per rad
  }
  return val;
}

double PressureTable::max_pressure() const {
  return p_.empty() ? 0.0 : *std::max_element(p_.begin(), p_.end());
}

void PressureTable::write(const std::string& path, const std::string& comment) const {
  std::ofstream out(path);
  if (!out) throw InputError(path + ": cannot write the pressure table");
  out << "# unit: bar\n";
  std::istringstream cs(comment);
  for (std::string l; std::getline(cs, l);) out << "# " << l << "\n";
  out << "# crank_angle_deg  pressure_bar   (cycle angle, 0 = firing TDC, period 720 deg)\n";
  out << std::fixed;
  for (std::size_t k = 0; k < angle_.size(); ++k)
    out << std::setprecision(2) << std::setw(7) << angle_[k] << "  " << std::setprecision(6)
        << std::setw(12) << p_[k] / 1e5 << "\n";
  if (!out) throw InputError(path + ": write failed");
}

// ---------------------------------------------------------------------------
// Synthetic diesel cycle.

namespace {

struct CycleModel {
  const DieselCycle& c;
  double A, R, L, Vc;

  explicit CycleModel(const DieselCycle& cyc) : c(cyc) {
    A = M_PI / 4 * c.bore * c.bore;
    R = c.stroke / 2;
    L = c.conrod;
    Vc = A * c.stroke / (c.compression_ratio - 1.0);
  }
  // Volume and dV/dtheta (theta in rad, 0 = TDC).
  void volume(double th, double& V, double& dV) const {
    const double s = std::sin(th), co = std::cos(th);
    const double Lc = std::sqrt(L * L - R * R * s * s);
    const double xp = R * co + Lc;
    const double dxp = -R * s - R * R * s * co / Lc;
    V = Vc + A * (R + L - xp);
    dV = -A * dxp;
  }
  static double wiebe(double th, double th0, double dur, double a, double m, double& dx) {
    if (th <= th0) {
      dx = 0.0;
      return 0.0;
    }
    const double u = (th - th0) / dur;
    const double e = std::exp(-a * std::pow(u, m + 1));
    dx = a * (m + 1) / dur * std::pow(u, m) * e;
    return 1.0 - e;
  }
  // Burn fraction and its rate [1/rad].
  double burn(double th, double& dxb) const {
    const double d2r = M_PI / 180;
    double dp, dd;
    const double xp =
        wiebe(th, c.soc_deg * d2r, c.premixed_duration_deg * d2r, c.wiebe_a, c.premixed_m, dp);
    const double xd =
        wiebe(th, c.soc_deg * d2r, c.diffusion_duration_deg * d2r, c.wiebe_a, c.diffusion_m, dd);
    const double f = c.premixed_fraction;
    dxb = f * dp + (1 - f) * dd;
    return f * xp + (1 - f) * xd;
  }
  double rhs(double th, double p, double Q) const {
    double V, dV, dxb;
    volume(th, V, dV);
    const double xb = burn(th, dxb);
    const double g = c.n_compression + (c.n_expansion - c.n_compression) * xb;
    return (g - 1.0) / V * Q * dxb - g * p / V * dV;
  }
  // RK4 from IVC to EVO on a fine grid; returns pressures at ivc + k*h.
  std::vector<double> closed_cycle(double Q, double h_deg, double* peak, double* peak_at) const {
    const double d2r = M_PI / 180;
    const int n = static_cast<int>(std::lround((c.evo_deg - c.ivc_deg) / h_deg));
    std::vector<double> out(n + 1);
    double p = c.p_intake, th = c.ivc_deg * d2r;
    const double h = h_deg * d2r;
    out[0] = p;
    *peak = p;
    *peak_at = c.ivc_deg;
    for (int k = 0; k < n; ++k) {
      const double k1 = rhs(th, p, Q), k2 = rhs(th + h / 2, p + h / 2 * k1, Q);
      const double k3 = rhs(th + h / 2, p + h / 2 * k2, Q), k4 = rhs(th + h, p + h * k3, Q);
      p += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
      th += h;
      out[k + 1] = p;
      if (p > *peak) {
        *peak = p;
        *peak_at = c.ivc_deg + (k + 1) * h_deg;
      }
    }
    return out;
  }
};

}  // namespace

PressureTable synthetic_diesel_cycle(const DieselCycle& c, double* used_heat) {
  if (!(c.ivc_deg < 0 && c.ivc_deg > -360 && c.evo_deg > 0 && c.evo_deg < 180 && c.step_deg > 0 &&
        c.compression_ratio > 1 && c.conrod > c.stroke / 2))
    throw InputError("synthetic diesel cycle: inconsistent parameters");
  const CycleModel m(c);
  const double fine = std::min(0.05, c.step_deg);
  const int sub = std::max(1, static_cast<int>(std::lround(c.step_deg / fine)));
  const double h = c.step_deg / sub;
  double Q = c.heat_release, peak = 0.0, at = 0.0;
  if (c.target_peak > 0.0) {
    double lo = 0.0, hi = 1e3;
    m.closed_cycle(hi, h, &peak, &at);
    while (peak < c.target_peak && hi < 1e7) {
      hi *= 2;
      m.closed_cycle(hi, h, &peak, &at);
    }
    for (int it = 0; it < 80; ++it) {
      Q = 0.5 * (lo + hi);
      m.closed_cycle(Q, h, &peak, &at);
      (peak < c.target_peak ? lo : hi) = Q;
    }
  }
  const std::vector<double> closed = m.closed_cycle(Q, h, &peak, &at);
  if (used_heat) *used_heat = Q;
  const double p_evo = closed.back();
  // Gas exchange (cycle deg): blowdown EVO -> 240, exhaust stroke, valve
  // overlap 340 -> 380, intake stroke until IVC + 720; cosine blends.
  auto blend = [](double s) { return 0.5 * (1.0 - std::cos(M_PI * std::clamp(s, 0.0, 1.0))); };
  const double blow_end = 240.0, ovl0 = 340.0, ovl1 = 380.0;
  std::vector<double> a, p;
  const int n = static_cast<int>(std::lround(kPeriodDeg / c.step_deg));
  for (int k = 0; k < n; ++k) {
    const double ang = k * c.step_deg;
    double val;
    const double th = ang > 360.0 ? ang - kPeriodDeg : ang;  // (-360, 360]
    if (th >= c.ivc_deg && th <= c.evo_deg) {
      const long idx = std::lround((th - c.ivc_deg) / h);
      val = closed[std::clamp<long>(idx, 0, static_cast<long>(closed.size()) - 1)];
    } else if (ang < blow_end) {
      val = p_evo + (c.p_exhaust - p_evo) * blend((ang - c.evo_deg) / (blow_end - c.evo_deg));
    } else {
      val = c.p_exhaust + (c.p_intake - c.p_exhaust) * blend((ang - ovl0) / (ovl1 - ovl0));
    }
    a.push_back(ang);
    p.push_back(val);
  }
  return PressureTable(std::move(a), std::move(p), "synthetic diesel cycle");
}

DieselCycle diesel_cycle_at(const DieselCycle& ref, double ref_rpm, double ref_heat, double rpm,
                            double load) {
  if (!(rpm > 0.0 && std::isfinite(rpm)) || !(ref_rpm > 0.0))
    throw InputError("diesel cycle: the speed must be > 0 rpm, got " + std::to_string(rpm));
  if (!(load > 0.0 && load <= 1.5))
    throw InputError("diesel cycle: the load must be in (0, 1.5] (a fraction of full load), got " +
                     std::to_string(load));
  DieselCycle c = ref;
  const double r = rpm / ref_rpm;
  c.premixed_duration_deg = ref.premixed_duration_deg * std::sqrt(r);
  c.diffusion_duration_deg = ref.diffusion_duration_deg * std::sqrt(r);
  c.diffusion_m = ref.diffusion_m * std::pow(1.0 / r, 0.3);
  c.heat_release = load * ref_heat;
  c.target_peak = 0.0;
  constexpr double ambient = 1.0e5;
  const double boost = std::min(1.0, r * r);
  c.p_intake = ambient + (ref.p_intake - ambient) * boost;
  c.p_exhaust = c.p_intake + (ref.p_exhaust - ref.p_intake) * boost;
  return c;
}

}  // namespace evas
