// Every integrator setting, declared once: its key, kind, range, default and
// meaning. The scene reader (`integrator:` block), the command line
// (`--set KEY=VALUE`), the studies (`--case "NAME KEY=V1,V2 ..."`), the run
// summary and `evas run --help-settings` all read this one table, so a setting
// added here is available everywhere with the same name and checks.
#pragma once

#include <string>
#include <vector>

#include "integrators/integrator.h"

namespace evas {

struct SettingInfo {
  std::string key;
  std::string kind;     ///< "number", "integer", "choice" or "bool"
  std::string applies;  ///< integrators it acts on ("all" or a list)
  std::string doc;      ///< one line: meaning, unit, range
};

/// The table, in documentation order (the built-in settings; those a
/// plug-in declares for itself are in declared_settings(), integrator.h).
const std::vector<SettingInfo>& integrator_settings();

/// True when `key` is in the built-in table.
bool is_builtin_setting(const std::string& key);

/// Sets `key` from its text form, checking kind and range. A key a loaded
/// integrator declares for itself (DeclaredSetting) is checked against its
/// declaration (that of s.name when it declares the key, else the first) and
/// stored in s.own. Throws InputError "<key>: <what is wrong>" (callers prefix
/// file, line or option), an unknown key listing the known ones.
void set_integrator_setting(IntegratorSettings& s, const std::string& key,
                            const std::string& value);

/// The text form of a setting (numbers with enough digits to round-trip).
std::string get_integrator_setting(const IntegratorSettings& s, const std::string& key);

/// Applies "KEY=VALUE" (as given to --set). Throws InputError naming the option.
void apply_setting_assignment(IntegratorSettings& s, const std::string& assignment);

/// "ida, cvode, ..." : the built-in integrators, or those of them that can step
/// at settings.step (their declared capabilities), for help texts.
std::string builtin_integrator_list(bool fixed_step_only = false);

/// True when `name` is a method that declares it can step at settings.step
/// (generalized-alpha, linear-acceleration, radau: step_control fixed or substep).
bool has_fixed_step(const std::string& name);
/// arkode's tables by ARKODE's names (integrators/arkode.cpp): diagonally
/// implicit (the default first), explicit.
const std::vector<std::string>& arkode_implicit_tables();
const std::vector<std::string>& arkode_explicit_tables();
/// True when `s` names such a method and step_control is not "adaptive".
bool takes_fixed_steps(const IntegratorSettings& s);

/// "name key=value ..." of the accuracy knob (rtol of an adaptive method, step
/// of a fixed-step one) and of every setting that differs from a
/// default-constructed IntegratorSettings (a compact label for tables).
std::string settings_label(const IntegratorSettings& s);

/// Keys of the settings the built-in method `integrator` does not read: those
/// whose table entry names built-in methods only, not this one (a setting
/// whose use depends on another, e.g. "iteration=anderson", is not listed).
/// Empty for a plug-in, whose reads are its own.
std::vector<std::string> settings_not_read_by(const std::string& integrator);

/// Why the setting `key` has no effect in a run with `s`: empty when s's method
/// reads it, or may (a plug-in's reads are its own); otherwise a clause such as
/// "ida does not read it (generalized-alpha, linear-acceleration, radau do)" or
/// "it is read only with iteration=anderson (here: effective-mass)", from the
/// table's `applies` column. Throws InputError for an unknown key.
std::string setting_unread_reason(const IntegratorSettings& s, const std::string& key);

/// Markdown table of every setting (for --help-settings and the user guide).
std::string settings_reference();

}  // namespace evas
