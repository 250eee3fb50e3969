// Studies on the library problems (study_problem.h).
#include "apps/study_problem.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>
#include <set>
#include <sstream>

#include "apps/problem_run.h"
#include "apps/study_checks.h"
#include "integrators/settings.h"
#include "io/text_escape.h"
#include "plot/gnuplot.h"
#include "plot/study_figures.h"
#include "problems/published.h"
#include "study/report.h"
#include "study/study.h"

namespace evas::cli {

namespace fs = std::filesystem;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct ProblemCase {
  study::Case c;
  std::string formulation;
  ProblemRun run;
  bool ran = false;
  double error = kNaN;    ///< 10^-digits
  std::string component;  ///< the component that sets mescd (q3, v1, y5)
};

std::string problem_name(const std::string& target) { return target.substr(8); }

// Options of a scene study that do not apply to a problem.
void refuse_scene_options(const po::variables_map& vm) {
  for (const char* o : {"param", "t-end", "channels", "window", "reference-file", "initial",
                        "steady", "jobs", "max-wall", "expect-error"})
    if (vm.count(o))
      throw InputError(std::string("--") + o +
                       " does not apply to problem:NAME (a problem runs to its end point and is "
                       "scored against its published reference)");
  if (vm.count("reference") && !vm["reference"].defaulted())
    throw InputError(
        "--reference does not apply to problem:NAME: the reference is the "
        "published end point");
}

// "mescd" (the default) or "scd".
std::string digits_measure(const po::variables_map& vm) {
  const std::string n = vm["norm"].as<std::string>();
  if (vm["norm"].defaulted() || n == "mescd") return "mescd";
  if (n == "scd") return "scd";
  throw InputError("--norm '" + n + "': problem:NAME is scored in mescd or scd");
}

double atol_ratio(const po::variables_map& vm) {
  if (!vm.count("atol-ratio")) return 0.01;  // stability: evas problem's
  const double r = vm["atol-ratio"].as<double>();
  if (!(r > 0.0) || !std::isfinite(r)) throw InputError("--atol-ratio must be a positive number");
  return r;
}

std::string component_name(const problems::LibraryProblem& lp, int worst) {
  if (worst < 0) return "";
  if (lp.implicit()) return "y" + std::to_string(worst + 1);
  const int n = static_cast<int>(lp.reference_qv.size() / 2);
  return worst < n ? "q" + std::to_string(worst + 1) : "v" + std::to_string(worst - n + 1);
}

std::vector<ProblemCase> expand(const problems::LibraryProblem& lp,
                                const std::vector<std::pair<std::string, std::string>>& specs,
                                double ratio) {
  IntegratorSettings base;
  base.rtol = 1e-8;
  base.step = std::stod(study::gnum(lp.t_end / 2000.0, 12));  // 1.5e-05, not 1.4999999999999999e-05
  std::vector<ProblemCase> out;
  for (const auto& [spec, where] : specs)
    for (auto& c : study::expand_case(spec, base, where)) {
      ProblemCase pc;
      pc.c = std::move(c);
      pc.c.settings = problem_case_settings(pc.c.settings, spec, ratio);
      // the label names rtol always (settings_label leaves out a default value)
      pc.c.label = settings_label(pc.c.settings);
      if (pc.c.label.find(" rtol=") == std::string::npos) {
        const auto sp = pc.c.label.find(' ');
        const std::string r = " rtol=" + get_integrator_setting(pc.c.settings, "rtol");
        pc.c.label = sp == std::string::npos ? pc.c.label + r : pc.c.label.insert(sp, r);
      }
      pc.formulation = formulation_used(lp, pc.c.settings);
      out.push_back(std::move(pc));
    }
  return out;
}

void run_all(const problems::LibraryProblem& lp, std::vector<ProblemCase>& cases,
             const std::string& measure, int repeats, bool quiet) {
  if (repeats < 1) throw InputError("--repeats must be >= 1");
  for (std::size_t k = 0; k < cases.size(); ++k) {
    ProblemCase& pc = cases[k];
    try {
      // the wall time is the minimum over the repeats (warm-up left out)
      for (int rep = 0; rep < repeats; ++rep) {
        ProblemRun r = run_problem(lp, pc.c.settings);
        const double best = rep == 0 ? r.wall : std::min(r.wall, pc.run.wall);
        pc.run = std::move(r);
        pc.run.wall = best;
        if (!pc.run.failure.empty()) break;
      }
    } catch (const InputError& e) {
      pc.run.failure = e.what();  // a case the problem cannot take is a failed case
    }
    pc.ran = true;
    if (pc.run.failure.empty()) {
      const double d = measure == "scd" ? pc.run.score.scd : pc.run.score.mescd;
      pc.error = std::pow(10.0, -d);
      pc.component = component_name(lp, pc.run.score.worst);
    }
    if (!quiet) {
      std::cerr << "evas study: [" << k + 1 << "/" << cases.size() << "] " << pc.c.label << ": ";
      if (pc.run.failure.empty())
        std::cerr << "mescd " << study::gnum(pc.run.score.mescd, 4) << ", scd "
                  << study::gnum(pc.run.score.scd, 4) << ", " << pc.run.stats.steps << " steps, "
                  << study::gnum(pc.run.wall, 3) << " s\n";
      else
        std::cerr << "failed: " << pc.run.failure << "\n";
    }
  }
}

fs::path out_dir(const std::string& out, const problems::LibraryProblem& lp) {
  const fs::path d = !out.empty() ? fs::path(out) : fs::path("out") / ("study-problem-" + lp.name);
  std::error_code ec;
  fs::create_directories(d, ec);
  if (ec) throw InputError(d.string() + ": cannot create the output directory: " + ec.message());
  return d;
}

// The table of the cases: one row each.
std::string cases_csv(const std::vector<ProblemCase>& cases, const std::string& lead_name,
                      const std::vector<double>& lead, const std::vector<double>& order) {
  std::ostringstream os;
  os << "label,integrator,formulation,rtol,atol,step,";
  if (!lead_name.empty()) os << lead_name << ",order,";
  os << "status,message,error,error_component,mescd,scd,mescd_lambda,wall,steps,residual_evals,"
        "jacobian_evals,linear_setups,max_constraint_end\n";
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const ProblemCase& p = cases[k];
    const bool ok = p.ran && p.run.failure.empty();
    auto num = [&](double x) { return ok ? study::gnum(x, 9) : std::string(); };
    auto cnt = [&](long x) { return p.ran ? std::to_string(x) : std::string(); };
    os << csv_field(p.c.label) << "," << p.c.settings.name << "," << csv_field(p.formulation) << ","
       << study::gnum(p.c.settings.rtol, 9) << "," << study::gnum(p.c.settings.atol, 9) << ","
       << study::gnum(p.c.settings.step, 9) << ",";
    if (!lead_name.empty()) os << study::gnum(lead[k], 9) << "," << study::gnum(order[k], 6) << ",";
    os << (!p.ran ? "not run"
           : ok   ? "completed"
                  : "failed")
       << "," << csv_field(p.run.failure) << "," << num(p.error) << "," << p.component << ","
       << num(p.run.score.mescd) << "," << num(p.run.score.scd) << ","
       << (ok && std::isfinite(p.run.score.mescd_lambda) ? study::gnum(p.run.score.mescd_lambda, 9)
                                                         : std::string())
       << "," << (p.ran ? study::gnum(p.run.wall, 6) : "") << "," << cnt(p.run.stats.steps) << ","
       << cnt(p.run.stats.residual_evals) << "," << cnt(p.run.stats.jacobian_evals) << ","
       << cnt(p.run.stats.linear_setups) << "," << num(p.run.g_end) << "\n";
  }
  return os.str();
}

