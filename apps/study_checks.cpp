// Options, checks and exit code of the CI checks (study_checks.h).
#include "apps/study_checks.h"

#include <cmath>
#include <cstdlib>
#include <iostream>

#include "model/types.h"
#include "study/report.h"

namespace evas::cli {

void add_report_options(po::options_description& o) {
  o.add_options()("junit", po::value<std::string>(),
                  "write the checks (--expect ...) as JUnit XML to FILE, one testcase each "
                  "(CI systems read it); exit 3 when one fails")(
      "json", po::value<std::string>(), "write the checks and their values as JSON to FILE");
}

std::string command_line(const std::string& command, const std::vector<std::string>& args) {
  std::string s = command;
  for (const auto& a : args) s += " " + a;
  return s;
}

int finish_checks(const po::variables_map& vm, const std::vector<study::CheckReport>& reports) {
  if (vm.count("junit"))
    study::write_report_file(vm["junit"].as<std::string>(), study::junit_xml(reports));
  if (vm.count("json"))
    study::write_report_file(vm["json"].as<std::string>(), study::checks_json(reports));
  bool passed = true;
  for (const auto& r : reports)
    for (const auto& c : r.checks)
      if (!c.passed) {
        std::cerr << "evas: check failed: " << c.name << ": " << c.message << "\n";
        passed = false;
      }
  return passed ? 0 : 3;
}

int finish_checks(const po::variables_map& vm, const study::CheckReport& r) {
  return finish_checks(vm, std::vector<study::CheckReport>{r});
}

study::Check order_check(const std::string& what, double slope, int points, double want,
                         double tol) {
  study::Check c;
  c.name = "observed order of " + what;
  c.expected = study::gnum(want, 6) + " +- " + study::gnum(tol, 6);
  if (std::isnan(slope)) {
    c.measured = "none";
    c.message = "no slope could be fitted (" + std::to_string(points) +
                " completed case(s) with a positive error; two are needed)";
    return c;
  }
  c.measured = study::gnum(slope, 4);
  c.passed = std::abs(slope - want) <= tol;
  if (!c.passed)
    c.message = "observed order " + c.measured + " is not " + c.expected + " (" +
                std::to_string(points) + " points)";
  return c;
}

ErrorExpect parse_error_expect(const std::string& expr) {
  const std::string bad = "--expect-error '" + expr + "': ";
  const auto le = expr.find("<=");
  if (le == std::string::npos || le == 0)
    throw InputError(bad + "expected CHANNELS<=TOL[@CASE], e.g. 'main*.fy<=1e-3@ida*'");
  ErrorExpect e;
  e.globs = expr.substr(0, le);
  std::string rest = expr.substr(le + 2);
  if (const auto at = rest.find('@'); at != std::string::npos) {
    e.case_glob = rest.substr(at + 1);
    rest = rest.substr(0, at);
  }
  char* end = nullptr;
  e.tol = std::strtod(rest.c_str(), &end);
  if (rest.empty() || *end || !(e.tol >= 0) || !std::isfinite(e.tol))
    throw InputError(bad + "TOL '" + rest + "' is not a number >= 0");
  return e;
}

std::vector<study::Check> error_checks(const std::string& expr,
                                       const std::vector<study::CaseResult>& cases,
                                       const std::vector<std::string>& names) {
  const std::string bad = "--expect-error '" + expr + "': ";
  const ErrorExpect ex = parse_error_expect(expr);
  const std::string& globs = ex.globs;
  const std::string& case_glob = ex.case_glob;
  const double tol = ex.tol;
  std::vector<std::size_t> sel;
  for (std::size_t c = 0; c < names.size(); ++c)
    for (const auto& g : study::split_list(globs, ','))
      if (!g.empty() && study::glob_match(g, names[c])) {
        sel.push_back(c);
        break;
      }
  if (sel.empty()) throw InputError(bad + "'" + globs + "' selects none of the study's channels");
  std::vector<study::Check> out;
  for (const auto& r : cases) {
    if (!study::glob_match(case_glob, r.c.label)) continue;
    study::Check c;
    c.name = "error of " + globs + " in " + r.c.label;
    c.expected = "<= " + study::gnum(tol, 6);
    if (r.status != study::CaseStatus::completed) {
      c.measured = "none";
      c.message = "the case " + std::string(study::to_text(r.status)) +
                  (r.message.empty() ? "" : ": " + r.message);
      out.push_back(c);
      continue;
    }
    double e = -1.0;
    std::string worst;
    for (std::size_t k : sel)
      if (k < r.channel_error.size() && r.channel_error[k] > e) {
        e = r.channel_error[k];
        worst = names[k];
      }
    if (e < 0.0) {
      c.measured = "none";
      c.message = "no selected channel has an error (constant in the reference)";
    } else {
      c.measured = study::sci(e, 3);
      c.passed = e <= tol;
      if (!c.passed) c.message = "error " + c.measured + " (" + worst + ") is above " + c.expected;
    }
    out.push_back(c);
  }
  if (out.empty()) throw InputError(bad + "the case glob '" + case_glob + "' names no case");
  return out;
}

std::vector<study::Check> stable_checks(double h, const study::StabilityResult& res) {
  std::vector<study::Check> out;
  for (const auto& p : res.points) {
    study::Check c;
    c.name = "largest stable step of " + res.c.label +
             (p.value.empty() ? "" : " at " + res.sweep_key + "=" + p.value);
    c.expected = ">= " + study::gnum(h, 6);
    c.measured = std::isnan(p.h_stable) ? "none" : study::gnum(p.h_stable, 6);
    c.passed = p.h_stable >= h;
    if (!c.passed)
      c.message = "search " + std::string(study::to_text(p.status)) + ": largest stable step " +
                  c.measured + (p.message.empty() ? "" : " (" + p.message + ")");
    out.push_back(c);
  }
  return out;
}

}  // namespace evas::cli
