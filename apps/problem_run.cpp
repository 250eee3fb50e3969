#include "apps/problem_run.h"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <vector>

#include "dae/constraint_stats.h"
#include "dae/implicit_form.h"
#include "integrators/implicit_ida.h"
#include "integrators/implicit_radau.h"
#include "integrators/settings.h"
#include "run/run.h"
#include "study/report.h"

namespace evas::cli {

namespace {

ProblemRun run_implicit(const problems::LibraryProblem& lp, const IntegratorSettings& s) {
  if (s.name != "ida" && s.name != "radau")
    throw InputError("problem '" + lp.name +
                     "' is a first-order implicit DAE (M y' = f): ida and radau run it; '" +
                     s.name + "' takes the second-order form of the mechanical problems only");
  if (s.formulation != "default")
    throw InputError("problem '" + lp.name +
                     "' has no formulations (it is M y' = f as "
                     "published): leave --formulation out");
  ProblemRun r;
  auto problem = lp.make_implicit();
  ImplicitRun run = s.name == "radau" ? integrate_implicit_radau(*problem, lp.t_end, s)
                                      : integrate_implicit_ida(*problem, lp.t_end, s);
  r.y = std::move(run.y);
  r.wall = run.wall;
  r.stats = run.stats;
  r.failure = run.failure;
  if (r.failure.empty()) r.score = problems::score_implicit(lp, r.y, s.rtol, s.atol);
  return r;
}

// Radau IIA on a constrained mechanical problem: its first-order form
// y = (q, v, a, lambda) (dae/implicit_form.h), index-3 by default.
ProblemRun run_radau_first_order(const problems::LibraryProblem& lp, const IntegratorSettings& s) {
  auto problem = lp.make();
  const std::string form = s.formulation == "default" ? "index-3" : s.formulation;
  dae::ImplicitForm f(*problem, form);
  ImplicitRun run = integrate_implicit_radau(f, lp.t_end, s);
  ProblemRun r;
  const int n = f.n(), m = f.m();
  r.q = run.y.head(n);
  r.v = run.y.segment(n, n);
  r.lambda = run.y.tail(m);
  r.wall = run.wall;
  r.stats = run.stats;
  r.failure = run.failure;
  if (!r.failure.empty()) return r;
  r.score = problems::score(lp, r.q, r.v, r.lambda, s.rtol, s.atol);
  double gv = 0.0;
  dae::constraint_norms(*problem, lp.t_end, r.q, r.v, r.g_end, gv);
  return r;
}

}  // namespace

ProblemRun run_problem(const problems::LibraryProblem& lp, const IntegratorSettings& s) {
  if (lp.implicit()) return run_implicit(lp, s);
  if (s.name == "radau" && lp.make()->constraint_count() > 0) return run_radau_first_order(lp, s);
  ProblemRun r;
  auto problem = lp.make();
  run::EndState end = run::run_to_end(*problem, s, 0.0, lp.t_end);
  r.q = std::move(end.q);
  r.v = std::move(end.v);
  r.lambda = std::move(end.lambda);
  r.wall = end.outcome.wall;
  r.stats = end.outcome.stats;
  r.failure = end.outcome.message;
  if (!r.failure.empty()) return r;
  r.score = problems::score(lp, r.q, r.v, r.lambda, s.rtol, s.atol);
  double gv = 0.0;
  dae::constraint_norms(*problem, lp.t_end, r.q, r.v, r.g_end, gv);
  return r;
}

void problem_work_precision(const problems::LibraryProblem& lp, const std::filesystem::path& dir) {
  struct Row {
    std::string family, label;
    ProblemRun run;
  };
  std::vector<Row> rows;
  auto add = [&](const std::string& family, const std::string& label, const IntegratorSettings& s) {
    rows.push_back({family, label, run_problem(lp, s)});
    const Row& r = rows.back();
    std::cout << "  " << std::left << std::setw(27) << family << std::setw(14) << label
              << std::right;
    if (r.run.failure.empty())
      std::cout << " mescd " << std::fixed << std::setprecision(2) << std::setw(6)
                << r.run.score.mescd << std::defaultfloat << "  steps " << std::setw(7)
                << r.run.stats.steps << "  wall " << std::setprecision(3) << r.run.wall << " s\n";
    else
      std::cout << " FAILED: " << r.run.failure.substr(0, 100) << "\n";
  };
  std::cout << "evas problem " << lp.name << " --work-precision"
            << (lp.implicit() ? "" : " (atol = rtol / 100)") << "\n";
  // one family: an integrator in a formulation over rtol 1e-3 ... 1e-kmax
  auto family = [&](const std::string& label, const std::string& integrator,
                    const std::string& form, int kmax, double atol_share) {
    for (int k = 3; k <= kmax; ++k) {
      IntegratorSettings s;
      s.name = integrator;
      s.formulation = form;
      s.rtol = std::pow(10.0, -k);
      s.atol = atol_share * s.rtol;
      s.step = lp.t_end / 2000.0;
      add(label, "rtol 1e-" + std::to_string(k), s);
    }
  };
  if (lp.implicit()) {
    // both mixes of the tolerances for IDA: the test set's runs take atol = rtol
    family("ida atol=rtol", "ida", "default", 12, 1.0);
    family("ida atol=rtol/100", "ida", "default", 12, 0.01);
    family("radau atol=rtol", "radau", "default", 12, 1.0);
  } else {
    for (const char* f : {"ggl", "index-2", "index-1", "index-3"})
      family(std::string("ida ") + f, "ida", f, 10, 0.01);
    // Radau IIA on the first-order form in each of its formulations
    for (const char* f : {"index-3", "index-2", "index-1"})
      family(std::string("radau ") + f, "radau", f, 10, 0.01);
  }
  // the index-3 members of the Newmark family at fixed steps: generalized-alpha
  // (rho_inf 0.8) and HHT-alpha (alpha -0.1, HHT-I3)
  for (const char* method : {"generalized-alpha", "hht-alpha"})
    for (int k = 0; k < 8 && !lp.implicit(); ++k) {
      IntegratorSettings s;
      s.name = method;
      if (s.name == "hht-alpha") apply_setting_assignment(s, "alpha=-0.1");
      s.formulation = "index-3";
      s.step = lp.t_end / (250.0 * std::pow(2.0, k));
      s.step_control = StepControl::fixed;
      s.rtol = 1e-10;
      s.atol = 1e-12;
      std::ostringstream label;
      label << "h " << std::setprecision(3) << s.step;
      add(std::string(method) + " index-3", label.str(), s);
    }
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  const std::filesystem::path csv = dir / "work_precision.csv";
  std::ofstream f(csv);
  if (!f) throw InputError(csv.string() + ": cannot write the file");
  f << "family,case,status,mescd,scd,mescd_lambda,steps,residual_evals,jacobian_evals,"
       "wall_seconds,max_constraint_end\n";
  for (const Row& r : rows) {
    const bool ok = r.run.failure.empty();
    f << r.family << "," << r.label << "," << (ok ? "completed" : "failed") << ","
      << std::setprecision(6) << (ok ? r.run.score.mescd : NAN) << ","
      << (ok ? r.run.score.scd : NAN) << "," << (ok ? r.run.score.mescd_lambda : NAN) << ","
      << r.run.stats.steps << "," << r.run.stats.residual_evals << "," << r.run.stats.jacobian_evals
      << "," << r.run.wall << "," << r.run.g_end << "\n";
  }
  f.close();
  if (!f) throw InputError(csv.string() + ": writing failed");
  std::cout << "  table: " << csv.string() << "\n";
  if (!study::have_gnuplot()) return;
  const std::filesystem::path gp = dir / "work_precision.gp";
  std::ofstream g(gp);
  g << "set terminal pngcairo size 900,600 font 'sans,10'\nset output 'work_precision.png'\n"
    << "set datafile separator ','\nset logscale x\nset grid\nset key left top\n"
    << "set xlabel 'wall time [s]'\nset ylabel 'mescd (significant correct digits)'\n"
    << "set title '" << lp.name << ": work-precision of integrators and formulations'\n"
    << "plot ";
  std::vector<std::string> fams = {
      "ida ggl",       "ida index-2",   "ida index-1",   "ida index-3",
      "radau index-3", "radau index-2", "radau index-1", "generalized-alpha index-3"};
  if (lp.implicit()) fams = {"ida atol=rtol", "ida atol=rtol/100", "radau atol=rtol"};
  for (std::size_t k = 0; k < fams.size(); ++k)
    g << (k ? ", \\\n     " : "") << "'work_precision.csv' using (strcol(1) eq '" << fams[k]
      << "' && strcol(3) eq 'completed' ? $10 : 1/0):4 with linespoints title '" << fams[k] << "'";
  g << "\n";
  g.close();
  if (study::run_gnuplot(gp))
    std::cout << "  figure: " << (dir / "work_precision.png").string() << "\n";
}

}  // namespace evas::cli