std::string header_md(const std::string& title, const problems::LibraryProblem& lp,
                      const std::string& measure, double ratio) {
  std::ostringstream md;
  md << "# " << title << ": problem " << lp.name << "\n\n"
     << "- problem: " << lp.description << "; end point t = " << study::gnum(lp.t_end, 6)
     << "\n- reference: the published end point (" << lp.source << ")\n"
     << "- digits: mescd = -log10 max_i |y_i - ref_i| / (atol/rtol + |ref_i|), scd = -log10 "
        "max_i |y_i - ref_i| / |ref_i| (test set, release 2.4); error = 10^-"
     << measure << "; atol = " << study::gnum(ratio, 6)
     << " rtol where a case does not set it (--atol-ratio; 1 is the test set's rtol = atol)\n\n";
  return md.str();
}

std::string status_md(const ProblemCase& p) {
  if (!p.ran) return "not run";
  if (!p.run.failure.empty()) return "failed: " + study::md_cell(p.run.failure, 70);
  return "completed";
}

// The curve of a case: its label without the accuracy knobs (rtol, atol,
// step) and the other knobs its spec sweeps.
std::string family_of(const study::Case& c) {
  std::set<std::string> strip = {"rtol", "atol", "step"};
  for (const auto& k : c.swept) strip.insert(k);
  std::istringstream is(settings_label(c.settings));
  std::string w, out;
  while (is >> w) {
    const auto eq = w.find('=');
    if (eq != std::string::npos && strip.count(w.substr(0, eq))) continue;
    out += (out.empty() ? "" : " ") + w;
  }
  return out;
}

