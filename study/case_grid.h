// Case grids of a study: "NAME KEY=V1,V2 KEY=A..B/N ..." expands to the
// cartesian product of its value lists, each case an IntegratorSettings. The
// keys are the integrator settings of integrators/settings.h (the same keys
// as `evas run --set KEY=VALUE` and the scene's `integrator:` block).
//
// Values of one key: a comma list of items, each either a value or a log
// range `A..B/N`, N log-spaced values from A to B inclusive (A, B > 0; on an
// integer setting the values are rounded and repeats dropped). The first key
// varies slowest. A case starts from the scene's integrator block (`base`), so
// settings the spec does not name keep the scene's values; then the name is
// set (when the first word has no '=', else the scene's integrator is kept),
// then every key in the order written.
#pragma once

#include <string>
#include <vector>

#include "integrators/integrator.h"

namespace evas::study {

/// One expanded case.
struct Case {
  IntegratorSettings settings;
  std::string label;  ///< settings_label(settings)
  std::string spec;   ///< the spec it came from
  /// Keys the spec gave more than one value (the swept keys), in spec order.
  std::vector<std::string> swept;
};

/// The values of one key ("1e-3,1e-4" or "1e-3..1e-7/5" or a mix), in text
/// form. Throws InputError "<key>: ...".
std::vector<std::string> expand_values(const std::string& key, const std::string& values);

/// N log-spaced values of the range "A..B/N" in text form (endpoints as
/// written). `kind` is "number" or "integer" (rounded, repeats dropped); any
/// other kind is an error. Throws InputError "<key>: ...".
std::vector<std::string> log_range(const std::string& key, const std::string& item,
                                   const std::string& kind);

/// Expands one spec. Throws InputError "--case '<spec>': <what>" (or with
/// `where` instead of "--case" when given, e.g. "cases.txt:3").
std::vector<Case> expand_case(const std::string& spec, const IntegratorSettings& base,
                              const std::string& where = "");

/// Reads a cases file: one spec per line, '#' starts a comment, blank lines
/// skipped. Returns {spec, "FILE:LINE"} pairs. Throws InputError naming the file.
std::vector<std::pair<std::string, std::string>> read_cases_file(const std::string& path);

/// One scene-parameter sweep "ITEM.KEY=V1,V2,..." (the --sweep of `evas study
/// stability` and `sweep`): the key and its values in text form. Items are
/// values (brackets protect commas: [1e6, 1e6, 1e6]), log ranges "A..B/N" (N
/// log-spaced numbers from A to B inclusive, A, B > 0) or linear ranges
/// "A..B:S" (A, A+S, ... up to B inclusive, S > 0 when B > A; the values are
/// A + k S rounded once, so they do not accumulate round-off). Throws InputError quoting it.
struct ParamSweep {
  std::string key;
  std::vector<std::string> values;
};
ParamSweep parse_sweep(const std::string& assignment, const std::string& option = "--sweep");

/// Glob match: '*' any run of characters, '?' one character, anything else literally.
bool glob_match(const std::string& pattern, const std::string& text);

/// Splits on `sep`, trimming blanks around items; brackets [..] and {..} protect
/// separators inside them. Empty items are kept (callers reject them).
std::vector<std::string> split_list(const std::string& text, char sep);

/// Shortest text form of a number that reads back exactly.
std::string number_text(double x);

}  // namespace evas::study
