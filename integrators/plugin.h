// Integrator plug-ins: shared libraries loaded at run time that register
// integrators by name (register_integrator, integrators/integrator.h).
//
// A plug-in exports one C function,
//     EVAS_PLUGIN_EXPORT int evas_plugin_init(int abi_version);
// which checks abi_version == EVAS_PLUGIN_ABI_VERSION, calls register_integrator
// for each of its integrators and returns 0 (anything else: refused). It is
// compiled against evas's public headers with the same compiler and standard
// library, and links nothing of evas: the symbols it uses (register_integrator,
// the error types) resolve against the evas program, which exports them.
// docs/extending.md has a worked example (examples/radau_plugin).
#pragma once

#include <string>
#include <vector>

// 2: Problem::force_jacobian_combination (the vtable changed); 3: IntegratorSettings
// keeps step_control and iteration as enums, register_integrator takes capabilities;
// 4: IntegratorSettings::own and IntegratorCapabilities::settings (settings of a
// plug-in's own), the Newmark-family bases public (integrators/newmark_dae.h)
#define EVAS_PLUGIN_ABI_VERSION 4
/// Declares a plug-in's entry point exported whatever the visibility preset:
///     EVAS_PLUGIN_EXPORT int evas_plugin_init(int abi_version) { ... }
#define EVAS_PLUGIN_EXPORT extern "C" __attribute__((visibility("default")))

namespace evas {

/// Loads a plug-in and returns the names of the integrators it registered.
/// `spec` is a file path (it contains '/' or ends in ".so"), or a name looked
/// up as lib<spec>.so, then <spec>.so, in the folders of the environment
/// variable EVAS_PLUGIN_PATH (':'-separated). Loading the same file twice
/// returns the names of the first load. Throws InputError naming the plug-in
/// and what is wrong (not found, not a shared library, no entry point, ABI
/// version, a name already taken).
std::vector<std::string> load_plugin(const std::string& spec);

/// Loads each plug-in named in the environment variable EVAS_PLUGINS
/// (':'-separated specs as for load_plugin); nothing when it is unset.
std::vector<std::string> load_env_plugins();

}  // namespace evas