// Two panels: digits against wall time (evas's cases) and against steps
// (evas's cases and the published solvers' runs).
std::string wp_script(const problems::LibraryProblem& lp, const std::vector<ProblemCase>& cases,
                      const std::vector<problems::PublishedRun>& pub, const std::string& measure,
                      const fs::path& png) {
  std::map<std::string, std::vector<const ProblemCase*>> fam;
  std::vector<std::string> order;
  for (const auto& p : cases) {
    if (!p.ran || !p.run.failure.empty() || !std::isfinite(p.error) || !(p.error > 0)) continue;
    std::string f = family_of(p.c);
    if (f.find("formulation=") == std::string::npos) f += " (" + p.formulation + ")";
    if (!fam.count(f)) order.push_back(f);
    fam[f].push_back(&p);
  }
  if (order.empty() && pub.empty()) return "";
  std::ostringstream gp;
  gp << "# work-precision of problem " << lp.name << " (evas study)\n"
     << gp_terminal(png, 1400, 600);
  for (std::size_t i = 0; i < order.size(); ++i) {
    for (const char* b : {"F", "S"}) {
      auto pts = fam[order[i]];
      const bool wall = b[0] == 'F';
      std::stable_sort(pts.begin(), pts.end(), [wall](const ProblemCase* a, const ProblemCase* c) {
        return wall ? a->run.wall < c->run.wall : a->run.stats.steps < c->run.stats.steps;
      });
      gp << "$" << b << i << " << EOD\n";
      for (const auto* p : pts)
        gp << gp_num(p->run.wall, 9) << " " << gp_num(-std::log10(p->error), 9) << " "
           << p->run.stats.steps << "\n";
      gp << "EOD\n";
    }
  }
  std::vector<std::string> solvers;
  for (const auto& r : pub)
    if (std::find(solvers.begin(), solvers.end(), r.solver) == solvers.end())
      solvers.push_back(r.solver);
  for (std::size_t i = 0; i < solvers.size(); ++i) {
    gp << "$P" << i << " << EOD\n";
    for (const auto& r : pub)
      if (r.solver == solvers[i])
        gp << r.steps << " " << gp_num(measure == "scd" ? r.scd : r.mescd, 6) << " "
           << gp_quote(study::gnum(r.tol, 3)) << "\n";
    gp << "EOD\n";
  }
  gp << "set multiplot layout 1,2 title "
     << gp_quote("work-precision: problem " + lp.name + " (digits " + measure +
                 " at the end point against the published reference)")
     << "\nset grid\nset logscale x\nset key inside left top vertical Left reverse box opaque\n"
     << "set ylabel " << gp_quote(measure + " (significant correct digits)") << "\n"
     << "set xlabel 'wall time [s]'\n";
  auto plot = [&](const char* block, const char* use, bool with_pub) {
    std::string cmd;
    for (std::size_t i = 0; i < order.size(); ++i)
      cmd += (cmd.empty() ? "" : ", ") + std::string("$") + block + std::to_string(i) + " using " +
             use + " with linespoints pt 7 title " + gp_quote("evas " + order[i]);
    if (with_pub)
      for (std::size_t i = 0; i < solvers.size(); ++i)
        cmd += (cmd.empty() ? "" : ", ") + std::string("$P") + std::to_string(i) +
               " using 1:2 with points pt " + std::to_string(4 + 2 * static_cast<int>(i)) +
               " ps 1.6 title " + gp_quote(solvers[i] + " (published, rtol = atol)");
    if (cmd.empty()) cmd = "NaN notitle";
    gp << "plot " << cmd << "\n";
  };
  gp << "unset key\n";
  plot("F", "1:2", false);
  // room above the curves for the legend
  gp << "set key\nset offsets graph 0, graph 0, graph 0.4, graph 0\nset xlabel 'steps'\n";
  plot("S", "3:2", true);
  gp << "unset multiplot\n";
  return gp.str();
}

