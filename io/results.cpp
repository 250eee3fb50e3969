#include "io/results.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

#include "integrators/settings.h"
#include "io/hdf5_util.h"
#include "io/isolated_read.h"
#include "io/text_escape.h"

#ifndef EVAS_BUILD_ARCH  // set by CMakeLists.txt
#define EVAS_BUILD_ARCH "unknown"
#endif

namespace evas {

namespace {

std::string number_text(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.10g", x);
  return buf;
}

std::string errno_text() {
  const int e = errno;
  return e ? std::strerror(e) : "write error";
}

std::string errno_suffix() {
  const int e = errno;
  return e ? std::string(": ") + std::strerror(e) : std::string();
}

void flush_file(hid_t file) {
  if (H5Fflush(file, H5F_SCOPE_GLOBAL) < 0) throw h5::Failure("cannot flush the file");
}

// Space kept allocated beyond the end of the file (see io/write_guard.h): a
// chunk of each dataset rewritten (twice: compressed chunks move), a batch of
// rows, the metadata and close, and later the summary (~200 bytes a channel).
long long default_reserve(std::size_t nc, int flush_rows, hsize_t chunk, hsize_t vchunk) {
  const long long n = static_cast<long long>(nc);
  const long long chunks =
      2 * 8 * (static_cast<long long>(vchunk) * n + static_cast<long long>(chunk));
  return chunks + 8LL * (n + 1) * flush_rows + 64 * 1024 + 256 * n + 16 * 1024;
}

// Writes a whole file; the check after close() also catches a full disk on the last buffer.
void write_text_file(const std::string& path, const std::string& text, const char* what) {
  errno = 0;
  std::ofstream f(path);
  if (!f) throw RunError(path + ": cannot write " + what + ": " + errno_text());
  f << text;
  f.close();
  if (!f) throw RunError(path + ": cannot write " + what + ": " + errno_text());
}

}  // namespace

ResultsWriter::ResultsWriter(const std::string& path, std::vector<Channel> channels,
                             const Options& opt)
    : path_(path), channels_(std::move(channels)), opt_(opt) {
  const std::size_t nc = channels_.size();
  min_.assign(nc, std::numeric_limits<double>::infinity());
  max_.assign(nc, -std::numeric_limits<double>::infinity());
  sumsq_.assign(nc, 0.0);
  opt_.flush_rows = std::max(1, opt_.flush_rows);
  const hsize_t chunk = static_cast<hsize_t>(std::max(16, opt_.flush_rows));
  const hsize_t vchunk = nc > 0 ? std::max<hsize_t>(1, std::min<hsize_t>(chunk, 65536 / nc)) : 1;
  guard_ = std::make_unique<WriteGuard>(
      path_, opt_.reserve_bytes >= 0 ? opt_.reserve_bytes
                                     : default_reserve(nc, opt_.flush_rows, chunk, vchunk));
  const bool ok = write_step([&] {
    file_ = guard_->create_file();
    h5::write_attribute(file_, "scene", opt_.scene_text);
    h5::write_attribute(file_, "integrator", opt_.integrator);
    h5::write_attribute(file_, "grid", opt_.grid);
    h5::write_attribute(file_, "status", std::string("running"));
    time_ = h5::create_extendible(file_, "time", 1, 1, chunk, opt_.compress);
    h5::write_attribute(time_, "unit", std::string("s"));
    h5::Handle g = h5::create_group(file_, "channels");
    std::vector<std::string> names, units;
    for (const Channel& c : channels_) {
      names.push_back(c.name);
      units.push_back(c.unit);
    }
    h5::write_strings(g, "names", names);
    h5::write_strings(g, "units", units);
    if (nc > 0) values_ = h5::create_extendible(g, "values", 2, nc, vchunk, opt_.compress);
    flush_file(file_);
  });
  if (!ok && !file_.valid()) throw RunError(broken_);  // not even created
  if (ok) note_flush();  // a full disk shows here: the first row then fails the run
  last_flush_ = std::chrono::steady_clock::now();
}

ResultsWriter::~ResultsWriter() {
  try {
    flush();
  } catch (...) {
    // Destructors must not throw; what was flushed before stays readable.
  }
  close_file();
}

// One step of writing; false (and the first failure kept in broken_) when it
// failed: an HDF5 error, or a write the guard had to divert into memory.
template <class Step>
bool ResultsWriter::write_step(Step&& step) {
  if (guard_->failed()) return false;
  h5::Quiet quiet;
  errno = 0;
  try {
    step();
  } catch (const h5::Failure& e) {
    if (broken_.empty()) broken_ = "results file " + path_ + ": " + e.what() + errno_suffix();
    return false;
  }
  if (guard_->failed()) {
    if (broken_.empty())
      broken_ = "results file " + path_ + ": cannot write: " + std::strerror(guard_->error());
    return false;
  }
  return true;
}

// After a complete flush: keep the space for the next one, or stop here.
void ResultsWriter::note_flush() {
  const int err = guard_->after_flush(written_);
  if (err != 0 && broken_.empty())
    broken_ = "results file " + path_ + ": cannot write: " + std::strerror(err) +
              " (less than the " + std::to_string((guard_->bytes() + 1023) / 1024) +
              " kB the next rows may need are left)";
}

void ResultsWriter::close_file() noexcept {
  h5::Quiet quiet;
  values_.reset();
  time_.reset();
  file_.reset();
}

std::string ResultsWriter::kept_text() const {
  if (guard_->failed())
    return "; the file could not be completed: it keeps at most the " + std::to_string(written_) +
           " rows written before, with status 'running'";
  std::string s = "; the file keeps " + std::to_string(written_) + " rows";
  if (written_ > 0) s += " up to t = " + number_text(written_t_) + " s";
  return s;
}

void ResultsWriter::append(double t, const double* values) {
  if (!file_.valid()) throw RunError(path_ + ": results file is already closed");
  if (!broken_.empty()) fail_on_write();
  const std::size_t nc = channels_.size();
  if (!std::isfinite(t)) {
    flush();
    throw RunError("non-finite output time after t = " + number_text(last_t_) + " s");
  }
  for (std::size_t c = 0; c < nc; ++c) {
    if (!std::isfinite(values[c])) {
      flush();
      throw RunError("channel '" + channels_[c].name + "' is " +
                     (std::isnan(values[c]) ? "NaN" : "infinite") + " at t = " + number_text(t) +
                     " s");
    }
  }
  tbuf_.push_back(t);
  vbuf_.insert(vbuf_.end(), values, values + nc);
  for (std::size_t c = 0; c < nc; ++c) {
    min_[c] = std::min(min_[c], values[c]);
    max_[c] = std::max(max_[c], values[c]);
    sumsq_[c] += values[c] * values[c];
  }
  ++rows_;
  last_t_ = t;
  if (static_cast<int>(tbuf_.size()) >= opt_.flush_rows)
    flush();
  else
    flush_if_due();
}

void ResultsWriter::flush_if_due() {
  if (tbuf_.empty() || !broken_.empty()) return;
  const auto now = std::chrono::steady_clock::now();
  if (std::chrono::duration<double>(now - last_flush_).count() >= opt_.flush_seconds) flush();
}

void ResultsWriter::flush() { write_buffer(true); }

// keep_space: renew the space kept for the next rows (not after the last rows).
void ResultsWriter::write_buffer(bool keep_space) {
  last_flush_ = std::chrono::steady_clock::now();
  if (!file_.valid() || tbuf_.empty()) return;
  if (broken_.empty()) {
    const hsize_t first = static_cast<hsize_t>(written_);
    const hsize_t rows = tbuf_.size();
    const bool ok = write_step([&] {
      if (values_.valid()) h5::write_rows(values_, channels_.size(), first, rows, vbuf_.data());
      // Time last: a reader that sees a time row also sees its values.
      h5::write_rows(time_, 1, first, rows, tbuf_.data());
      flush_file(file_);
    });
    if (ok) {
      written_ += static_cast<long>(rows);
      written_t_ = tbuf_.back();
      if (keep_space) note_flush();
    }
  }
  tbuf_.clear();
  vbuf_.clear();
  if (!broken_.empty()) fail_on_write();
}

void ResultsWriter::fail_on_write() {
  reported_ = true;
  throw RunError(broken_ + kept_text());
}

void ResultsWriter::finish(const IntegratorStats& st, const std::string& status) {
  if (!file_.valid()) return;
  std::string error;
  try {
    write_buffer(false);  // the last rows: the space kept takes the statistics too
  } catch (const RunError& e) {
    error = e.what();
  }
  const bool failed_before = status.rfind("failed", 0) == 0;
  const std::string written_status = error.empty()   ? status
                                     : failed_before ? status + "; " + error
                                                     : "failed: " + error;
  const bool ok = write_step([&] {
    h5::Handle g = h5::exists(file_, "stats") ? h5::open_group(file_, "stats")
                                              : h5::create_group(file_, "stats");
    for (const StatField& f : stat_fields()) {
      if (f.integer)
        h5::write_attribute(g, f.name, static_cast<long long>(f.get(st)));
      else
        h5::write_attribute(g, f.name, f.get(st));
    }
    h5::write_attribute(file_, "status", written_status);
    h5::write_attribute(file_, "rows", static_cast<long long>(written_));
    flush_file(file_);
  });
  if (!ok && error.empty() && !reported_) error = broken_ + kept_text();
  close_file();
  guard_.reset();  // gives back the space kept for the next rows: the summary may need it
  if (!error.empty()) throw RunError(error);
}

std::vector<ChannelSummary> ResultsWriter::summary() const {
  std::vector<ChannelSummary> out(channels_.size());
  for (std::size_t c = 0; c < channels_.size(); ++c) {
    out[c].count = rows_;
    if (rows_ > 0) {
      out[c].min = min_[c];
      out[c].max = max_[c];
      out[c].rms = std::sqrt(sumsq_[c] / static_cast<double>(rows_));
    }
  }
  return out;
}

// ---------------------------------------------------------------------------
// Summary JSON (hand-written: a flat, stable layout that any tool can read).

double process_peak_memory_mb() {
  std::ifstream f("/proc/self/status");
  std::string line;
  while (std::getline(f, line))
    if (line.rfind("VmHWM:", 0) == 0) {
      std::istringstream is(line.substr(6));
      double kb = 0.0;
      if (is >> kb) return kb / 1024.0;
    }
  return 0.0;
}

const char* build_arch() { return EVAS_BUILD_ARCH; }

void write_summary_json(const std::string& path, const RunSummary& s) {
  std::ostringstream o;
  const IntegratorSettings& is = s.settings;
  const IntegratorStats& st = s.stats;
  o << "{\n";
  o << "  \"scene\": " << json_string(s.scene) << ",\n";
  o << "  \"scene_path\": " << json_string(s.scene_path) << ",\n";
  o << "  \"integrator\": " << json_string(s.integrator) << ",\n";
  o << "  \"settings\": {\n";
  const auto& table = integrator_settings();
  for (std::size_t k = 0; k < table.size(); ++k) {
    const SettingInfo& info = table[k];
    const std::string v = get_integrator_setting(is, info.key);
    const bool text = info.kind == "choice";
    o << "    " << json_string(info.key) << ": " << (text ? json_string(v) : v)
      << (k + 1 < table.size() || !is.own.empty() ? ",\n" : "\n");
  }
  // a plug-in's own settings (IntegratorSettings::own)
  std::size_t k_own = 0;
  for (const auto& [key, value] : is.own)
    o << "    " << json_string(key) << ": " << json_number(value)
      << (++k_own < is.own.size() ? ",\n" : "\n");
  o << "  },\n";
  // settings listed above that this method does not read (e.g. IDA's
  // max_steps in a generalized-alpha run), so that no one reads meaning into them
  o << "  \"settings_not_read\": [";
  const std::vector<std::string> unread = settings_not_read_by(s.integrator);
  for (std::size_t k = 0; k < unread.size(); ++k) o << (k ? ", " : "") << json_string(unread[k]);
  o << "],\n";
  o << "  \"grid\": " << json_string(s.grid) << ",\n";
  o << "  \"status\": " << json_string(s.status) << ",\n";
  o << "  \"t_start\": " << json_number(s.t_start) << ",\n";
  o << "  \"t_end\": " << json_number(s.t_end) << ",\n";
  o << "  \"t_reached\": " << json_number(s.t_reached) << ",\n";
  o << "  \"rows\": " << s.rows << ",\n";
  o << "  \"peak_memory_mb\": " << json_number(s.peak_memory_mb) << ",\n";
  // the -march evas was built for (CMakeLists.txt, EVAS_ARCH)
  o << "  \"build_arch\": " << json_string(build_arch()) << ",\n";
  o << "  \"stats\": {\n";
  o << stats_json_members(st, "    ") << "\n";
  o << "  },\n";
  for (const auto& [key, value] : s.extra) o << "  " << json_string(key) << ": " << value << ",\n";
  o << "  \"channels\": [";
  for (std::size_t c = 0; c < s.channels.size(); ++c) {
    o << (c ? ",\n" : "\n");
    o << "    {\"name\": " << json_string(s.channels[c].name)
      << ", \"unit\": " << json_string(s.channels[c].unit);
    if (c < s.channel_summary.size() && s.channel_summary[c].count > 0) {
      const ChannelSummary& cs = s.channel_summary[c];
      o << ", \"min\": " << json_number(cs.min) << ", \"max\": " << json_number(cs.max)
        << ", \"rms\": " << json_number(cs.rms);
    } else {
      o << ", \"min\": null, \"max\": null, \"rms\": null";
    }
    o << "}";
  }
  o << (s.channels.empty() ? "]\n" : "\n  ]\n");
  o << "}\n";
  write_text_file(path, o.str(), "the summary");
}

// ---------------------------------------------------------------------------
// Reading back.

ResultsData read_results(const std::string& path) {
  ResultsData d;
  h5::Quiet quiet;
  try {
    h5::Handle file = h5::open_file(path);
    std::vector<hsize_t> dims;
    d.time = h5::read_doubles(file, "/time", dims);
    if (dims.size() != 1) throw h5::Failure("dataset '/time' must be one-dimensional");
    // the variable-length strings in one child process (io/isolated_read.h):
    // the four attributes ("" when missing, "=" + value), the count of
    // channels, their names, their units
    const std::vector<std::string> text = h5::read_isolated(
        [&] {
          std::vector<std::string> v;
          for (const auto& a :
               h5::read_string_attributes(file, {"scene", "integrator", "grid", "status"}))
            v.push_back(a ? "=" + *a : "");
          const std::vector<std::string> names = h5::read_strings(file, "/channels/names");
          const std::vector<std::string> units = h5::read_strings(file, "/channels/units");
          v.push_back(std::to_string(names.size()));
          v.insert(v.end(), names.begin(), names.end());
          v.insert(v.end(), units.begin(), units.end());
          return v;
        },
        "the attributes and datasets '/channels/names', '/channels/units'");
    if (text.size() < 5) throw h5::Failure("the channel names cannot be read");
    auto attr = [&](std::size_t i) { return text[i].empty() ? "" : text[i].substr(1); };
    d.scene = attr(0);
    d.integrator = attr(1);
    d.grid = attr(2);
    d.status = attr(3);
    const std::size_t n_names = static_cast<std::size_t>(std::stoull(text[4]));
    if (n_names > text.size() - 5) throw h5::Failure("the channel names cannot be read");
    const auto names = text.begin() + 5;
    d.names.assign(names, names + static_cast<std::ptrdiff_t>(n_names));
    d.units.assign(names + static_cast<std::ptrdiff_t>(n_names), text.end());
    if (d.units.size() != d.names.size())
      throw h5::Failure("datasets '/channels/names' and '/channels/units' differ in length");
    const std::size_t nc = d.names.size(), nt = d.time.size();
    d.values.resize(static_cast<Eigen::Index>(nt), static_cast<Eigen::Index>(nc));
    if (nc > 0) {
      const std::vector<double> v = h5::read_doubles(file, "/channels/values", dims);
      if (dims.size() != 2 || dims[1] != nc || dims[0] < nt)
        throw h5::Failure(
            "dataset '/channels/values' does not match '/time' and the channel names");
      for (std::size_t r = 0; r < nt; ++r)
        for (std::size_t c = 0; c < nc; ++c)
          d.values(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = v[r * nc + c];
    }
  } catch (const h5::Failure& e) {
    throw InputError(path + ": " + e.what());
  }
  return d;
}

void export_csv(const std::string& h5path, const std::string& csvpath) {
  const ResultsData d = read_results(h5path);
  errno = 0;
  std::ofstream f(csvpath);
  if (!f) throw InputError(csvpath + ": cannot write the CSV file: " + errno_text());
  f << "time[s]";
  for (std::size_t c = 0; c < d.names.size(); ++c)
    f << ',' << csv_field(d.names[c] + '[' + d.units[c] + ']');
  f << '\n';
  char buf[40];
  for (std::size_t r = 0; r < d.time.size(); ++r) {
    std::snprintf(buf, sizeof buf, "%.12g", d.time[r]);
    f << buf;
    for (Eigen::Index c = 0; c < d.values.cols(); ++c) {
      const double x = d.values(static_cast<Eigen::Index>(r), c);
      std::snprintf(buf, sizeof buf, "%.12g", x == 0.0 ? 0.0 : x);
      f << ',' << buf;
    }
    f << '\n';
  }
  f.close();  // the last buffer reaches the disk here: check after it
  if (!f) throw InputError(csvpath + ": cannot write the CSV file: " + errno_text());
}

}  // namespace evas
