// The checks of a study for CI systems: `--expect ORDER`, `--expect-error`,
// `--expect-stable-to`, `--expect-digits` each give one Check; `--junit FILE`
// writes them as JUnit XML (one <testcase> per check, with the measured and
// expected values as properties and a <failure> when it failed) and `--json
// FILE` as a JSON summary. The command exits non-zero when a check failed
// (apps/cmd_study.cpp: 3).
#pragma once

#include <string>
#include <vector>

namespace evas::study {

struct Check {
  std::string name;      ///< what is checked, e.g. "observed order of ida over rtol"
  std::string measured;  ///< the measured value as text ("none" when there is none)
  std::string expected;  ///< the condition, e.g. "4 +- 0.1" or "<= 1e-3"
  bool passed = false;
  std::string message;  ///< why it failed ("" when it passed)
};

/// `suite` names the study ("convergence andrews"), `command` the command line;
/// `seconds` the study's wall time.
struct CheckReport {
  std::string suite, command;
  double seconds = 0.0;
  std::vector<Check> checks;
  bool passed() const;
};

/// JUnit XML of the reports, one testsuite each (the schema Jenkins, GitLab
/// and GitHub read: testsuites > testsuite > testcase, failure).
std::string junit_xml(const std::vector<CheckReport>& r);
std::string junit_xml(const CheckReport& r);
/// A JSON object: passed, suites [{suite, command, seconds, passed, checks
/// [{name, measured, expected, passed, message}]}].
std::string checks_json(const std::vector<CheckReport>& r);
std::string checks_json(const CheckReport& r);
/// Writes `text` to `path` (atomically); throws InputError naming the file.
void write_report_file(const std::string& path, const std::string& text);

}  // namespace evas::study
