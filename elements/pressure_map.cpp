#include "elements/pressure_map.h"

#include <cmath>
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
}  // namespace

PressureMap::PressureMap(std::vector<Entry> entries, const std::string& where)
    : entries_(std::move(entries)), source_(where) {
  if (entries_.empty()) throw InputError(where + ": a pressure map needs at least one table");
  for (std::size_t i = 0; i < entries_.size(); ++i) {
    if (!(entries_[i].speed > 0.0) || !std::isfinite(entries_[i].speed))
      throw InputError(where + ": speed " + rpm_text(entries_[i].speed) +
                       " rpm must be positive and finite");
    if (i > 0 && !(entries_[i].speed > entries_[i - 1].speed))
      throw InputError(where + ": speeds must increase strictly (" +
                       rpm_text(entries_[i - 1].speed) + " rpm, then " +
                       rpm_text(entries_[i].speed) + " rpm)");
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
  std::vector<Entry> entries;
  std::string line;
  int number = 0;
  while (std::getline(f, line)) {
    ++number;
    const std::string at = path + ":" + std::to_string(number);
    const auto hash = line.find('#');
    if (hash != std::string::npos) line.erase(hash);
    std::istringstream is(line);
    double rpm = 0.0;
    std::string file, extra;
    if (!(is >> rpm)) {
      std::istringstream blank(line);
      if (blank >> extra)
        throw InputError(at + ": expected 'speed_rpm table_file', got '" + line + "'");
      continue;
    }
    if (!(is >> file) || (is >> extra))
      throw InputError(at + ": expected 'speed_rpm table_file', got '" + line + "'");
    std::filesystem::path p(file);
    if (p.is_relative()) p = dir / p;
    Entry e;
    e.speed = rpm * kRpm;
    try {
      e.table = PressureTable::read(p.string());
    } catch (const InputError& err) {
      throw InputError(at + ": " + err.what());
    }
    if (!entries.empty() && !(e.speed > entries.back().speed))
      throw InputError(at + ": speeds must increase strictly (" + rpm_text(entries.back().speed) +
                       " rpm, then " + rpm_text(e.speed) + " rpm)");
    entries.push_back(std::move(e));
  }
  return PressureMap(std::move(entries), path);
}

double PressureMap::operator()(double theta, double w) const {
  if (entries_.size() == 1 || w <= entries_.front().speed) return entries_.front().table(theta);
  if (w >= entries_.back().speed) return entries_.back().table(theta);
  std::size_t k = 0;
  while (entries_[k + 1].speed < w) ++k;
  const Entry &a = entries_[k], &b = entries_[k + 1];
  const double s = (w - a.speed) / (b.speed - a.speed);
  return (1.0 - s) * a.table(theta) + s * b.table(theta);
}

void PressureMap::check_covers(double w_lo, double w_hi, const std::string& where) const {
  if (entries_.size() == 1) return;  // one table: used at every speed
  // 1e-4 relative: "3000 rpm = 314.159 rad/s" is 2.6e-4 % below 3000 rpm
  const double tol = 1e-4 * max_speed();
  if (w_lo >= min_speed() - tol && w_hi <= max_speed() + tol) return;
  throw InputError(where + ": the pressure map " + source_ + " covers " + rpm_text(min_speed()) +
                   " .. " + rpm_text(max_speed()) + " rpm, but the crank turns at " +
                   rpm_text(w_lo) + " .. " + rpm_text(w_hi) + " rpm" +
                   (w_lo < 0.0 ? " (a map's speeds are positive: a piston's crank speed must not "
                                 "be negative)"
                               : " (add tables for the missing speeds)"));
}

}  // namespace evas