void draw(const fs::path& script, const std::string& text, const fs::path& png, bool plot,
          bool quiet) {
  study::write_file_atomic(script, text);
  if (!plot || text.empty() || !study::have_gnuplot()) return;
  std::error_code ec;
  fs::remove(png, ec);
  if ((!study::run_gnuplot(script) || !fs::exists(png)) && !quiet)
    std::cerr << "evas study: gnuplot failed on " << script.string() << "\n";
}

// What both problem studies read first: the problem, its digits, atol's ratio.
struct Begun {
  const problems::LibraryProblem& lp;
  std::string measure;
  double ratio;
};

Begun begin(const po::variables_map& vm, const std::string& target) {
  refuse_scene_options(vm);
  return {problems::library_problem(problem_name(target)), digits_measure(vm), atol_ratio(vm)};
}

double total_wall(const std::vector<ProblemCase>& cases) {
  double t = 0.0;
  for (const auto& p : cases) t += p.ran ? p.run.wall : 0.0;
  return t;
}

std::vector<std::pair<std::string, std::string>> specs_of(const po::variables_map& vm) {
  std::vector<std::pair<std::string, std::string>> in;
  if (vm.count("case")) {
    if (vm["case"].value().type() == typeid(std::string))
      in.push_back({vm["case"].as<std::string>(), ""});
    else
      for (const auto& c : vm["case"].as<std::vector<std::string>>()) in.push_back({c, ""});
  }
  if (vm.count("cases"))
    for (const auto& p : study::read_cases_file(vm["cases"].as<std::string>())) in.push_back(p);
  return in;
}

}  // namespace

bool is_problem(const std::string& target) { return target.rfind("problem:", 0) == 0; }

std::string formulation_used(const problems::LibraryProblem& lp, const IntegratorSettings& s) {
  if (lp.implicit()) return "M y' = f";
  if (lp.make()->constraint_count() == 0) return "none";
  if (s.formulation != "default") return s.formulation;
  if (s.name == "ida") return "ggl";
  if (s.name == "radau" || s.name == "generalized-alpha" || s.name == "linear-acceleration")
    return "index-3";
  return "default (" + s.name + "'s)";
}

IntegratorSettings problem_case_settings(IntegratorSettings s, const std::string& spec,
                                         double atol_ratio) {
  if (spec.find("atol=") == std::string::npos) s.atol = s.rtol * atol_ratio;
  return s;
}

