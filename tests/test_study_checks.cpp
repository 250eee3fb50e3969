// The CI side of `evas study` (study/checks.h, apps/study_checks.h,
// apps/study_problem.h): JUnit XML that xmllint accepts, a failing expectation
// that exits 3, the problem studies scored in the IVP Test Set's digits
// (F. Mazzia, C. Magherini, Test Set for IVP Solvers, release 2.4, Bari 2008)
// beside its published solvers, and --expect-error on a scene.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "io/text_escape.h"
#include "model/nearest_name.h"
#include "study/checks.h"

namespace fs = std::filesystem;
using namespace evas;

namespace {

const fs::path kOut = fs::path(EVAS_BINARY_DIR) / "tests" / "study_checks";

std::string read(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

// Runs evas with `args`; the exit code and everything it printed.
std::string run_evas(const std::string& args, int& code) {
  fs::create_directories(kOut);
  // one log per process: CTest runs the tests of this file in parallel processes
  const fs::path log = kOut / ("log_" + std::to_string(getpid()) + ".txt");
  code = std::system(
      (std::string(EVAS_BINARY_DIR) + "/evas " + args + " > " + log.string() + " 2>&1").c_str());
  code = WIFEXITED(code) ? WEXITSTATUS(code) : -1;
  return read(log);
}

// xmllint's verdict on a file (the CI installs libxml2-utils with `make deps`).
bool xml_well_formed(const fs::path& p) {
  if (std::system("command -v xmllint > /dev/null 2>&1") != 0) {
    ADD_FAILURE() << "xmllint is not installed (Debian: libxml2-utils)";
    return false;
  }
  return std::system(("xmllint --noout " + p.string() + " 2> /dev/null").c_str()) == 0;
}

int count(const std::string& s, const std::string& part) {
  int n = 0;
  for (auto p = s.find(part); p != std::string::npos; p = s.find(part, p + 1)) ++n;
  return n;
}

}  // namespace

TEST(StudyChecks, JunitEscapesAnyTextAndCountsFailures) {
  study::CheckReport r;
  r.suite = "convergence a<b>&'c\"";
  r.command = "evas study convergence x --case \"ida rtol=1e-3..1e-5/3\"";
  r.seconds = 1.5;
  r.checks.push_back({"order <2>", "2.01", "2 +- 0.1", true, ""});
  r.checks.push_back({std::string("ctrl \x01 and bad \xff utf-8"), "none", ">= 3", false,
                      "no slope & no <points>"});
  EXPECT_FALSE(r.passed());
  const std::string x = study::junit_xml(r);
  EXPECT_NE(x.find("tests=\"2\" failures=\"1\""), std::string::npos) << x;
  EXPECT_EQ(count(x, "<testcase "), 2);
  EXPECT_EQ(count(x, "<failure "), 1);
  EXPECT_NE(x.find("a&lt;b&gt;&amp;&apos;c&quot;"), std::string::npos) << x;
  EXPECT_EQ(x.find('\x01'), std::string::npos);
  const fs::path f = kOut / "escape.xml";
  fs::create_directories(kOut);
  study::write_report_file(f.string(), x);
  EXPECT_TRUE(xml_well_formed(f)) << x;
  const std::string j = study::checks_json(r);
  EXPECT_NE(j.find("\"passed\": false"), std::string::npos) << j;
  EXPECT_NE(j.find("\"measured\": \"2.01\""), std::string::npos) << j;
  EXPECT_EQ(xml_text("tab\tok"), "tab\tok");
}

// The bar of the research-workflow issue: a convergence study on Andrews'
// mechanism with an expected order and JUnit XML. Generalized-alpha is second
// order (Chung & Hulbert 1993; on index-3 DAEs Arnold & Bruls 2007).
TEST(StudyChecks, ProblemConvergenceWritesJunitAndFailsAWrongOrder) {
  const std::string kase =
      "--case 'generalized-alpha step_control=fixed rtol=1e-12 atol=1e-14 step=2e-5..5e-6/3'";
  const fs::path xml = kOut / "andrews.xml", json = kOut / "andrews.json";
  fs::remove(xml);
  int code = 0;
  std::string text =
      run_evas("study convergence problem:andrews " + kase + " --expect 2 --junit " + xml.string() +
                   " --json " + json.string() + " --no-plot --out " + (kOut / "conv").string(),
               code);
  EXPECT_EQ(code, 0) << text;
  ASSERT_TRUE(fs::exists(xml)) << text;
  EXPECT_TRUE(xml_well_formed(xml));
  const std::string x = read(xml);
  EXPECT_EQ(count(x, "<testcase "), 1) << x;
  EXPECT_EQ(count(x, "<failure "), 0) << x;
  EXPECT_NE(read(json).find("\"passed\": true"), std::string::npos);
  // the table: the swept value once, the component that sets the error
  const std::string csv = read(kOut / "conv" / "convergence.csv");
  const std::string header = csv.substr(0, csv.find('\n'));
  EXPECT_EQ(count(header, ",step,"), 1) << header;
  EXPECT_EQ(count(header, ",swept_step,"), 1) << header;
  EXPECT_NE(header.find(",error_component,"), std::string::npos) << header;
  EXPECT_EQ(count(csv, ",completed,"), 3) << csv;
  // a wrong expectation: exit 3, a failure in the XML, a message with the value
  text = run_evas("study convergence problem:andrews " + kase + " --expect 4 --junit " +
                      xml.string() + " --no-plot --out " + (kOut / "conv4").string(),
                  code);
  EXPECT_EQ(code, 3) << text;
  EXPECT_TRUE(xml_well_formed(xml));
  EXPECT_EQ(count(read(xml), "<failure "), 1);
  EXPECT_NE(text.find("observed order 2"), std::string::npos) << text;
  EXPECT_NE(text.find("is not 4 +- 0.1"), std::string::npos) << text;
  // options of a scene study are refused for a problem
  text = run_evas("study convergence problem:andrews " + kase + " --channels 'x*'", code);
  EXPECT_EQ(code, 1) << text;
  EXPECT_NE(text.find("--channels does not apply to problem:NAME"), std::string::npos) << text;
  text = run_evas("study convergence problem:andrew " + kase, code);
  EXPECT_EQ(code, 1) << text;
  EXPECT_NE(text.find("no problem named 'andrew'"), std::string::npos) << text;
}

// The published solvers' runs beside evas's, at the test set's rtol = atol.
TEST(StudyChecks, ProblemWorkPrecisionShowsThePublishedSolvers) {
  const fs::path dir = kOut / "wp";
  fs::remove_all(dir);
  int code = 0;
  const fs::path xml = kOut / "digits.xml";
  const std::string text = run_evas(
      "study work-precision problem:andrews --case 'ida rtol=1e-4,1e-7' --atol-ratio 1 "
      "--expect-digits 2 --junit " +
          xml.string() + " --no-plot --out " + dir.string(),
      code);
  // IDA at rtol = atol = 1e-4 has 0.44 digits (docs/problems.md): its check fails
  EXPECT_EQ(code, 3) << text;
  EXPECT_TRUE(xml_well_formed(xml));
  EXPECT_EQ(count(read(xml), "<failure "), 1) << read(xml);
  const std::string pub = read(dir / "published.csv");
  EXPECT_EQ(count(pub, "\n"), 9) << pub;  // header + 4 solvers at 1e-4 and 1e-7
  EXPECT_NE(pub.find("PSIDE-1,1e-07,2.1,4.98,113"), std::string::npos) << pub;
  const std::string csv = read(dir / "study.csv");
  EXPECT_NE(csv.find(",ggl,0.0001,0.0001,"), std::string::npos) << csv;  // atol = rtol
  const std::string md = read(dir / "study.md");
  EXPECT_NE(md.find("## Published solvers"), std::string::npos) << md;
}

// --expect-error on a scene: the physical channel's error at a tolerance.
TEST(StudyChecks, ExpectErrorOnASceneChannel) {
  const std::string scene = std::string(EVAS_SOURCE_DIR) + "/scenes/hinged_beam.yaml";
  const fs::path xml = kOut / "error.xml";
  int code = 0;
  std::string text =
      run_evas("study work-precision " + scene +
                   " --case 'ida rtol=1e-5' --expect-error 'spring.fz<=1e-4' --junit " +
                   xml.string() + " --no-plot --quiet --out " + (kOut / "beam").string(),
               code);
  EXPECT_EQ(code, 0) << text;
  EXPECT_TRUE(xml_well_formed(xml));
  text = run_evas("study work-precision " + scene +
                      " --case 'ida rtol=1e-5' --expect-error 'spring.fz<=1e-9@ida*' --junit " +
                      xml.string() + " --no-plot --quiet --out " + (kOut / "beam").string(),
                  code);
  EXPECT_EQ(code, 3) << text;
  EXPECT_NE(text.find("(spring.fz) is above <= 1e-09"), std::string::npos) << text;
  text =
      run_evas("study work-precision " + scene +
                   " --case 'ida rtol=1e-5' --expect-error 'nothing*<=1' --no-plot --quiet --out " +
                   (kOut / "beam").string(),
               code);
  EXPECT_EQ(code, 1) << text;
  EXPECT_NE(text.find("selects none of the study's channels"), std::string::npos) << text;
}

// `evas study compare`: two tables agree within tolerances, a changed cell is
// found and named, the exit code is 3, rows only one table has are listed.
TEST(StudyChecks, CompareFindsTheCellThatChanged) {
  const fs::path dir = kOut / "cmp";
  fs::create_directories(dir / "a");
  fs::create_directories(dir / "b");
  std::ofstream(dir / "a" / "study.csv") << "label,error,wall,status\n"
                                            "ida rtol=1e-3,1.0e-3,0.5,completed\n"
                                            "ida rtol=1e-5,2.0e-5,0.7,completed\n";
  std::ofstream(dir / "b" / "study.csv") << "label,error,wall,status\n"
                                            "ida rtol=1e-3,1.0000001e-3,9.5,completed\n"
                                            "ida rtol=1e-5,2.1e-5,0.8,completed\n"
                                            "ida rtol=1e-7,3e-7,0.9,completed\n";
  int code = 0;
  const fs::path xml = dir / "compare.xml";
  std::string text = run_evas("study compare " + (dir / "a").string() + " " + (dir / "b").string() +
                                  " --rtol 1e-3 --junit " + xml.string(),
                              code);
  EXPECT_EQ(code, 3) << text;
  EXPECT_NE(text.find("| study.csv | ida rtol=1e-5 | error | 2.0e-5 | 2.1e-5 |"), std::string::npos)
      << text;
  EXPECT_EQ(text.find("rtol=1e-3 | error"), std::string::npos) << text;  // within 1e-3
  EXPECT_EQ(text.find("| wall |"), std::string::npos) << text;           // ignored by default
  EXPECT_NE(text.find("row 'ida rtol=1e-7' only in the second table"), std::string::npos) << text;
  EXPECT_TRUE(xml_well_formed(xml));
  // the same table against itself: exit 0
  text = run_evas("study compare " + (dir / "a" / "study.csv").string() + " " +
                      (dir / "a" / "study.csv").string(),
                  code);
  EXPECT_EQ(code, 0) << text;
  EXPECT_NE(text.find("the tables agree"), std::string::npos) << text;
  // --ignore '' compares the wall times as well
  text = run_evas("study compare " + (dir / "a" / "study.csv").string() + " " +
                      (dir / "b" / "study.csv").string() + " --rtol 0.1 --ignore ''",
                  code);
  EXPECT_EQ(code, 3) << text;
  EXPECT_NE(text.find("| wall |"), std::string::npos) << text;
  text = run_evas("study compare " + (dir / "a").string() + " " + (dir / "nothing").string(), code);
  EXPECT_EQ(code, 1) << text;
  EXPECT_NE(text.find("no such file or folder"), std::string::npos) << text;
}

// A set: the same study on several targets (DiffEqDevTools' WorkPrecisionSet),
// each into a folder of its own, one JUnit testsuite each, a summary.
TEST(StudyChecks, ASetRunsTheStudyOnEveryTarget) {
  const fs::path dir = kOut / "set";
  fs::remove_all(dir);
  const fs::path xml = dir / "set.xml";
  fs::create_directories(dir);
  int code = 0;
  const std::string text = run_evas(
      "study convergence problem:andrews --and problem:pendulum --case "
      "'generalized-alpha step_control=fixed rtol=1e-12 atol=1e-14 step=2e-5..5e-6/3' "
      "--expect 2 --junit " +
          xml.string() + " --no-plot -q --out " + dir.string(),
      code);
  EXPECT_TRUE(code == 0 || code == 3) << text;
  for (const char* sub : {"andrews/convergence.csv", "pendulum/convergence.csv", "set.md"})
    EXPECT_TRUE(fs::exists(dir / sub)) << sub << "\n" << text;
  EXPECT_TRUE(xml_well_formed(xml));
  const std::string x = read(xml);
  EXPECT_EQ(count(x, "<testsuite "), 2) << x;
  EXPECT_NE(x.find("convergence problem:pendulum"), std::string::npos) << x;
  EXPECT_NE(read(dir / "set.md").find("| problem:andrews | "), std::string::npos);
}

// Stability on a problem: generalized-alpha on Andrews' mechanism is
// unconditionally stable for the linear part (Chung & Hulbert 1993); the
// search finds where its Newton iteration stops converging, and a case that
// cannot run on the problem is bad input, not an unstable step.
TEST(StudyChecks, ProblemStabilitySearchAndBadCase) {
  int code = 0;
  const fs::path xml = kOut / "stab.xml";
  std::string text = run_evas(
      "study stability problem:andrews --case 'generalized-alpha step_control=fixed rtol=1e-10 "
      "atol=1e-12' --step-range 1e-6:1e-3 --bisections 4 --expect-stable-to 1e-5 --junit " +
          xml.string() + " -q --out " + (kOut / "stab").string(),
      code);
  EXPECT_EQ(code, 0) << text;
  EXPECT_NE(text.find("result: **bracketed**"), std::string::npos) << text;
  EXPECT_TRUE(xml_well_formed(xml));
  const std::string csv = read(kOut / "stab" / "stability.csv");
  EXPECT_EQ(csv.rfind("h,stable,steps,reason\n", 0), 0u) << csv;
  EXPECT_EQ(count(csv, "\n"), 1 + 2 + 4) << csv;  // HMAX, HMIN, 4 bisections
  text = run_evas(
      "study stability problem:andrews --case 'linear-acceleration step_control=fixed' "
      "--step-range 1e-7:1e-4 -q --out " +
          (kOut / "stab2").string(),
      code);
  EXPECT_EQ(code, 1) << text;
  EXPECT_NE(text.find("does not run on problem andrews"), std::string::npos) << text;
}

// A sweep checks what a run checks: every point's plausibility warnings (a
// speed of 3000 rad/s, likely meant in rpm) before any run and in sweep.md;
// a downward range is refused; a refused sweep leaves no empty folder; the
// option is named right and the nearest channel names suggested.
TEST(StudyChecks, SweepChecksWhatARunChecks) {
  const std::string demo = std::string(EVAS_SOURCE_DIR) + "/scenes/demo.yaml";
  const fs::path dir = kOut / "sweep";
  fs::remove_all(dir);
  int code = 0;
  std::string text = run_evas("study sweep " + demo +
                                  " --t-end 0.002 --sweep 'shaft.lof.speed=100,3000' --no-plot "
                                  "--jobs 1 --out " +
                                  dir.string(),
                              code);
  EXPECT_EQ(code, 0) << text;
  EXPECT_NE(text.find("evas study sweep: warning: point 1 (shaft.lof.speed=3000)"),
            std::string::npos)
      << text;
  EXPECT_EQ(text.find("point 0 (shaft.lof.speed=100)"), std::string::npos) << text;
  EXPECT_NE(read(dir / "sweep.md").find("- **warning**: point 1 (shaft.lof.speed=3000)"),
            std::string::npos);
  const fs::path refused = kOut / "sweep_refused";
  fs::remove_all(refused);
  text = run_evas(
      "study sweep " + demo + " --sweep 'shaft.lof.speed=300..100/3' --out " + refused.string(),
      code);
  EXPECT_EQ(code, 1) << text;
  EXPECT_NE(text.find("the range 300..100/3 runs downward"), std::string::npos) << text;
  EXPECT_FALSE(fs::exists(refused));
  text = run_evas("study sweep " + demo +
                      " --sweep 'shaft.lof.speed=100' --order-channels 'frame_right.VZ' --out " +
                      refused.string(),
                  code);
  EXPECT_EQ(code, 1) << text;
  EXPECT_NE(text.find("--order-channels 'frame_right.VZ' matches no output channel (nearest: "
                      "frame_right.vz"),
            std::string::npos)
      << text;
  EXPECT_FALSE(fs::exists(refused));
}

// Levenshtein's distance (Levenshtein 1966): kitten -> sitting is 3 edits;
// letters compare without case; the nearest names come first.
TEST(StudyChecks, NearestNamesForMessages) {
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);
  EXPECT_EQ(edit_distance("main3.Fy", "main3.fy"), 0u);
  EXPECT_EQ(edit_distance("", "abc"), 3u);
  const std::vector<std::string> names = {"crank_angle", "main1.fy", "main3.fx", "main3.fy"};
  EXPECT_EQ(nearest_names("main3.Fy", names, 2),
            (std::vector<std::string>{"main3.fy", "main1.fy"}));  // a tie: names order
  EXPECT_EQ(nearest_names("main3*.fy", names, 1), (std::vector<std::string>{"main3.fy"}));
  EXPECT_EQ(nearest_text("mian3.fy", names, 2), "nearest: main3.fy, main1.fy; 4 in all");
  EXPECT_EQ(nearest_text("x", {}), "");
}
