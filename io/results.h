// Results files, written while a run goes (HDF5):
//   /time               (nt,) extendible [s]
//   /channels/values    (nt x nc) extendible, row = one output time
//   /channels/names, /channels/units   (nc,) string datasets
//   root attributes     scene (the full scene text), integrator, grid ("time" or
//                       "crank-angle"), status ("running", "completed", "failed: ...")
//   /stats              group; integrator statistics as attributes (finish())
// Rows are buffered and flushed (extent + write + H5Fflush) every `flush_rows`
// rows or `flush_seconds` of wall time (checked by append() and by
// flush_if_due(), which a run calls between steps too), so a crash keeps what
// was computed. Non-finite values are never written: append() throws RunError.
//
// A full disk keeps the file valid, and a failed write does not crash (see
// io/write_guard.h): append() and flush() then throw RunError naming the file,
// the error and the rows the file keeps; finish() still writes the status (if
// the disk allows) and closes the file.
#pragma once

#include <chrono>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "integrators/integrator.h"
#include "io/hdf5_util.h"
#include "io/write_guard.h"
#include "model/element.h"

namespace evas {

/// Running statistics of one channel over the appended rows.
struct ChannelSummary {
  double min = 0.0, max = 0.0, rms = 0.0;
  long count = 0;
};

class ResultsWriter {
 public:
  struct Options {
    std::string scene_text;
    std::string integrator;
    std::string grid = "time";
    int flush_rows = 256;
    double flush_seconds = 1.0;
    /// Space kept allocated beyond the end of the file, so that a full disk stops
    /// the run while the file is complete [bytes]; -1: enough for one flush of
    /// rows, the close and a summary; 0: none.
    long long reserve_bytes = -1;
    /// Shuffle + deflate on the time and values datasets. Off by default: on
    /// the paper's engine (4,320 rows of 63 channels, generalized-alpha) the
    /// run without it takes 0.93 of the time (7 alternating pairs, median) for
    /// a file 23 % larger (2.26 against 1.83 MB): the channels are doubles
    /// that vary in their low bits.
    bool compress = false;
  };

  /// Creates (truncates) `path`. Throws RunError naming the file on failure.
  ResultsWriter(const std::string& path, std::vector<Channel> channels, const Options& opt);
  /// Flushes buffered rows and closes; the status stays "running" unless finish() was called.
  ~ResultsWriter();
  ResultsWriter(const ResultsWriter&) = delete;
  ResultsWriter& operator=(const ResultsWriter&) = delete;

  /// Buffers one row (size = number of channels). If any value is NaN/Inf the
  /// rows before it are flushed and RunError names the channel and the time.
  void append(double t, const double* values);
  void append(double t, const std::vector<double>& values) { append(t, values.data()); }
  /// Writes buffered rows and flushes the file.
  void flush();
  /// flush() if rows are buffered for `flush_seconds` or longer (cheap otherwise).
  void flush_if_due();
  /// Flushes, writes statistics and status, closes the file. When the final
  /// flush or these writes fail, the status written (if it can be) is
  /// "failed: <the write error>" unless `status` already reports a failure, the
  /// file is closed all the same, and RunError names the file and the error.
  void finish(const IntegratorStats& stats, const std::string& status);

  const std::string& path() const { return path_; }
  const std::vector<Channel>& channels() const { return channels_; }
  /// Rows appended, and the time of the last.
  long rows() const { return rows_; }
  double last_time() const { return last_t_; }
  /// Rows in the file (equal to rows() after a successful flush), and the time of the last.
  long rows_written() const { return written_; }
  double last_time_written() const { return written_t_; }
  /// Empty, or the first write failure (the file keeps rows_written() rows).
  const std::string& write_error() const { return broken_; }
  std::vector<ChannelSummary> summary() const;

 private:
  std::string path_;
  std::vector<Channel> channels_;
  template <class Step>
  bool write_step(Step&& step);
  void write_buffer(bool keep_space);
  void note_flush();
  [[noreturn]] void fail_on_write();
  void close_file() noexcept;
  std::string kept_text() const;

  Options opt_;
  std::unique_ptr<WriteGuard> guard_;  // before the handles: outlives them
  h5::Handle file_, time_, values_;
  std::vector<double> tbuf_, vbuf_;
  std::vector<double> min_, max_, sumsq_;
  long rows_ = 0, written_ = 0;
  double last_t_ = 0.0, written_t_ = 0.0;
  std::string broken_;
  bool reported_ = false;  // broken_ was thrown
  std::chrono::steady_clock::time_point last_flush_;
};

/// Everything write_summary_json reports.
struct RunSummary {
  std::string scene;
  std::string scene_path;
  std::string integrator;
  IntegratorSettings settings;
  std::string grid;
  std::string status;
  double t_start = 0.0, t_end = 0.0;  ///< requested
  double t_reached = 0.0;             ///< last output time written
  long rows = 0;
  double peak_memory_mb = 0.0;  ///< the process's peak resident memory (0: unknown)
  IntegratorStats stats;
  std::vector<Channel> channels;
  std::vector<ChannelSummary> channel_summary;
  /// Further members, written after "stats" in this order: (key, JSON value
  /// as text, e.g. the settledness of the run or a periodic solution's method).
  std::vector<std::pair<std::string, std::string>> extra;
};

/// Peak resident memory of this process so far [MB] (Linux: VmHWM of
/// /proc/self/status, the high-water mark of this program's own memory map);
/// 0 where it cannot be read.
double process_peak_memory_mb();

/// The instruction set evas was built for (-march: "x86-64-v3", or "x86-64"
/// for the baseline; CMakeLists.txt, EVAS_ARCH), recorded with results.
const char* build_arch();

/// Writes `s` as JSON to `path`. Throws RunError naming the file on failure.
void write_summary_json(const std::string& path, const RunSummary& s);

/// The contents of a results file.
struct ResultsData {
  std::vector<double> time;
  Mat values;  ///< nt x nc
  std::vector<std::string> names, units;
  std::string scene, integrator, grid, status;
};

/// Reads a (possibly partial) results file. Throws InputError naming the file.
ResultsData read_results(const std::string& path);

/// Writes a CSV with header `time[s],name[unit],...`. Throws InputError naming the file.
void export_csv(const std::string& h5path, const std::string& csvpath);

}  // namespace evas
