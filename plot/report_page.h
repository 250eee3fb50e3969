// `evas report RESULTS.h5 --out DIR`: the page an NVH engineer opens first
// for a run of an engine scene (docs/user-guide.md, "evas report"). It writes
// DIR/index.html (HTML5, one file, no external resource, relative links only,
// so the folder can be moved) and beside it the figures, each drawn by
// plot_results (plot/figures.h) as PNG with its gnuplot script and data:
//
//   run summary       scene, status, grid, time and crank-angle span, speed,
//                     integrator and its statistics (the file's /stats group,
//                     the settings of summary.json beside it when there)
//   journal bearings  a table of peaks per bearing; for each: polar load
//                     diagram, orbit, film thickness and peak pressure
//   bearing loads     fx and fy of every bearing against crank angle (one
//                     figure per component), their order spectra and a table
//                     of the largest orders [kN]
//   friction power    the bearings' friction_power channels, when there
//   crank torsion     each NAME.twist channel (a torsion request's, with its
//                     markers' angles, or an element's such as the dyno's)
//                     and its order spectrum, when there
//   block surface     channels ending in .vn_rms, .vn_mean, .erp; without
//                     them the section names the output request to add
//
// The file must hold a run on the crank-angle grid (a crank_angle channel):
// anything else is an InputError naming the grid and what the file holds. A
// crank-angle run without journal bearings gets a report of what there is,
// its bearing sections saying what output request would give them.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace evas {

struct ReportOptions {
  std::string title;  ///< "" for "Engine report: SCENE"
  int cycles = -1;    ///< last whole cycles drawn and analysed (-1: the last one, as evas spectrum)
  bool overwrite = false;  ///< replace DIR/index.html of an earlier report
};

struct ReportResult {
  std::filesystem::path index;     ///< DIR/index.html
  std::vector<std::string> files;  ///< every file written (figures, scripts, data, the page)
  int figures = 0;
  std::vector<std::string> notes;  ///< what the report could not show, and why
  std::string cycles;              ///< which cycles it drew and analysed (Run::span_text)
};

/// Writes the report of `results` into `dir` (created if missing). Throws
/// InputError for a missing results file, a `dir` that is a file, an existing
/// DIR/index.html without `overwrite`, a file that is not a crank-angle engine
/// run, cycles beyond the record, and a failing figure (plot_results).
ReportResult write_report(const std::string& results, const std::filesystem::path& dir,
                          const ReportOptions& o);

}  // namespace evas
