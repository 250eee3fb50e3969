// The options `evas run` and `evas periodic` share: the scene and its
// parameters (--param), the integrator and its settings (--integrator, --rtol,
// --atol, --step, --set), and the output folder (--out, --overwrite, --csv,
// --max-wall, --quiet).
#pragma once

#include <string>

#include "apps/commands.h"
#include "io/scene.h"
#include "run/folder_run.h"

namespace evas::cli {

/// Parses the arguments of `evas COMMAND SCENE ...`: -1 to go on, else the
/// exit code (0 after --help or --help-settings, 1 without SCENE).
int parse_scene_command(const std::string& command, const std::vector<std::string>& args,
                        const po::options_description& opts, po::variables_map& vm);

/// Adds the shared options to `opts` (after --help, which each command adds).
void add_scene_run_options(po::options_description& opts);

/// The scene of vm["scene"] with --param applied, its integrator settings
/// from --integrator, --rtol, --atol, --step and --set, and a warning on
/// stderr ("evas COMMAND: warning: ...") of each setting the method does not
/// read. Throws InputError for bad input.
Scene scene_from_options(const std::string& command, const po::variables_map& vm);

/// The output folder's options: --out (default out/<scene name>, checked to be
/// one plain path component), --overwrite, --csv, --max-wall, --quiet; the
/// log prefix "evas COMMAND".
run::FolderOptions folder_from_options(const std::string& command, const po::variables_map& vm,
                                       const Scene& scene);

}  // namespace evas::cli