void problem_work_precision_study(const po::variables_map& vm, const std::vector<std::string>& args,
                                  const std::string& target, const std::string& out,
                                  study::CheckReport& report) {
  const Begun b = begin(vm, target);
  const problems::LibraryProblem& lp = b.lp;
  const std::string& measure = b.measure;
  const double ratio = b.ratio;
  auto specs = specs_of(vm);
  if (specs.empty()) {
    const std::string form = lp.implicit() ? "" : " formulation=index-2";
    specs = {{"ida rtol=1e-3..1e-10/8", ""}, {"radau rtol=1e-3..1e-10/8" + form, ""}};
  }
  std::vector<ProblemCase> cases = expand(lp, specs, ratio);
  const fs::path dir = out_dir(out, lp);
  const bool quiet = vm.count("quiet") > 0;
  run_all(lp, cases, measure, vm["repeats"].as<int>(), quiet);
  const auto pub = problems::published_runs(lp.name);

  study::write_file_atomic(dir / "study.csv", cases_csv(cases, "", {}, {}));
  std::ostringstream pc;
  pc << "solver,rtol_atol,mescd,scd,steps,source\n";
  for (const auto& r : pub)
    pc << r.solver << "," << study::gnum(r.tol, 6) << "," << study::gnum(r.mescd, 4) << ","
       << study::gnum(r.scd, 4) << "," << r.steps << "," << csv_field(problems::published_source())
       << "\n";
  study::write_file_atomic(dir / "published.csv", pc.str());
  std::ostringstream md;
  md << header_md("Work-precision study", lp, measure, ratio);
  md << "| case | formulation | status | mescd | scd | set by | wall [s] | steps | residuals |\n"
     << "|---|---|---|---:|---:|---|---:|---:|---:|\n";
  for (const auto& p : cases) {
    const bool ok = p.ran && p.run.failure.empty();
    md << "| " << study::md_cell(p.c.label) << " | " << p.formulation << " | " << status_md(p)
       << " | " << (ok ? study::gnum(p.run.score.mescd, 3) : "") << " | "
       << (ok ? study::gnum(p.run.score.scd, 3) : "") << " | " << p.component << " | "
       << (p.ran ? study::gnum(p.run.wall, 4) : "") << " | "
       << (p.ran ? std::to_string(p.run.stats.steps) : "") << " | "
       << (p.ran ? std::to_string(p.run.stats.residual_evals) : "") << " |\n";
  }
  md << "\n## Published solvers (rtol = atol)\n\n";
  if (pub.empty()) {
    md << "The test set's report gives no runs of this problem that evas lists.\n";
  } else {
    md << "From " << problems::published_source() << ".\n\n"
       << "| solver | rtol = atol | mescd | scd | steps |\n|---|---:|---:|---:|---:|\n";
    for (const auto& r : pub)
      md << "| " << r.solver << " | " << study::gnum(r.tol, 3) << " | " << study::gnum(r.mescd, 3)
         << " | " << study::gnum(r.scd, 3) << " | " << r.steps << " |\n";
  }
  study::write_file_atomic(dir / "study.md", md.str());
  std::cout << md.str();
  draw(dir / "study.gp", wp_script(lp, cases, pub, measure, dir / "study.png"), dir / "study.png",
       !vm.count("no-plot"), quiet);
  if (!quiet)
    for (const char* f : {"study.csv", "published.csv", "study.md", "study.gp", "study.png"})
      if (fs::exists(dir / f)) std::cerr << "  " << (dir / f).string() << "\n";

  report = study::CheckReport{
      "work-precision problem:" + lp.name, command_line("evas study", args), total_wall(cases), {}};
  if (vm.count("expect-digits")) {
    const double want = vm["expect-digits"].as<double>();
    for (const auto& p : cases) {
      study::Check c;
      c.name = measure + " of " + p.c.label;
      c.expected = ">= " + study::gnum(want, 4);
      const bool ok = p.run.failure.empty();
      const double d = measure == "scd" ? p.run.score.scd : p.run.score.mescd;
      c.measured = ok ? study::gnum(d, 4) : "none";
      c.passed = ok && d >= want;
      if (!c.passed)
        c.message = ok ? measure + " " + c.measured + " is below " + study::gnum(want, 4)
                       : "the run failed: " + p.run.failure;
      report.checks.push_back(c);
    }
  }
}

