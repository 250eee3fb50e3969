// Private to study/: the sweep driver (sweep.cpp) and its files
// (sweep_files.cpp, sweep_plots.cpp).
#pragma once

#include "post/assembled_modes.h"
#include "post/natural_frequencies.h"
#include "post/order_spectrum.h"
#include "study/study_common.h"
#include "study/sweep.h"

namespace evas::study::detail {

/// Everything the files of a sweep are made from.
struct SweepData {
  SweepResult res;
  std::vector<std::string> names, units;  ///< selected channels
  bool crank_grid = false;
  std::vector<double> orders;  ///< spectrum orders (0.5 steps up to max_order)
  /// per task, per channel: amplitude at each order (empty: no spectrum)
  std::vector<std::vector<std::vector<double>>> amplitude;
  std::vector<NaturalFrequency> natural;  ///< of the scene's bodies
  /// The assembled system's modes at each periodic point (post/assembled_modes.h)
  struct Assembled {
    std::size_t task = 0;
    double rpm = 0.0;
    AssembledMode mode;
  };
  std::vector<Assembled> assembled;
  std::string assembled_note;        ///< why points have none ("" when every one has)
  std::vector<int> figure_channels;  ///< indices into names
};

/// Order spectra and mean speed of task k (after its run).
void analyse_task(SweepData& d, const SweepOptions& so, std::size_t k);

/// The natural frequencies (post/natural_frequencies.h) of the scene's bodies
/// up to 1.2 x the highest order at the highest speed; none without a speed.
std::vector<NaturalFrequency> campbell_frequencies(const SceneSource& src, const SweepData& d,
                                                   const SweepOptions& so);

/// The modes of the assembled system linearized about each completed periodic
/// task's cycle (RunData::cycle_states), up to 1.2 x the highest order at the
/// highest speed, into d.assembled (and d.assembled_note).
void assembled_campbell(const std::vector<TaskSpec>& tasks, SweepData& d, const SweepOptions& so);

/// campbell.csv: speed [rpm], frequency_hz, label, where, damping_ratio, point, case_index.
void write_campbell_csv(const fs::path& path, const SweepData& d);

/// Task k's file: its key (the point and case, readable), its fingerprint
/// (task_fingerprint: what it computes), status, channels and statistics.
void write_task_file(const fs::path& path, const SweepData& d, std::size_t k,
                     const std::string& key, const std::string& fingerprint);
/// Reads a task file into task k when its key and fingerprint match; false
/// otherwise (another sweep's, an edited scene's, or an unreadable file).
bool read_task_file(const fs::path& path, SweepData& d, std::size_t k, const std::string& key,
                    const std::string& fingerprint);

void write_sweep_tables(const Options& opt, SweepData& d);
void write_sweep_h5(const Options& opt, SweepData& d, const SweepOptions& so);
void plot_sweep(const Options& opt, SweepData& d, const SweepOptions& so,
                GnuplotProcess* started = nullptr);

}  // namespace evas::study::detail
