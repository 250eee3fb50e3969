// The figures of a sweep over operating points (`evas study sweep`, sweep.h5):
// order cuts, waterfall and Campbell diagram, as gnuplot scripts. `evas study
// sweep` draws them from its data as it writes sweep.h5; `evas plot
// waterfall|campbell|order-cuts SWEEP.h5` draws them again from the file.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "post/natural_frequencies.h"

namespace evas {

/// What the sweep figures are drawn from (sweep.h5's groups).
struct SweepFigureData {
  std::string scene_name;
  std::vector<std::string> keys;  ///< swept ITEM.KEYs
  struct Task {
    int point = 0, case_index = 0;
    std::vector<std::string> values;  ///< value of each key
    double rpm = 0.0;                 ///< mean crank speed [rpm] (NaN: none)
  };
  std::vector<Task> tasks;
  std::vector<std::string> names, units;  ///< channels with order spectra
  std::vector<double> orders;             ///< spectrum orders
  /// [task][channel][order]; empty for a task without a spectrum
  std::vector<std::vector<std::vector<double>>> amplitude;
  std::vector<NaturalFrequency> natural;  ///< of the scene's bodies (Campbell)
  /// The assembled system's modes per point (/assembled; post/assembled_modes.h)
  struct Mode {
    double rpm = 0.0, hz = 0.0, damping_ratio = 0.0;
    std::string where, label;
  };
  std::vector<Mode> assembled;
  int cycles = 1;  ///< engine cycles per spectrum
  double max_order = 12.0;
};

/// Reads sweep.h5. Throws InputError naming the file when it is not a sweep's
/// (a run's results.h5, a work-precision study.h5), `why` first (e.g. "a
/// waterfall is drawn from a sweep over speeds"), or cannot be read.
SweepFigureData read_sweep_figures(const std::string& path, const std::string& why = "");

/// True when some task has an order spectrum.
bool has_spectra(const SweepFigureData& d);

/// Index of a channel, or an InputError naming the channels the sweep has.
int sweep_channel(const SweepFigureData& d, const std::string& name, const std::string& file);

/// gnuplot scripts writing `out` (.png or .svg). Order cuts: the amplitude of
/// each order in `orders` against the swept value, one panel per channel (at
/// most 4); waterfall: the order spectrum of `channel` against the swept
/// value; Campbell: natural frequencies against speed with engine orders up to
/// max_order ("" when no task has a speed).
std::string order_cuts_script(const SweepFigureData& d, const std::vector<int>& channels,
                              const std::vector<double>& orders, const std::filesystem::path& out);
std::string waterfall_script(const SweepFigureData& d, int channel,
                             const std::filesystem::path& out);
std::string campbell_script(const SweepFigureData& d, const std::filesystem::path& out);

}  // namespace evas