void problem_convergence(const po::variables_map& vm, const std::vector<std::string>& args,
                         const std::string& target, const std::string& out,
                         study::CheckReport& report) {
  const Begun b = begin(vm, target);
  const problems::LibraryProblem& lp = b.lp;
  const std::string& measure = b.measure;
  const double ratio = b.ratio;
  if (!vm.count("case")) throw InputError("missing --case SPEC (one family sweeping step or rtol)");
  const std::string spec = vm["case"].as<std::string>();
  std::vector<ProblemCase> cases = expand(lp, {{spec, ""}}, ratio);
  if (cases.empty() || cases.front().c.swept.size() != 1 ||
      (cases.front().c.swept.front() != "step" && cases.front().c.swept.front() != "rtol"))
    throw InputError("--case '" + spec +
                     "': a convergence study sweeps exactly one key, step or rtol");
  const std::string key = cases.front().c.swept.front();
  auto value = [&](const ProblemCase& p) {
    return key == "step" ? p.c.settings.step : p.c.settings.rtol;
  };
  std::stable_sort(cases.begin(), cases.end(),
                   [&](const ProblemCase& a, const ProblemCase& b) { return value(a) > value(b); });
  const fs::path dir = out_dir(out, lp);
  const bool quiet = vm.count("quiet") > 0;
  run_all(lp, cases, measure, vm["repeats"].as<int>(), quiet);
  std::vector<double> x, e, order(cases.size(), kNaN);
  int last = -1;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    x.push_back(value(cases[i]));
    e.push_back(cases[i].run.failure.empty() ? cases[i].error : kNaN);
    if (!(e[i] > 0) || !std::isfinite(e[i])) continue;
    if (last >= 0)
      order[i] = std::log(e[i] / e[static_cast<std::size_t>(last)]) /
                 std::log(x[i] / x[static_cast<std::size_t>(last)]);
    last = static_cast<int>(i);
  }
  int points = 0;
  const double slope = study::log_log_slope(x, e, &points);
  const std::string family = family_of(cases.front().c);

  study::write_file_atomic(dir / "convergence.csv", cases_csv(cases, "swept_" + key, x, order));
  std::ostringstream md;
  md << header_md("Convergence study", lp, measure, ratio);
  md << "| case | " << key
     << " | formulation | status | error | set by | order | wall [s] | "
        "steps |\n|---|---:|---|---|---:|---|---:|---:|---:|\n";
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const ProblemCase& p = cases[i];
    md << "| " << study::md_cell(p.c.label) << " | " << study::gnum(x[i], 6) << " | "
       << p.formulation << " | " << status_md(p) << " | " << study::sci(e[i], 3) << " | "
       << p.component << " | " << study::gnum(order[i], 3) << " | " << study::gnum(p.run.wall, 4)
       << " | " << p.run.stats.steps << " |\n";
  }
  md << "\n**observed order** (least-squares slope of log error against log " << key << ", "
     << points << " points): "
     << (std::isnan(slope) ? std::string("none (fewer than two completed cases)")
                           : study::gnum(slope, 4))
     << "\n";
  study::write_file_atomic(dir / "convergence.md", md.str());
  std::cout << md.str();
  draw(dir / "convergence.gp",
       convergence_script("problem " + lp.name, family,
                          "error 10^-" + measure + " against the published end point", key, x, e,
                          slope, dir / "convergence.png"),
       dir / "convergence.png", !vm.count("no-plot"), quiet);
  report = study::CheckReport{
      "convergence problem:" + lp.name, command_line("evas study", args), total_wall(cases), {}};
  if (vm.count("expect"))
    report.checks.push_back(order_check(family + " over " + key + " on " + lp.name, slope, points,
                                        vm["expect"].as<double>(), vm["tolerance"].as<double>()));
}

