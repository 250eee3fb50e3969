// Study sets and `evas study compare` on the command line (study_set.h).
#include "apps/study_set.h"

#include <filesystem>
#include <iostream>
#include <map>
#include <sstream>

#include "apps/commands.h"
#include "apps/study_checks.h"
#include "apps/study_problem.h"
#include "study/case_grid.h"
#include "study/compare.h"
#include "study/report.h"

namespace evas::cli {

namespace {

std::string target_slug(const std::string& scene) {
  if (is_problem(scene)) return scene.substr(8);
  return std::filesystem::path(scene).stem().string();
}

}  // namespace

void add_target_options(po::options_description& o) {
  o.add_options()("and", po::value<std::vector<std::string>>()->composing(),
                  "another SCENE or problem:NAME: the same study on each (a set), into "
                  "OUT/<name>, with OUT/set.md and one JUnit testsuite per target; repeatable")(
      "atol-ratio", po::value<double>()->default_value(0.01, "0.01"),
      "problem:NAME: atol = R x rtol where a case does not set atol (1: the test set's "
      "rtol = atol)");
}

std::vector<Target> targets_of(const po::variables_map& vm, const std::string& sub) {
  if (!vm.count("scene"))
    throw InputError("missing SCENE file or problem:NAME (evas study " + sub + " SCENE.yaml ...)");
  std::vector<std::string> scenes = {vm["scene"].as<std::string>()};
  if (vm.count("and"))
    for (const auto& a : vm["and"].as<std::vector<std::string>>()) scenes.push_back(a);
  const std::string out = vm.count("out") ? vm["out"].as<std::string>() : "";
  if (scenes.size() == 1) return {{scenes[0], out}};
  const std::filesystem::path base =
      std::filesystem::path(out.empty() ? std::string("out/study-set") : out);
  std::vector<Target> t;
  std::map<std::string, int> seen;
  for (const auto& sc : scenes) {
    std::string slug = target_slug(sc);
    if (++seen[slug] > 1) slug += "-" + std::to_string(seen[slug]);
    t.push_back({sc, (base / slug).string()});
  }
  return t;
}

int run_targets(const po::variables_map& vm, const std::vector<Target>& targets,
                const std::function<int(const Target&, study::CheckReport&)>& one) {
  std::vector<study::CheckReport> reports;
  std::vector<int> codes;
  for (const auto& t : targets) {
    study::CheckReport r;
    r.suite = t.scene;
    const int code = one(t, r);
    codes.push_back(code);
    reports.push_back(r);
    if (code >= 128) break;  // interrupted: the rest is not run
  }
  if (targets.size() > 1) {
    const std::filesystem::path base = std::filesystem::path(targets[0].out).parent_path();
    std::ostringstream md;
    md << "# Study set\n\n| target | output | result | checks |\n|---|---|---|---|\n";
    for (std::size_t i = 0; i < targets.size(); ++i) {
      const bool ran = i < codes.size();
      int failed = 0;
      if (ran)
        for (const auto& c : reports[i].checks) failed += c.passed ? 0 : 1;
      md << "| " << targets[i].scene << " | " << targets[i].out << " | "
         << (!ran            ? "not run"
             : codes[i] == 0 ? "completed"
                             : "exit " + std::to_string(codes[i]))
         << " | "
         << (ran ? std::to_string(reports[i].checks.size() - failed) + " of " +
                       std::to_string(reports[i].checks.size()) + " passed"
                 : "")
         << " |\n";
    }
    study::write_file_atomic(base / "set.md", md.str());
    std::cout << "\n" << md.str();
  }
  const int checks = finish_checks(vm, reports);
  for (int c : codes)
    if (c != 0) return c;
  return checks;
}

int study_compare(const std::vector<std::string>& args) {
  po::options_description opts(
      "usage: evas study compare A B [--rtol R] [--atol A] [--ignore GLOBS] [options]\n\n"
      "Compares two study tables (study.csv, convergence.csv, errors.csv, ... of two runs\n"
      "of a study), or every CSV table two folders both hold, cell by cell: rows matched\n"
      "by --key (default the first column, a case's label), columns by name; numbers\n"
      "agree when |a - b| <= atol + rtol max(|a|, |b|), texts when equal. Prints the\n"
      "differences (and rows or columns only one table has).\n\n"
      "Exit codes: 0 the tables agree, 1 bad input, 3 they differ.\n\noptions");
  opts.add_options()("help,h", "show this help")("rtol", po::value<double>()->default_value(1e-9),
                                                 "relative tolerance")(
      "atol", po::value<double>()->default_value(0.0), "absolute tolerance")(
      "ignore", po::value<std::string>()->default_value("wall,wall_seconds"),
      "comma-separated globs of the columns not compared (default: the wall times); '' "
      "compares every column")("key", po::value<std::string>(),
                               "the column that names the rows (default: the first)");
  add_report_options(opts);
  po::variables_map vm;
  if (parse_args(args, opts, {"a", "b"}, vm)) return 0;
  if (!vm.count("a") || !vm.count("b"))
    throw InputError("give two tables or folders: evas study compare A B");
  study::CompareOptions co;
  co.rtol = vm["rtol"].as<double>();
  co.atol = vm["atol"].as<double>();
  co.ignore.clear();
  for (const auto& g : study::split_list(vm["ignore"].as<std::string>(), ','))
    if (!g.empty()) co.ignore.push_back(g);
  if (vm.count("key")) co.key = vm["key"].as<std::string>();
  const auto res = study::compare_tables(vm["a"].as<std::string>(), vm["b"].as<std::string>(), co);
  std::cout << study::compare_report(res, co);
  study::CheckReport report{
      "compare " + vm["a"].as<std::string>(), command_line("evas study", args), 0.0, {}};
  study::Check c;
  c.name = "tables " + vm["a"].as<std::string>() + " and " + vm["b"].as<std::string>() + " agree";
  c.expected =
      "no cell beyond rtol " + study::gnum(co.rtol, 3) + ", atol " + study::gnum(co.atol, 3);
  c.measured = std::to_string(res.diffs.size()) + " differing of " + std::to_string(res.cells) +
               " cells, " + std::to_string(res.problems.size()) + " rows or columns unmatched";
  c.passed = res.same();
  if (!c.passed) c.message = c.measured;
  report.checks.push_back(c);
  return finish_checks(vm, report);
}

}  // namespace evas::cli
