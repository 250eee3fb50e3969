#include "elements/pressure_map.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace evas {

namespace {
constexpr double kRpm = M_PI / 30.0;  // rad/s per rpm

std::string rpm_text(double w) {
  std::ostringstream os;
  os.precision(6);
  os << w / kRpm;
  return os.str();
}

std::string load_text(double L) {
  std::ostringstream os;
  os.precision(6);
  os << L;
  return os.str();
}

// Linear in speed between the two tables that bracket w (the map without
// loads reads exactly this, as it did before loads existed).
double at_speed(const std::vector<PressureMap::Entry>& entries, double theta, double w) {
  if (entries.size() == 1 || w <= entries.front().speed) return entries.front().table(theta);
  if (w >= entries.back().speed) return entries.back().table(theta);
  std::size_t k = 0;
  while (entries[k + 1].speed < w) ++k;
  const PressureMap::Entry &a = entries[k], &b = entries[k + 1];
  const double s = (w - a.speed) / (b.speed - a.speed);
  return (1.0 - s) * a.table(theta) + s * b.table(theta);
}

const char* kNoLoad = "'speed_rpm table_file'";
const char* kWithLoad = "'speed_rpm load table_file'";
}  // namespace

void PressureMap::check_speeds(const std::vector<Entry>& entries, const std::string& where) const {
  if (entries.empty()) throw InputError(where + ": a pressure map needs at least one table");
  for (std::size_t i = 0; i < entries.size(); ++i) {
    if (!(entries[i].speed > 0.0) || !std::isfinite(entries[i].speed))
      throw InputError(where + ": speed " + rpm_text(entries[i].speed) +
                       " rpm must be positive and finite");
    if (i > 0 && !(entries[i].speed > entries[i - 1].speed))
      throw InputError(where + ": speeds must increase strictly (" +
                       rpm_text(entries[i - 1].speed) + " rpm, then " + rpm_text(entries[i].speed) +
                       " rpm)");
  }
}

PressureMap::PressureMap(std::vector<Entry> entries, const std::string& where) : source_(where) {
  check_speeds(entries, where);
  loads_.push_back(Load{0.0, std::move(entries)});
}

PressureMap::PressureMap(std::vector<Load> loads, const std::string& where)
    : loads_(std::move(loads)), has_loads_(true), source_(where) {
  if (loads_.empty()) throw InputError(where + ": a pressure map needs at least one table");
  for (std::size_t j = 0; j < loads_.size(); ++j) {
    if (!std::isfinite(loads_[j].load))
      throw InputError(where + ": load " + load_text(loads_[j].load) + " must be finite");
    if (j > 0 && !(loads_[j].load > loads_[j - 1].load))
      throw InputError(where + ": loads must increase strictly (" + load_text(loads_[j - 1].load) +
                       ", then " + load_text(loads_[j].load) + ")");
    check_speeds(loads_[j].entries, where + ": load " + load_text(loads_[j].load));
  }
}