void problem_stability(const po::variables_map& vm, const std::vector<std::string>& args,
                       const std::string& target, const std::string& out, double h_min,
                       double h_max, double growth, int bisections, study::CheckReport& report) {
  const Begun b = begin(vm, target);
  const problems::LibraryProblem& lp = b.lp;
  if (!vm.count("case")) throw InputError("missing --case SPEC");
  if (!(h_min > 0.0) || !(h_max > h_min)) throw InputError("--step-range: need 0 < HMIN < HMAX");
  if (!(growth > 1.0)) throw InputError("--growth must be > 1");
  const std::string spec = vm["case"].as<std::string>();
  std::vector<ProblemCase> base = expand(lp, {{spec, ""}}, b.ratio);
  if (base.size() != 1)
    throw InputError("--case '" + spec + "': one case (it expands to " +
                     std::to_string(base.size()) + ")");
  if (!takes_fixed_steps(base[0].c.settings))
    throw InputError("--case '" + spec + "': " + base[0].c.settings.name +
                     " does not take fixed steps (step_control fixed or substep)");
  double ref_max = 0.0;
  for (double x : lp.implicit() ? lp.reference_y : lp.reference_qv)
    ref_max = std::max(ref_max, std::abs(x));
  struct Trial {
    double h;
    bool stable;
    std::string why;
    long steps;
  };
  std::vector<Trial> trials;
  const bool quiet = vm.count("quiet") > 0;
  auto stable = [&](double h) {
    IntegratorSettings s = base[0].c.settings;
    s.step = h;
    ProblemRun r;
    try {
      r = run_problem(lp, s);
    } catch (const InputError& e) {
      r.failure = e.what();
    }
    std::string why = r.failure;
    if (why.empty()) {
      double m = 0.0;
      for (const Vec* v : {&r.q, &r.v, &r.y})
        for (int i = 0; i < v->size(); ++i) m = std::max(m, std::abs((*v)(i)));
      if (!std::isfinite(m) || m > growth * ref_max)
        why = "end point max |y| = " + study::gnum(m, 4) + " > " + study::gnum(growth, 3) +
              " x the reference's " + study::gnum(ref_max, 4);
    }
    trials.push_back({h, why.empty(), why, r.stats.steps});
    if (!quiet)
      std::cerr << "evas study: h = " << study::gnum(h, 6) << ": "
                << (why.empty() ? "stable" : "unstable: " + why) << "\n";
    return why.empty();
  };
  std::string status;
  double lo = std::numeric_limits<double>::quiet_NaN(), hi = lo;
  if (stable(h_max)) {
    status = "stable up to HMAX";
    lo = h_max;
  } else if (!stable(h_min)) {
    // neither end ran a step, for the same reason: the case cannot run here
    if (trials[0].steps == 0 && trials[1].steps == 0 && trials[0].why == trials[1].why)
      throw InputError("--case '" + spec + "' does not run on problem " + lp.name + ": " +
                       trials[0].why);
    status = "unstable at HMIN";
    hi = h_min;
  } else {
    status = "bracketed";
    lo = h_min;
    hi = h_max;
    for (int k = 0; k < bisections; ++k) {
      const double mid = std::sqrt(lo * hi);
      (stable(mid) ? lo : hi) = mid;
    }
  }
  const fs::path dir = out_dir(out, lp);
  std::ostringstream csv, md;
  csv << "h,stable,steps,reason\n";
  for (const auto& t : trials)
    csv << study::gnum(t.h, 12) << "," << (t.stable ? 1 : 0) << "," << t.steps << ","
        << csv_field(t.why) << "\n";
  study::write_file_atomic(dir / "stability.csv", csv.str());
  md << "# Stability study: problem " << lp.name << "\n\n- case: " << family_of(base[0].c)
     << ", step searched in [" << study::gnum(h_min, 6) << ", " << study::gnum(h_max, 6) << "] s"
     << "\n- a step is stable when the run completes and its end point's largest |component| "
        "is at most "
     << study::gnum(growth, 3) << " x the published reference's (" << study::gnum(ref_max, 4)
     << ")\n- result: **" << status << "**; largest stable step "
     << (std::isnan(lo) ? std::string("none") : study::gnum(lo, 6)) << ", smallest unstable "
     << (std::isnan(hi) ? std::string("none") : study::gnum(hi, 6))
     << "\n\n| h [s] | stable | steps | reason |\n|---:|---|---:|---|\n";
  for (const auto& t : trials)
    md << "| " << study::gnum(t.h, 6) << " | " << (t.stable ? "yes" : "no") << " | " << t.steps
       << " | " << study::md_cell(t.why, 90) << " |\n";
  study::write_file_atomic(dir / "stability.md", md.str());
  std::cout << md.str();
  report =
      study::CheckReport{"stability problem:" + lp.name, command_line("evas study", args), 0.0, {}};
  if (vm.count("expect-stable-to")) {
    const double want = vm["expect-stable-to"].as<double>();
    study::Check c{"largest stable step of " + family_of(base[0].c) + " on " + lp.name,
                   std::isnan(lo) ? "none" : study::gnum(lo, 6), ">= " + study::gnum(want, 6),
                   lo >= want, ""};
    if (!c.passed) c.message = "search " + status + ": largest stable step " + c.measured;
    report.checks.push_back(c);
  }
}

}  // namespace evas::cli
