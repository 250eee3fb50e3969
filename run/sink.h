// Where the rows of a run go (run/run.h): the results file of `evas run`,
// memory for studies, NumPy arrays for Python. A sink also sees the run
// between its steps, to stop it on request or to show progress.
#pragma once

#include <exception>
#include <vector>

#include "integrators/integrator.h"
#include "io/outputs.h"

namespace evas::run {

/// Thrown by a sink (from row() or between_steps()) to end a run as completed
/// before its end time, e.g. when its last two cycles agree (evas run
/// --until-settled): the outcome is "completed" and the rows so far are kept.
class EndRun : public std::exception {
 public:
  const char* what() const noexcept override { return "the run ended before its end time"; }
};

class RowSink {
 public:
  virtual ~RowSink() = default;
  /// Once, after the start (consistent state, internal states, integrator
  /// init), also when the start failed: the run's channels (with the
  /// multipliers' when the integrator has them) and its integrator.
  virtual void begin(const std::vector<Channel>& channels, const Integrator& integ) = 0;
  /// One output row (size: the channels), finite. May throw to end the run.
  virtual void row(double t, const double* values) = 0;
  /// Between accepted steps (t reached, the step h just taken; 0 before the
  /// first), and before every row. May throw (RunError, run::Stopped) to end
  /// the run.
  virtual void between_steps(double t, double h) {
    (void)t;
    (void)h;
  }
};

/// Keeps the rows in memory: every channel, or the chosen ones.
class MemorySink : public RowSink {
 public:
  /// `columns`: indices into the run's channels; empty: every channel.
  explicit MemorySink(std::vector<int> columns = {}) : columns_(std::move(columns)) {}
  void begin(const std::vector<Channel>& channels, const Integrator&) override;
  void row(double t, const double* values) override;

  const std::vector<Channel>& channels() const { return channels_; }
  const std::vector<double>& times() const { return times_; }
  /// Row-major, width() values per row.
  const std::vector<double>& values() const { return values_; }
  long width() const { return static_cast<long>(channels_.size()); }

 private:
  std::vector<int> columns_;
  std::vector<Channel> channels_;  ///< the kept channels
  std::vector<double> times_, values_;
};

}  // namespace evas::run