PressureMap PressureMap::read(const std::string& path) {
  // kind and size before reading: a device or pipe (/dev/zero) never ends
  std::error_code ec;
  const auto st = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(st))
    throw InputError(path + ": cannot open the pressure map (no such file)");
  if (!std::filesystem::is_regular_file(st))
    throw InputError(path + ": the pressure map is not a regular file (a folder, device or pipe)");
  const auto bytes = std::filesystem::file_size(path, ec);
  if (!ec && bytes > (1u << 20))
    throw InputError(path + ": the pressure map is " + std::to_string(bytes) +
                     " bytes, more than the limit of 1 MiB");
  std::ifstream f(path);
  if (!f) throw InputError(path + ": cannot open the pressure map");
  const std::filesystem::path dir = std::filesystem::path(path).parent_path();
  std::vector<Entry> entries;  // without loads
  std::vector<Load> loads;     // with loads
  std::size_t columns = 0;     // of the first table line: 2 or 3, then every line's
  int first_line = 0;
  std::string line;
  int number = 0;
  while (std::getline(f, line)) {
    ++number;
    const std::string at = path + ":" + std::to_string(number);
    const auto hash = line.find('#');
    if (hash != std::string::npos) line.erase(hash);
    const std::string expected = columns == 2   ? kNoLoad
                                 : columns == 3 ? kWithLoad
                                                : std::string(kNoLoad) + " or " + kWithLoad;
    std::istringstream is(line);
    double rpm = 0.0;
    std::string extra;
    if (!(is >> rpm)) {
      std::istringstream blank(line);
      if (blank >> extra) throw InputError(at + ": expected " + expected + ", got '" + line + "'");
      continue;
    }
    std::vector<std::string> rest;
    while (rest.size() < 3 && is >> extra) rest.push_back(extra);
    if (rest.empty() || rest.size() > 2)
      throw InputError(at + ": expected " + expected + ", got '" + line + "'");
    if (columns == 0) {
      columns = rest.size() + 1;
      first_line = number;
    } else if (rest.size() + 1 != columns) {
      // a line without a load among lines with one (or the reverse) has no
      // load to group by: refused rather than guessed
      throw InputError(at + ": mixes " + kNoLoad + " and " + kWithLoad + " lines (line " +
                       std::to_string(first_line) + " has " + std::to_string(columns) +
                       " columns, this one " + std::to_string(rest.size() + 1) +
                       "): give every line a load, or none");
    }
    Entry e;
    e.speed = rpm * kRpm;
    if (columns == 3) {
      const std::string& word = rest[0];
      char* end = nullptr;
      const double L = std::strtod(word.c_str(), &end);
      if (end == word.c_str() || *end != '\0')
        throw InputError(at + ": load '" + word + "' is not a number (expected " + kWithLoad + ")");
      if (!std::isfinite(L)) throw InputError(at + ": load '" + word + "' must be finite");
      // the lines of one load together, loads in increasing order: each load's
      // speed interpolation is then one run of lines
      if (loads.empty() || L > loads.back().load) {
        loads.push_back(Load{L, {}});
      } else if (L < loads.back().load) {
        throw InputError(at + ": loads must increase (load " + load_text(L) + " after load " +
                         load_text(loads.back().load) +
                         "): give all lines of one load together, loads in increasing order");
      } else if (!(e.speed > loads.back().entries.back().speed)) {
        throw InputError(at + ": speeds must increase strictly within load " + load_text(L) + " (" +
                         rpm_text(loads.back().entries.back().speed) + " rpm, then " +
                         rpm_text(e.speed) + " rpm)");
      }
    }
    std::filesystem::path p(rest.back());
    if (p.is_relative()) p = dir / p;
    try {
      e.table = *PressureTable::read_cached(p.string());
    } catch (const InputError& err) {
      throw InputError(at + ": " + err.what());
    }
    if (columns == 3) {
      loads.back().entries.push_back(std::move(e));
      continue;
    }
    if (!entries.empty() && !(e.speed > entries.back().speed))
      throw InputError(at + ": speeds must increase strictly (" + rpm_text(entries.back().speed) +
                       " rpm, then " + rpm_text(e.speed) + " rpm)");
    entries.push_back(std::move(e));
  }
  if (columns == 3) return PressureMap(std::move(loads), path);
  return PressureMap(std::move(entries), path);
}

double PressureMap::operator()(double theta, double w) const {
  return at_speed(loads_.front().entries, theta, w);
}

double PressureMap::operator()(double theta, double w, double L) const {
  if (loads_.size() == 1 || L <= loads_.front().load)
    return at_speed(loads_.front().entries, theta, w);
  if (L >= loads_.back().load) return at_speed(loads_.back().entries, theta, w);
  std::size_t j = 0;
  while (loads_[j + 1].load < L) ++j;
  const Load &a = loads_[j], &b = loads_[j + 1];
  const double u = (L - a.load) / (b.load - a.load);
  return (1.0 - u) * at_speed(a.entries, theta, w) + u * at_speed(b.entries, theta, w);
}

double PressureMap::min_speed() const {
  double w = loads_.front().entries.front().speed;
  for (const Load& g : loads_) w = std::max(w, g.entries.front().speed);
  return w;
}

double PressureMap::max_speed() const {
  double w = loads_.front().entries.back().speed;
  for (const Load& g : loads_) w = std::min(w, g.entries.back().speed);
  return w;
}

void PressureMap::check_covers(double w_lo, double w_hi, const std::string& where) const {
  for (const Load& g : loads_) {
    if (g.entries.size() == 1) continue;  // one table: used at every speed
    const double lo = g.entries.front().speed, hi = g.entries.back().speed;
    // 1e-4 relative: "3000 rpm = 314.159 rad/s" is 2.6e-4 % below 3000 rpm
    const double tol = 1e-4 * hi;
    if (w_lo >= lo - tol && w_hi <= hi + tol) continue;
    throw InputError(where + ": the pressure map " + source_ +
                     (has_loads_ ? " at load " + load_text(g.load) : std::string()) + " covers " +
                     rpm_text(lo) + " .. " + rpm_text(hi) + " rpm, but the crank turns at " +
                     rpm_text(w_lo) + " .. " + rpm_text(w_hi) + " rpm" +
                     (w_lo < 0.0 ? " (a map's speeds are positive: a piston's crank speed must not "
                                   "be negative)"
                      : has_loads_ ? " (add tables for the missing speeds at this load)"
                                   : " (add tables for the missing speeds)"));
  }
}

void PressureMap::check_load(double L, const std::string& where) const {
  if (!has_loads_ || loads_.size() == 1) return;  // one load: used at every load
  // a tolerance of rounding only: a sweep's A..B:STEP may land an ulp past B
  const double tol = 1e-9 * (max_load() - min_load());
  if (L >= min_load() - tol && L <= max_load() + tol) return;
  throw InputError(where + ": operating_point.load = " + load_text(L) +
                   " is outside the loads of the pressure map " + source_ + ", " +
                   load_text(min_load()) + " .. " + load_text(max_load()) +
                   " (the map is not extrapolated: add tables at the missing loads)");
}

}  // namespace evas
