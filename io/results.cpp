#include "io/results.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

#include "integrators/settings.h"

namespace evas {

namespace {

std::string number_text(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.10g", x);
  return buf;
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
  h5::Quiet quiet;
  try {
    file_ = h5::create_file(path_);
    h5::write_attribute(file_, "scene", opt_.scene_text);
    h5::write_attribute(file_, "integrator", opt_.integrator);
    h5::write_attribute(file_, "grid", opt_.grid);
    h5::write_attribute(file_, "status", std::string("running"));
    const hsize_t chunk = static_cast<hsize_t>(std::max(16, opt_.flush_rows));
    time_ = h5::create_extendible(file_, "time", 1, 1, chunk);
    h5::write_attribute(time_, "unit", std::string("s"));
    h5::Handle g = h5::create_group(file_, "channels");
    std::vector<std::string> names, units;
    for (const Channel& c : channels_) {
      names.push_back(c.name);
      units.push_back(c.unit);
    }
    h5::write_strings(g, "names", names);
    h5::write_strings(g, "units", units);
    if (nc > 0) {
      const hsize_t vchunk = std::max<hsize_t>(1, std::min<hsize_t>(chunk, 65536 / nc));
      values_ = h5::create_extendible(g, "values", 2, nc, vchunk);
    }
    H5Fflush(file_, H5F_SCOPE_GLOBAL);
  } catch (const h5::Failure& e) {
    throw RunError(path_ + ": " + e.what());
  }
  last_flush_ = std::chrono::steady_clock::now();
}

ResultsWriter::~ResultsWriter() {
  try {
    flush();
  } catch (...) {
    // Destructors must not throw; what was flushed before stays readable.
  }
  h5::Quiet quiet;
  values_.reset();
  time_.reset();
  file_.reset();
}

void ResultsWriter::append(double t, const double* values) {
  if (!file_.valid()) throw RunError(path_ + ": results file is already closed");
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
  const auto now = std::chrono::steady_clock::now();
  if (static_cast<int>(tbuf_.size()) >= opt_.flush_rows ||
      std::chrono::duration<double>(now - last_flush_).count() >= opt_.flush_seconds)
    flush();
}

void ResultsWriter::flush() {
  last_flush_ = std::chrono::steady_clock::now();
  if (!file_.valid() || tbuf_.empty()) return;
  h5::Quiet quiet;
  try {
    const hsize_t rows = tbuf_.size();
    if (values_.valid()) h5::append_rows(values_, channels_.size(), rows, vbuf_.data());
    // Time last: a reader that sees a time row also sees its values.
    h5::append_rows(time_, 1, rows, tbuf_.data());
    if (H5Fflush(file_, H5F_SCOPE_GLOBAL) < 0) throw h5::Failure("cannot flush the file");
  } catch (const h5::Failure& e) {
    tbuf_.clear();
    vbuf_.clear();
    throw RunError(path_ + ": " + e.what());
  }
  tbuf_.clear();
  vbuf_.clear();
}

void ResultsWriter::finish(const IntegratorStats& st, const std::string& status) {
  flush();
  if (!file_.valid()) return;
  h5::Quiet quiet;
  try {
    h5::Handle g = h5::exists(file_, "stats") ? h5::open_group(file_, "stats")
                                              : h5::create_group(file_, "stats");
    h5::write_attribute(g, "steps", static_cast<long long>(st.steps));
    h5::write_attribute(g, "residual_evals", static_cast<long long>(st.residual_evals));
    h5::write_attribute(g, "jacobian_evals", static_cast<long long>(st.jacobian_evals));
    h5::write_attribute(g, "linear_setups", static_cast<long long>(st.linear_setups));
    h5::write_attribute(g, "linear_solves", static_cast<long long>(st.linear_solves));
    h5::write_attribute(g, "nonlinear_iterations", static_cast<long long>(st.nonlinear_iterations));
    h5::write_attribute(g, "error_test_failures", static_cast<long long>(st.error_test_failures));
    h5::write_attribute(g, "convergence_failures", static_cast<long long>(st.convergence_failures));
    h5::write_attribute(g, "restarts", static_cast<long long>(st.restarts));
    h5::write_attribute(g, "refused_states", static_cast<long long>(st.refused_states));
    h5::write_attribute(g, "substeps", static_cast<long long>(st.substeps));
    h5::write_attribute(g, "max_step_iterations", static_cast<long long>(st.max_step_iterations));
    h5::write_attribute(g, "wall_seconds", st.wall_seconds);
    h5::write_attribute(g, "last_step", st.last_step);
    h5::write_attribute(g, "min_step", st.min_step);
    h5::write_attribute(g, "max_step", st.max_step);
    h5::write_attribute(g, "last_order", static_cast<long long>(st.last_order));
    h5::write_attribute(file_, "status", status);
    h5::write_attribute(file_, "rows", static_cast<long long>(rows_));
    g.reset();
    values_.reset();
    time_.reset();
    file_.reset();
  } catch (const h5::Failure& e) {
    throw RunError(path_ + ": " + e.what());
  }
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

namespace {

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (char ch : s) {
    const unsigned char c = static_cast<unsigned char>(ch);
    switch (ch) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\r':
        out += "\\r";
        break;
      case '\t':
        out += "\\t";
        break;
      default:
        if (c < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          out += buf;
        } else {
          out += ch;
        }
    }
  }
  return out + "\"";
}

std::string json_number(double x) {
  if (!std::isfinite(x)) return "null";
  if (x == 0.0) x = 0.0;  // no "-0"
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

}  // namespace

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
      << (k + 1 < table.size() ? ",\n" : "\n");
  }
  o << "  },\n";
  o << "  \"grid\": " << json_string(s.grid) << ",\n";
  o << "  \"status\": " << json_string(s.status) << ",\n";
  o << "  \"t_start\": " << json_number(s.t_start) << ",\n";
  o << "  \"t_end\": " << json_number(s.t_end) << ",\n";
  o << "  \"t_reached\": " << json_number(s.t_reached) << ",\n";
  o << "  \"rows\": " << s.rows << ",\n";
  o << "  \"stats\": {\n";
  o << "    \"steps\": " << st.steps << ",\n";
  o << "    \"residual_evals\": " << st.residual_evals << ",\n";
  o << "    \"jacobian_evals\": " << st.jacobian_evals << ",\n";
  o << "    \"linear_setups\": " << st.linear_setups << ",\n";
  o << "    \"linear_solves\": " << st.linear_solves << ",\n";
  o << "    \"nonlinear_iterations\": " << st.nonlinear_iterations << ",\n";
  o << "    \"error_test_failures\": " << st.error_test_failures << ",\n";
  o << "    \"convergence_failures\": " << st.convergence_failures << ",\n";
  o << "    \"restarts\": " << st.restarts << ",\n";
  o << "    \"refused_states\": " << st.refused_states << ",\n";
  o << "    \"substeps\": " << st.substeps << ",\n";
  o << "    \"max_step_iterations\": " << st.max_step_iterations << ",\n";
  o << "    \"wall_seconds\": " << json_number(st.wall_seconds) << ",\n";
  o << "    \"last_step\": " << json_number(st.last_step) << ",\n";
  o << "    \"min_step\": " << json_number(st.min_step) << ",\n";
  o << "    \"max_step\": " << json_number(st.max_step) << ",\n";
  o << "    \"last_order\": " << st.last_order << "\n";
  o << "  },\n";
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
  std::ofstream f(path);
  if (!f) throw RunError(path + ": cannot write the summary (directory missing or not writable?)");
  f << o.str();
  if (!f) throw RunError(path + ": error while writing the summary");
}

