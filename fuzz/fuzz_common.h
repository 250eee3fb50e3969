// Shared helpers of the libFuzzer harnesses (docs/fuzzing.md).
//
// Every harness writes the input bytes to a file in a private temporary folder
// (created once per process under $TMPDIR, removed at exit) and calls one
// reader on it. evas::InputError and evas::RunError are the documented answer
// to bad input and are caught; anything else -- another exception, a crash, a
// sanitizer report, a timeout, a leak -- escapes and is a finding.
//
// A skip list (environment variable EVAS_FUZZ_SKIP: a file of FNV-1a 64-bit
// hashes in hex, one per line, '#' comments) lets known crashes that are not
// evas's to fix (e.g. inside libhdf5) be passed over: such inputs return at once.
#pragma once

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "model/types.h"

namespace evas_fuzz {

inline std::uint64_t fnv1a(const std::uint8_t* data, std::size_t size) {
  std::uint64_t h = 1469598103934665603ull;
  for (std::size_t i = 0; i < size; ++i) {
    h ^= data[i];
    h *= 1099511628211ull;
  }
  return h;
}

inline const std::set<std::uint64_t>& skip_list() {
  static const std::set<std::uint64_t> list = [] {
    std::set<std::uint64_t> s;
    const char* file = std::getenv("EVAS_FUZZ_SKIP");
    if (!file || !*file) return s;
    std::ifstream in(file);
    std::string line;
    while (std::getline(in, line)) {
      const auto hash = line.find('#');
      if (hash != std::string::npos) line.erase(hash);
      std::istringstream is(line);
      std::string word;
      if (is >> word) s.insert(std::strtoull(word.c_str(), nullptr, 16));
    }
    return s;
  }();
  return list;
}

/// True if the input is on the skip list.
inline bool skipped(const std::uint8_t* data, std::size_t size) {
  const auto& s = skip_list();
  return !s.empty() && s.count(fnv1a(data, size)) > 0;
}

/// The process's private temporary folder (removed at normal exit).
inline const std::filesystem::path& temp_dir() {
  static const std::filesystem::path dir = [] {
    const char* t = std::getenv("TMPDIR");
    std::string pattern = std::string(t && *t ? t : "/tmp") + "/evas-fuzz-XXXXXX";
    std::vector<char> buf(pattern.begin(), pattern.end());
    buf.push_back('\0');
    if (!mkdtemp(buf.data())) {
      std::perror("mkdtemp");
      std::abort();
    }
    std::filesystem::path p(buf.data());
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(temp_dir(), ec);
    });
    return p;
  }();
  return dir;
}

/// Writes bytes to `path` (creating its folder), overwriting.
inline void write_file(const std::filesystem::path& path, const std::uint8_t* data,
                       std::size_t size) {
  std::filesystem::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  if (!out) {
    std::fprintf(stderr, "cannot write %s\n", path.c_str());
    std::abort();
  }
}

inline void write_file(const std::filesystem::path& path, const std::string& text) {
  write_file(path, reinterpret_cast<const std::uint8_t*>(text.data()), text.size());
}

/// Splits `text` at every line that is exactly `sep` (the multi-file inputs).
inline std::vector<std::string> split_parts(const std::string& text, const std::string& sep) {
  std::vector<std::string> parts(1);
  std::size_t pos = 0;
  while (pos <= text.size()) {
    std::size_t eol = text.find('\n', pos);
    const bool last = eol == std::string::npos;
    if (last) eol = text.size();
    std::string line = text.substr(pos, eol - pos);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line == sep)
      parts.emplace_back();
    else
      parts.back() += text.substr(pos, eol - pos) + (last ? "" : "\n");
    if (last) break;
    pos = eol + 1;
  }
  return parts;
}

/// Runs `f`; the expected errors of bad input are swallowed, anything else escapes.
/// EVAS_FUZZ_VERBOSE=1 prints the outcome of each input (to check seeds).
template <class F>
void expect_only_input_errors(F&& f) {
  static const bool verbose = std::getenv("EVAS_FUZZ_VERBOSE") != nullptr;
  try {
    f();
    if (verbose) std::fprintf(stderr, "evas-fuzz: accepted\n");
  } catch (const evas::InputError& e) {
    if (verbose) std::fprintf(stderr, "evas-fuzz: InputError: %s\n", e.what());
  } catch (const evas::RunError& e) {
    if (verbose) std::fprintf(stderr, "evas-fuzz: RunError: %s\n", e.what());
  }
}

}  // namespace evas_fuzz
