// `evas problem NAME`: a test problem of the library (problems/library.h) run
// from t = 0 to its reference end point with any integrator and formulation,
// scored in significant correct digits as the IVP Test Set scores.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "apps/commands.h"
#include "apps/problem_run.h"
#include "apps/study_checks.h"
#include "apps/study_problem.h"
#include "integrators/integrator.h"
#include "integrators/settings.h"
#include "io/text_escape.h"
#include "problems/library.h"
#include "study/report.h"

namespace evas::cli {

namespace {

std::string json_number(double x) {
  std::ostringstream os;
  os << std::setprecision(16) << x;
  return std::isfinite(x) ? os.str() : "null";
}

// DIR/summary.json of one run: its settings, status ("completed" or "failed:
// ..."), statistics and, when it completed, its end point and digits. A failed
// run's summary is written too, so that a sweep over tolerances keeps a record
// of every case.
void write_summary(const std::filesystem::path& dir, const problems::LibraryProblem& lp,
                   const IntegratorSettings& s, const ProblemRun& run) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  std::ofstream f(dir / "summary.json");
  if (!f) throw InputError((dir / "summary.json").string() + ": cannot write the file");
  const bool ok = run.failure.empty();
  f << "{\n  \"problem\": " << json_string(lp.name)
    << ",\n  \"integrator\": " << json_string(s.name)
    << ",\n  \"formulation\": " << json_string(formulation_used(lp, s))
    << ",\n  \"rtol\": " << json_number(s.rtol) << ",\n  \"atol\": " << json_number(s.atol)
    << ",\n  \"t_end\": " << json_number(lp.t_end)
    << ",\n  \"status\": " << json_string(ok ? "completed" : "failed: " + run.failure);
  if (ok && lp.implicit()) {
    f << ",\n  \"mescd\": " << json_number(run.score.mescd)
      << ",\n  \"scd\": " << json_number(run.score.scd) << ",\n  \"y\": [";
    for (int i = 0; i < run.y.size(); ++i) f << (i ? ", " : "") << json_number(run.y(i));
    f << "]";
  } else if (ok) {
    const int n = static_cast<int>(run.q.size());
    f << ",\n  \"mescd\": " << json_number(run.score.mescd)
      << ",\n  \"scd\": " << json_number(run.score.scd)
      << ",\n  \"mescd_lambda\": " << json_number(run.score.mescd_lambda) << ",\n  \"q\": [";
    for (int i = 0; i < n; ++i) f << (i ? ", " : "") << json_number(run.q(i));
    f << "],\n  \"v\": [";
    for (int i = 0; i < n; ++i) f << (i ? ", " : "") << json_number(run.v(i));
    f << "]";
  }
  f << ",\n  \"wall_seconds\": " << json_number(run.wall) << ",\n  \"stats\": {\n"
    << stats_json_members(run.stats, "    ") << "\n  }";
  if (ok && !lp.implicit()) f << ",\n  \"max_constraint_end\": " << json_number(run.g_end);
  f << "\n}\n";
  if (!f) throw InputError((dir / "summary.json").string() + ": writing failed");
  std::cout << "  summary: " << (dir / "summary.json").string() << "\n";
}

void list_problems() {
  for (const auto& p : problems::library()) {
    std::cout << std::left << std::setw(10) << p.name;
    if (p.implicit())
      std::cout << " M y' = f, n = " << p.make_implicit()->size();
    else
      std::cout << " n = " << p.make()->size() << ", m = " << p.make()->constraint_count();
    std::cout << ", t_end = " << p.t_end << ": " << p.description << "\n";
  }
}

}  // namespace

