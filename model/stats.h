// The statistics every run reports, declared once: the struct the integrators
// fill, and the table of its fields (name, unit, meaning) that the results file,
// summary.json, the study tables, `evas problem` and Python all iterate. A new
// statistic is a member here and one row in stats.cpp.
#pragma once

#include <string>
#include <vector>

namespace evas {

/// Statistics every run reports.
struct IntegratorStats {
  long steps = 0;
  long residual_evals = 0;  ///< f (or F) evaluations, including those for finite differences
  long jacobian_evals = 0;
  long linear_setups = 0;  ///< factorizations
  long linear_solves = 0;
  long nonlinear_iterations = 0;
  long error_test_failures = 0;
  long convergence_failures = 0;
  long restarts = 0;        ///< re-initializations at stops that changed the state
  long refused_states = 0;  ///< trial states an element refused (RangeError), each retried
  long substeps = 0;  ///< fixed-step methods: steps retried as sub-steps after a failed iteration
  long max_step_iterations = 0;  ///< fixed-step methods: most iterations taken in one step
  double wall_seconds = 0.0;
  double last_step = 0.0;
  double min_step = 0.0, max_step = 0.0;
  int last_order = 0;
  /// Constrained problems: largest |g| and |G v + g_t| seen at the outputs.
  double max_constraint = 0.0, max_constraint_rate = 0.0;
};

/// One statistic: its name in files and tables, unit ("" for a count), meaning.
struct StatField {
  const char* name;
  const char* unit;
  const char* meaning;
  bool integer;  ///< a count (written as an integer)
  double (*get)(const IntegratorStats&);
};

/// Every IntegratorStats field, in declaration order.
const std::vector<StatField>& stat_fields();

/// The statistics as exact bytes, field after field (no padding bytes, whose
/// values C++ leaves open), and back. stats_from_bytes throws
/// std::runtime_error when the size is not that of every field.
std::string stats_to_bytes(const IntegratorStats& s);
IntegratorStats stats_from_bytes(const std::string& bytes);

/// The value as files write it: an integer for a count, else 17 digits ("null"
/// when not finite, as JSON has no NaN).
std::string stat_text(const StatField& f, const IntegratorStats& s);

/// The members of a JSON object, one per statistic ("name": value), each line
/// begun with `indent`, separated by ",\n", without a final line break.
std::string stats_json_members(const IntegratorStats& s, const std::string& indent);

}  // namespace evas
