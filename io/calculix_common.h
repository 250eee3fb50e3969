// Private to io/ (included by io/calculix*.cpp only): the text helpers, file
// checks and limits shared by the CalculiX readers. The readers are split by
// what they read: the .inp deck in calculix_inp.cpp, the matrix storage files
// (.sti, .mas, .dof) in calculix_matrix.cpp, the .frd and .dat results in
// calculix_results.cpp, the ModalBody from ccx's eigenmodes in
// calculix_body.cpp; unit systems and these helpers are in calculix.cpp.
#pragma once

#include <cstdint>
#include <string>

namespace evas::calculix_detail {

/// Largest accepted CalculiX file (4 GiB) and GENERATE range (entries).
constexpr std::uintmax_t kMaxFileBytes = 4ull << 30;
constexpr long kMaxGenerate = 10000000;

/// `s` in upper case (ASCII).
std::string upper(std::string s);
/// `s` without leading and trailing white space.
std::string trim(const std::string& s);
/// Throws InputError "<file>:<line>: <what>" ("<file>: <what>" if line <= 0).
[[noreturn]] void fail_at(const std::string& file, long line, const std::string& what);
/// Refuses, before opening, a missing path, anything but a regular file (a
/// device or pipe such as /dev/zero never ends) and a file above the limit.
void check_input_file(const std::string& path);
/// A whole decimal integer (trailing white space allowed) into `v`.
bool parse_long(const std::string& s, long& v);
/// A whole number (trailing white space allowed) into `v`.
bool parse_double(const std::string& s, double& v);

}  // namespace evas::calculix_detail
