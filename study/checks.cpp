// JUnit XML and JSON of a study's checks (checks.h).
#include "study/checks.h"

#include <sstream>

#include "io/text_escape.h"
#include "model/types.h"
#include "study/report.h"

namespace evas::study {

bool CheckReport::passed() const {
  for (const auto& c : checks)
    if (!c.passed) return false;
  return true;
}

namespace {

std::string testsuite(const CheckReport& r) {
  int failures = 0;
  for (const auto& c : r.checks) failures += c.passed ? 0 : 1;
  std::ostringstream x;
  x << "  <testsuite name=\"" << xml_text(r.suite) << "\" tests=\"" << r.checks.size()
    << "\" failures=\"" << failures << "\" errors=\"0\" skipped=\"0\" time=\"" << gnum(r.seconds, 6)
    << "\">\n"
    << "    <properties>\n      <property name=\"command\" value=\"" << xml_text(r.command)
    << "\"/>\n    </properties>\n";
  // the class: evas.study.<the study's kind> (the suite's first word)
  const std::string cls = "evas.study." + r.suite.substr(0, r.suite.find(' '));
  for (const auto& c : r.checks) {
    x << "    <testcase classname=\"" << xml_text(cls) << "\" name=\"" << xml_text(c.name)
      << "\" time=\"0\">\n"
      << "      <properties>\n"
      << "        <property name=\"measured\" value=\"" << xml_text(c.measured) << "\"/>\n"
      << "        <property name=\"expected\" value=\"" << xml_text(c.expected) << "\"/>\n"
      << "      </properties>\n";
    if (!c.passed)
      x << "      <failure message=\"" << xml_text(c.message) << "\" type=\"expectation\">"
        << xml_text(c.name + ": measured " + c.measured + ", expected " + c.expected)
        << "</failure>\n";
    x << "      <system-out>" << xml_text("measured " + c.measured + ", expected " + c.expected)
      << "</system-out>\n"
      << "    </testcase>\n";
  }
  x << "  </testsuite>\n";
  return x.str();
}

std::string suite_json(const CheckReport& r, const std::string& pad) {
  std::ostringstream j;
  j << pad << "{\"suite\": " << json_string(r.suite) << ", \"command\": " << json_string(r.command)
    << ", \"seconds\": " << json_number(r.seconds)
    << ", \"passed\": " << (r.passed() ? "true" : "false") << ", \"checks\": [";
  for (std::size_t i = 0; i < r.checks.size(); ++i) {
    const Check& c = r.checks[i];
    j << (i ? "," : "") << "\n"
      << pad << "  {\"name\": " << json_string(c.name)
      << ", \"measured\": " << json_string(c.measured)
      << ", \"expected\": " << json_string(c.expected)
      << ", \"passed\": " << (c.passed ? "true" : "false")
      << ", \"message\": " << json_string(c.message) << "}";
  }
  j << (r.checks.empty() ? "" : "\n" + pad) << "]}";
  return j.str();
}

}  // namespace

std::string junit_xml(const std::vector<CheckReport>& reports) {
  std::size_t tests = 0;
  int failures = 0;
  double seconds = 0.0;
  for (const auto& r : reports) {
    tests += r.checks.size();
    for (const auto& c : r.checks) failures += c.passed ? 0 : 1;
    seconds += r.seconds;
  }
  std::ostringstream x;
  x << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    << "<testsuites name=\"evas study\" tests=\"" << tests << "\" failures=\"" << failures
    << "\" errors=\"0\" time=\"" << gnum(seconds, 6) << "\">\n";
  for (const auto& r : reports) x << testsuite(r);
  x << "</testsuites>\n";
  return x.str();
}

std::string junit_xml(const CheckReport& r) { return junit_xml(std::vector<CheckReport>{r}); }

std::string checks_json(const std::vector<CheckReport>& reports) {
  bool passed = true;
  for (const auto& r : reports) passed = passed && r.passed();
  std::ostringstream j;
  j << "{\n  \"passed\": " << (passed ? "true" : "false") << ",\n  \"suites\": [";
  for (std::size_t i = 0; i < reports.size(); ++i)
    j << (i ? "," : "") << "\n" << suite_json(reports[i], "    ");
  j << (reports.empty() ? "" : "\n  ") << "]\n}\n";
  return j.str();
}

std::string checks_json(const CheckReport& r) { return checks_json(std::vector<CheckReport>{r}); }

void write_report_file(const std::string& path, const std::string& text) {
  try {
    write_file_atomic(path, text);
  } catch (const std::exception& e) {
    throw InputError(path + ": cannot write the file: " + e.what());
  }
}

}  // namespace evas::study