// ---------------------------------------------------------------------------
// Reading back.

ResultsData read_results(const std::string& path) {
  ResultsData d;
  h5::Quiet quiet;
  try {
    h5::Handle file = h5::open_file(path);
    for (const char* key : {"scene", "integrator", "grid", "status"}) {
      if (!h5::has_attribute(file, key)) continue;
      const std::string v = h5::read_string_attribute(file, key);
      if (std::string(key) == "scene") d.scene = v;
      if (std::string(key) == "integrator") d.integrator = v;
      if (std::string(key) == "grid") d.grid = v;
      if (std::string(key) == "status") d.status = v;
    }
    std::vector<hsize_t> dims;
    d.time = h5::read_doubles(file, "/time", dims);
    if (dims.size() != 1) throw h5::Failure("dataset '/time' must be one-dimensional");
    d.names = h5::read_strings(file, "/channels/names");
    d.units = h5::read_strings(file, "/channels/units");
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
  std::ofstream f(csvpath);
  if (!f) throw InputError(csvpath + ": cannot write the CSV file");
  f << "time[s]";
  for (std::size_t c = 0; c < d.names.size(); ++c)
    f << ',' << d.names[c] << '[' << d.units[c] << ']';
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
  if (!f) throw InputError(csvpath + ": error while writing the CSV file");
}

}  // namespace evas
