// Reading a bearing's load cycle: see load_cycle.h.
#include "io/load_cycle.h"

#include <cstdint>
#include <filesystem>
#include <fstream>

#include "model/types.h"

namespace evas {

namespace {

constexpr std::uintmax_t kMaxBytes = 64u << 20;  // 64 MiB: far beyond any cycle

std::string trimmed(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return {};
  return s.substr(a, s.find_last_not_of(" \t\r") - a + 1);
}

bool number(const std::string& text, double& v) {
  const std::string s = trimmed(text);
  if (s.empty()) return false;
  std::size_t used = 0;
  try {
    v = std::stod(s, &used);
  } catch (const std::exception&) {
    return false;
  }
  return used == s.size();
}

}  // namespace

LoadCycle read_load_cycle(const std::string& path) {
  std::error_code ec;
  const auto st = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(st))
    throw InputError(path + ": cannot open the load cycle (no such file)");
  if (!std::filesystem::is_regular_file(st))
    throw InputError(path + ": the load cycle is not a regular file (a folder, device or pipe)");
  if (std::filesystem::file_size(path, ec) > kMaxBytes)
    throw InputError(path + ": the load cycle is larger than 64 MiB");
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the load cycle");
  LoadCycle c;
  bool header = false;
  int no = 0;
  for (std::string line; std::getline(in, line);) {
    ++no;
    const std::string at = path + ":" + std::to_string(no);
    const std::string t = trimmed(line);
    if (t.empty() || t[0] == '#') continue;
    std::string fields[3];
    int n = 0;
    std::size_t from = 0;
    for (;;) {
      const std::size_t comma = t.find(',', from);
      if (n == 3) {
        n = 4;
        break;
      }
      fields[n++] = t.substr(from, comma == std::string::npos ? std::string::npos : comma - from);
      if (comma == std::string::npos) break;
      from = comma + 1;
    }
    if (!header) {
      if (n != 3 || trimmed(fields[0]) != "angle_deg" || trimmed(fields[1]) != "fx" ||
          trimmed(fields[2]) != "fy")
        throw InputError(at +
                         ": the header must read 'angle_deg,fx,fy' (crank angle in deg, "
                         "the load on the journal in N), got '" +
                         t.substr(0, 80) + "'");
      header = true;
      continue;
    }
    double v[3];
    if (n != 3)
      throw InputError(at + ": a row has three values (angle_deg, fx, fy), this one " +
                       (n > 3 ? std::string("more") : std::to_string(n)));
    for (int k = 0; k < 3; ++k)
      if (!number(fields[k], v[k]))
        throw InputError(at + ": '" + trimmed(fields[k]).substr(0, 40) + "' is not a number");
    c.angle_deg.push_back(v[0]);
    c.fx.push_back(v[1]);
    c.fy.push_back(v[2]);
  }
  if (!header) throw InputError(path + ": empty: no header 'angle_deg,fx,fy'");
  check_load_cycle(c, path);
  return c;
}

}  // namespace evas