int cmd_problem(const std::vector<std::string>& args) {
  po::options_description opts(
      "usage: evas problem NAME [options]   (evas problem --list)\n\n"
      "Runs a test problem of the library from t = 0 to the end point of its published\n"
      "reference with the chosen integrator and formulation, and prints the end point\n"
      "against the reference, the mixed-error significant correct digits\n"
      "  mescd = -log10 max_i |y_i - ref_i| / (atol/rtol + |ref_i|)\n"
      "over positions and velocities (and over the multipliers where published), the\n"
      "relative digits scd, and the integrator's statistics (docs/problems.md).\n"
      "Exit codes: 0 completed, 1 bad input, 2 the integration failed.\n\noptions");
  opts.add_options()("help,h", "show this help")("list", "list the problems")(
      "integrator", po::value<std::string>()->default_value("ida"),
      (builtin_integrator_list() + " or a loaded plug-in").c_str())(
      "formulation", po::value<std::string>()->default_value("default"),
      "index-3, index-2, ggl, index-1, penalty or default (the integrator's: ida ggl; radau "
      "index-3, on the first-order form (q, v, a, lambda), which takes index-3/2/1 only)")(
      "rtol", po::value<std::string>()->default_value("1e-8"), "relative tolerance")(
      "atol", po::value<std::string>(), "absolute tolerance (default rtol / 100)")(
      "step", po::value<std::string>(),
      "step of the fixed-step integrators (default t_end / 2000), first step of the others")(
      "set", po::value<std::vector<std::string>>(),
      "KEY=VALUE: any integrator setting, repeatable (evas run --help-settings)")(
      "out", po::value<std::string>(),
      "folder for summary.json, written also when the run fails (and the sweep's files); "
      "one that holds an earlier run's summary.json is refused without --overwrite")(
      "overwrite", "replace the summary.json of an earlier run in --out")(
      "work-precision",
      "sweep IDA in every formulation and radau in index-3/2/1 over rtol 1e-3..1e-10 and "
      "generalized-alpha over 8 step halvings (first-order problems: ida and radau over "
      "1e-3..1e-12); writes OUT/work_precision.csv and .png")(
      "expect-digits", po::value<double>(),
      "a check that the run's mescd is at least D: exit 3 when it is not (with --junit: the "
      "testcase)");
  add_report_options(opts);
  po::variables_map vm;
  if (parse_args(args, opts, {"name"}, vm)) return 0;
  if (vm.count("list")) {
    list_problems();
    return 0;
  }
  if (!vm.count("name")) throw InputError("name a problem (evas problem --list shows them)");
  const problems::LibraryProblem& lp = problems::library_problem(vm["name"].as<std::string>());

  IntegratorSettings s;
  set_integrator_setting(s, "name", vm["integrator"].as<std::string>());
  set_integrator_setting(s, "formulation", vm["formulation"].as<std::string>());
  set_integrator_setting(s, "rtol", vm["rtol"].as<std::string>());
  if (vm.count("atol"))
    set_integrator_setting(s, "atol", vm["atol"].as<std::string>());
  else
    s.atol = s.rtol / 100.0;
  s.step = lp.t_end / 2000.0;
  if (vm.count("step")) set_integrator_setting(s, "step", vm["step"].as<std::string>());
  if (vm.count("set"))
    for (const auto& a : vm["set"].as<std::vector<std::string>>()) apply_setting_assignment(s, a);
  if (!vm.count("work-precision")) warn_unread_settings("problem", vm, s);

  if (vm.count("work-precision")) {
    if (!vm.count("out")) throw InputError("--work-precision needs --out DIR for its table");
    problem_work_precision(lp, vm["out"].as<std::string>());
    return 0;
  }
  if (vm.count("out") && !vm.count("overwrite")) {
    const std::filesystem::path earlier =
        std::filesystem::path(vm["out"].as<std::string>()) / "summary.json";
    std::error_code ec;
    if (std::filesystem::exists(earlier, ec))
      throw InputError(earlier.string() +
                       ": the folder holds an earlier run's summary: give --overwrite to "
                       "replace it, or choose another folder with --out DIR");
  }
  std::cout << "evas problem " << lp.name << ": " << lp.description << "\n"
            << "  integrator " << s.name << ", formulation " << formulation_used(lp, s) << ", rtol "
            << s.rtol << ", atol " << s.atol << "; reference: " << lp.source << "\n";
  const ProblemRun run = run_problem(lp, s);
  if (!run.failure.empty()) {
    std::cerr << "evas problem: FAILED: " << run.failure << "\n";
    if (vm.count("out")) write_summary(vm["out"].as<std::string>(), lp, s, run);
    if (vm.count("expect-digits")) {
      study::CheckReport report{"problem " + lp.name, command_line("evas", args), run.wall, {}};
      report.checks.push_back({"mescd of " + settings_label(s) + " on " + lp.name, "none",
                               ">= " + study::gnum(vm["expect-digits"].as<double>(), 4), false,
                               "the run failed: " + run.failure});
      finish_checks(vm, report);
    }
    return 2;
  }
  const problems::Score& sc = run.score;
  const IntegratorStats& st = run.stats;
  const double wall = run.wall, gmax = run.g_end;
  std::cout << "  end point t = " << lp.t_end << ":\n"
            << "    component            value                  reference              "
               "mixed error\n";
  const double ratio = s.atol / s.rtol;
  auto row = [&](const std::string& label, double y, double r, bool worst) {
    std::cout << "    " << std::left << std::setw(20) << label << std::right << std::setw(23)
              << std::setprecision(15) << y << std::setw(23) << r << std::setw(12)
              << std::setprecision(3) << std::abs(y - r) / (ratio + std::abs(r))
              << (worst ? "  <- worst" : "") << "\n";
  };
  if (lp.implicit()) {
    const auto problem = lp.make_implicit();
    for (int i = 0; i < run.y.size(); ++i)
      row(problem->component_name(i), run.y(i), lp.reference_y[static_cast<std::size_t>(i)],
          i == sc.worst);
  } else {
    const auto problem = lp.make();
    const int n = problem->size();
    for (int i = 0; i < 2 * n; ++i)
      row((i < n ? "q " : "v ") + problem->describe_coordinate(i < n ? i : i - n),
          i < n ? run.q(i) : run.v(i - n), lp.reference_qv[static_cast<std::size_t>(i)],
          i == sc.worst);
  }
  std::cout << std::setprecision(4) << "  mescd " << std::fixed << std::setprecision(2) << sc.mescd
            << "  scd " << sc.scd;
  if (!std::isnan(sc.mescd_lambda)) std::cout << "  mescd(lambda) " << sc.mescd_lambda;
  std::cout << std::defaultfloat << std::setprecision(4) << "\n  steps " << st.steps
            << ", residuals " << st.residual_evals << ", Jacobians " << st.jacobian_evals
            << ", factorisations " << st.linear_setups << ", error-test failures "
            << st.error_test_failures << ", convergence failures " << st.convergence_failures
            << ", wall " << wall << " s";
  if (!lp.implicit()) std::cout << "; at the end |g| " << gmax;
  std::cout << "\n";
  if (vm.count("out")) write_summary(vm["out"].as<std::string>(), lp, s, run);
  study::CheckReport report{"problem " + lp.name, command_line("evas", args), wall, {}};
  if (vm.count("expect-digits")) {
    const double want = vm["expect-digits"].as<double>();
    study::Check c{"mescd of " + settings_label(s) + " on " + lp.name, study::gnum(sc.mescd, 4),
                   ">= " + study::gnum(want, 4), sc.mescd >= want, ""};
    if (!c.passed) c.message = "mescd " + c.measured + " is below " + study::gnum(want, 4);
    report.checks.push_back(c);
  }
  return finish_checks(vm, report);
}

}  // namespace evas::cli
