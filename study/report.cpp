// Output helpers of the studies (report.h).
#include "study/report.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>

namespace evas::study {

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

std::string md_cell(const std::string& s, std::size_t max_len) {
  std::string out;
  std::size_t n = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (max_len && n >= max_len) {
      out += "...";
      break;
    }
    const char c = s[i];
    if (c == '|')
      out += "\\|";
    else if (c == '\n' || c == '\r')
      out += ' ';
    else
      out += c;
    ++n;
  }
  return out;
}

std::string sci(double x, int digits) {
  if (std::isnan(x)) return "";
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*e", digits, x);
  return buf;
}

std::string gnum(double x, int digits) {
  if (std::isnan(x)) return "";
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*g", digits, x);
  return buf;
}

std::string inum(double x) {
  if (std::isnan(x)) return "";
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.0f", x);
  return buf;
}

void write_file_atomic(const std::filesystem::path& path, const std::string& text) {
  const std::filesystem::path tmp = path.string() + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw RunError(tmp.string() + ": cannot write");
    out << text;
    out.close();
    if (!out) throw RunError(tmp.string() + ": write failed");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw RunError(path.string() + ": cannot replace: " + ec.message());
}

}  // namespace evas::study
