// CalculiX import (see calculix.h and docs/fe-pipeline.md): unit systems and
// the helpers the readers share (calculix_common.h). The .inp deck is read in
// calculix_inp.cpp, the matrix storage in calculix_matrix.cpp, the .frd and
// .dat results in calculix_results.cpp, the ModalBody from ccx's eigenmodes is
// assembled in calculix_body.cpp.
#include "io/calculix.h"

#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "io/calculix_common.h"

namespace evas {

namespace calculix_detail {

std::string upper(std::string s) {
  for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

std::string trim(const std::string& s) {
  std::size_t a = 0, b = s.size();
  while (a < b && std::isspace(static_cast<unsigned char>(s[a]))) ++a;
  while (b > a && std::isspace(static_cast<unsigned char>(s[b - 1]))) --b;
  return s.substr(a, b - a);
}

[[noreturn]] void fail_at(const std::string& file, long line, const std::string& what) {
  std::ostringstream os;
  os << file;
  if (line > 0) os << ":" << line;
  os << ": " << what;
  throw InputError(os.str());
}

void check_input_file(const std::string& path) {
  std::error_code ec;
  const auto st = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(st)) fail_at(path, 0, "cannot open the file (no such file)");
  if (!std::filesystem::is_regular_file(st))
    fail_at(path, 0, "not a regular file (a folder, device or pipe)");
  const auto bytes = std::filesystem::file_size(path, ec);
  if (!ec && bytes > kMaxFileBytes)
    fail_at(path, 0,
            "the file is " + std::to_string(bytes) + " bytes, more than the limit of " +
                std::to_string(kMaxFileBytes) + " bytes (4 GiB)");
}

bool parse_long(const std::string& s, long& v) {
  if (s.empty()) return false;
  char* end = nullptr;
  v = std::strtol(s.c_str(), &end, 10);
  while (end && *end && std::isspace(static_cast<unsigned char>(*end))) ++end;
  return end && *end == '\0';
}

bool parse_double(const std::string& s, double& v) {
  if (s.empty()) return false;
  char* end = nullptr;
  v = std::strtod(s.c_str(), &end);
  while (end && *end && std::isspace(static_cast<unsigned char>(*end))) ++end;
  return end && *end == '\0' && end != s.c_str();
}

}  // namespace calculix_detail

namespace {

using calculix_detail::trim;
using calculix_detail::upper;

}  // namespace

UnitSystem unit_system(const std::string& name) {
  const std::string n = upper(trim(name));
  if (n == "SI" || n == "M-KG-S" || n == "M-KG-S-N") return {1.0, 1.0};
  if (n == "MM-T-S" || n == "MM-T-S-N" || n == "MM-T-S-N-MPA") return {1e-3, 1e3};
  if (n == "MM-KG-S") return {1e-3, 1.0};
  throw InputError("unknown unit system '" + name + "' (known: SI, m-kg-s, mm-t-s, mm-kg-s)");
}

}  // namespace evas
