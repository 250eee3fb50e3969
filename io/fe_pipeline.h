// FE pipeline: Gmsh geometry script -> second-order tet mesh -> CalculiX decks
// -> ccx matrix storage (and optionally ccx's own eigen-solution) -> modal body.
// External programs run through std::system with their output in a log file;
// a missing program or a failed run is an InputError naming the program and the log.
// See docs/fe-pipeline.md.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "bodies/body_builder.h"
#include "bodies/interface_modes.h"
#include "bodies/reduce_body.h"
#include "io/calculix.h"

namespace evas {

/// Parameters of `evas modal build` (YAML, see docs/fe-pipeline.md).
struct PipelineParams {
  std::string name = "body";
  std::string geometry;                  ///< .geo script (absolute or relative to the YAML)
  std::map<std::string, double> params;  ///< -setnumber NAME VALUE for the script
  double mesh_size = 0.0;                ///< passed as -setnumber mesh_size (0 = script default)
  std::string units = "mm-t-s";          ///< unit system of geometry and material
  double youngs = 210e3;                 ///< [force/length^2], file units (MPa for mm-t-s)
  double poisson = 0.3;
  double density = 7.85e-9;  ///< [mass/length^3], file units (t/mm^3 for mm-t-s)
  BuildOptions build;        ///< modes kept, cut-off, damping, solver
  /// Node sets that get static correction (interface) modes, e.g. bearing journals.
  std::vector<std::string> interface_sets;
  /// Their loads, ranking, count and Ritz blocks (`interface_sets` entries
  /// `{set: NAME, loads: [y, z]}`, `interface_tolerance`, `interface_count`,
  /// `ritz_blocks`); damping_ratio is taken from `build`.
  InterfaceOptions interface;
  bool ccx_eigen = false;  ///< also run ccx's *FREQUENCY (frd/dat) for comparison
  int ccx_modes = 0;       ///< modes asked from ccx (0: 6 + elastic + 4, at least 16)
  std::string work_dir;    ///< where meshes, decks, logs go (relative to the output folder)
  std::string output;      ///< body file (relative to the output folder)
  /// Store the invariants and mass properties of the full body in the file
  /// (format version 2; a simulation then does not recompute them).
  bool store_invariants = true;
  /// `reduce: {keep_sets: all | [names], extra_nodes: [ids]}`: write a reduced
  /// body (solver/reduce_body.h); implies store_invariants.
  std::optional<ReduceOptions> reduce;
};

/// Reads the YAML parameter file. `geometry` is relative to the file's folder;
/// `output` and `work_dir` are relative to `out_dir` ("" = the current folder),
/// so a build never writes next to its parameter file unless asked to.
PipelineParams read_pipeline_params(const std::string& yaml_path, const std::string& out_dir = "");

/// Wall time, peak memory is not measured here (use /usr/bin/time -v).
struct StageTime {
  std::string stage;
  double seconds = 0.0;
};

struct PipelineResult {
  FeModel fe;       ///< SI, from matrix storage
  ModalBody body;   ///< from the evas builder (reduced when PipelineParams::reduce)
  std::string frd;  ///< ccx eigen-solution files when ccx_eigen (else empty)
  std::string dat;
  std::vector<StageTime> stages;
};

/// Path of the first program of `names` found on PATH (an executable regular
/// file; an empty entry is the current folder, no PATH is /usr/bin:/bin), or ""
/// if none.
std::string find_program(const std::vector<std::string>& names);

/// Runs a shell command with stdout and stderr to `log`; throws InputError naming
/// `what` and the log when the exit status is not zero.
void run_logged(const std::string& what, const std::string& command, const std::string& log);

/// gmsh -3 GEO (-setnumber ...) -format inp -o OUT_INP.
void run_gmsh(const std::string& geo, const std::map<std::string, double>& params, double mesh_size,
              const std::string& out_inp, const std::string& log);

/// Writes JOB.inp in `dir`: *INCLUDE of `mesh_file` (name relative to dir), an
/// isotropic material on EALL and one *FREQUENCY step; `matrix_storage` selects
/// SOLVER=MATRIXSTORAGE, otherwise `modes` eigenmodes with *NODE FILE U.
void write_ccx_deck(const std::string& dir, const std::string& job, const std::string& mesh_file,
                    double youngs, double poisson, double density, bool matrix_storage, int modes);

/// Runs ccx on JOB.inp in `dir` (log JOB.log); checks that `expect` files exist.
void run_ccx(const std::string& dir, const std::string& job,
             const std::vector<std::string>& expect);

/// The whole chain; `verbose` prints each stage and its wall time.
PipelineResult run_pipeline(const PipelineParams& p, bool verbose);

}  // namespace evas
