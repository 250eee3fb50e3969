// evas study work-precision|convergence|stability SCENE: compare integrators on a
// scene. The logic is in study/ (study/study.h); this file parses options.
#include <boost/program_options.hpp>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <sstream>

#include "apps/commands.h"
#include "apps/mpi_runner.h"
#include "apps/study_amplification.h"
#include "apps/study_checks.h"
#include "apps/study_problem.h"
#include "apps/study_set.h"
#include "integrators/settings.h"
#include "plot/study_figures.h"
#include "study/budget.h"
#include "study/budget_files.h"
#include "study/compare.h"
#include "study/report.h"
#include "study/study.h"
#include "study/sweep.h"

namespace evas::cli {

namespace {

volatile std::sig_atomic_t g_stop = 0;

extern "C" void on_study_signal(int sig) {
  g_stop = sig;               // the signal number: the exit code is 128 + it
  std::signal(sig, SIG_DFL);  // a second signal ends the process at once
}

// Installs the SIGINT/SIGTERM/SIGHUP handlers for the life of a study.
class SignalGuard {
 public:
  SignalGuard() {
    g_stop = 0;
    int_ = std::signal(SIGINT, on_study_signal);
    term_ = std::signal(SIGTERM, on_study_signal);
    hup_ = std::signal(SIGHUP, on_study_signal);
  }
  ~SignalGuard() {
    std::signal(SIGINT, int_);
    std::signal(SIGTERM, term_);
    std::signal(SIGHUP, hup_);
  }
  SignalGuard(const SignalGuard&) = delete;
  SignalGuard& operator=(const SignalGuard&) = delete;

 private:
  void (*int_)(int) = SIG_DFL;
  void (*term_)(int) = SIG_DFL;
  void (*hup_)(int) = SIG_DFL;
};

const char* kOverview =
    "usage: evas study <sub-command> SCENE.yaml [options]\n"
    "\n"
    "Compares integrators on a scene against a reference run (docs/study.md).\n"
    "\n"
    "sub-commands:\n"
    "  work-precision SCENE  error, wall time and statistics of a grid of cases\n"
    "                        (--case, repeatable); writes study.csv/.md/.h5/.png\n"
    "  convergence SCENE     observed order of one family sweeping step or rtol\n"
    "                        (--case); writes convergence.csv/.md/.png\n"
    "  stability SCENE       largest stable fixed step of one case (--case,\n"
    "                        --step-range), optionally over a parameter sweep;\n"
    "                        writes stability.csv/.md/.png\n"
    "  sweep SCENE           a grid of operating points (--sweep ITEM.KEY=VALUES,\n"
    "                        repeatable): every point's channels, order cuts,\n"
    "                        waterfall, Campbell diagram; writes sweep.h5/.csv/.md/.png\n"
    "  budget SCENE          the error budget of the scene's answer: integration,\n"
    "                        start-up, modal basis, element model, each measured with\n"
    "                        its cost; writes budget.csv/.md, budget_sources.csv\n"
    "  amplification         the one-step amplification of integrators (--case ...): spectral\n"
    "                        radius, damping and period error against h/T\n"
    "  compare A B           two study tables (CSV files, or folders of them) cell by\n"
    "                        cell with --rtol/--atol: a regression check (exit 3 when\n"
    "                        they differ)\n"
    "\n"
    "Every sub-command runs its cases on --jobs N local worker processes, or on the\n"
    "ranks of `mpirun -n N evas study ...`; the files are the same as a serial run's.\n"
    "\n"
    "`evas study <sub-command> --help` lists the options.\n"
    "Exit codes: 0 the study completed (failed cases are results), 1 bad input,\n"
    "2 the reference run failed, 3 a check (--expect, --expect-error, --expect-stable-to,\n"
    "--expect-digits) failed, 128 + N stopped by signal N (130: "
    "Ctrl-C).\n";

const char* kGrid =
    "Case spec: \"NAME KEY=V1,V2 KEY=A..B/N ...\": NAME an integrator (ida, cvode,\n"
    "generalized-alpha, linear-acceleration), KEY any integrator setting (the keys of\n"
    "`evas run --set`, see --help-settings). A comma list gives several values, A..B/N\n"
    "N log-spaced values from A to B inclusive; the case grid is the cartesian product.\n"
    "Settings a spec does not name keep the scene's integrator block.\n"
    "Example: --case \"ida rtol=1e-3..1e-7/5\" --case \"generalized-alpha step=2e-5,1e-5\"\n";

// Options of every sub-command.
void add_common(po::options_description& o, bool errors = true) {
  o.add_options()("help,h", "show this help")(
      "help-settings", "list every integrator setting (the KEYs of a case spec)")(
      "param,p", po::value<std::vector<std::string>>()->composing(),
      "ITEM.KEY=VALUE: change a scene parameter before the study, repeatable. ITEM is a glob "
      "over the names of bodies, markers and elements (every match changes; e.g. "
      "'main*.clearance=5e-5') or time, integrator, output, operating_point; KEY may go deeper "
      "with dots (shaft.lof.speed); VALUE is YAML (3e-5, quadrature, [1e6, 1e6, 1e6])")(
      "t-end", po::value<double>(), "end time [s] (shortcut for --param time.end=X)")(
      "channels", po::value<std::string>(),
      "comma-separated globs over the output channel names, e.g. 'main*.fx,main*.fy' "
      "(default: every channel except crank_angle)")(
      "out", po::value<std::string>(), "output directory (default out/study-<scene name>)")(
      "jobs,j", po::value<int>(),
      "runs at once, each in a worker process of its own (one thread each); default: the "
      "number of cores for sweep, else 1 (work-precision and convergence measure wall "
      "times; stability runs one search per --sweep value at once). Under mpirun the ranks "
      "are the workers (docs/study.md)")(
      "max-wall", po::value<double>(),
      "wall-clock limit of one case or sweep task (with --repeats: of all its runs) [s]: one "
      "that takes longer fails with 'timed out' and the study goes on")(
      "initial", po::value<std::string>(),
      "every run (the reference's too) starts from the state in FILE (evas periodic's "
      "DIR/state.yaml) in place of the scene's initial state")(
      "no-plot", "do not run gnuplot (the .gp script is still written)")("quiet,q",
                                                                         "no progress lines");
  if (!errors) return;  // a sweep measures no error: no reference, window or norm
  o.add_options()(
      "window", po::value<std::string>(),
      "output times the error is taken over: all | last-cycles=N (crank-angle grid: the "
      "last N x 720 degrees) | T0:T1 [s] (default: last-cycles=1 on a crank-angle grid, "
      "else all)")(
      "norm", po::value<std::string>()->default_value(study::kDefaultNorm),
      "the error measure (docs/study.md): group = max over channels c and window times of "
      "|y - y_ref| / A_g (default: a channel that barely moves counts on the scale of its "
      "unit's largest); channel (or max) = the same over A_c; rms = RMS over the window / "
      "A_c; floor=F = max |y - y_ref| / max(A_c, F A_g); l2 = relative L2 norm over the "
      "window per unit group; final = |y - y_ref| / A_g at the last time. A_c = max over the "
      "window of |y_ref - mean(y_ref)|, A_g = the largest A_c among the selected channels of "
      "c's unit. errors.csv gives every channel's error and names the one that sets it")(
      "reference", po::value<std::string>()->default_value(study::kDefaultReference),
      "case spec of the reference run (one case)")(
      "reference-expr", po::value<std::vector<std::string>>()->composing(),
      "CHANNEL=EXPR: an analytic reference, EXPR of t [s] (numbers, t, pi, e, + - * / ^, "
      "sin cos tan exp log sqrt abs sinh cosh tanh atan), one per channel compared "
      "(repeatable; they select the channels), e.g. 'c.px=1e-3*sin(2*pi*15.9*t)'")(
      "reference-file", po::value<std::string>(),
      "compare against this results file (evas run) instead of a reference run; channels "
      "are matched by name and times within 1e-9 relative")(
      "steady",
      "every run is one period from the scene's periodic state (found first with evas "
      "periodic's projected method and the scene's own integrator, or --initial FILE's): "
      "the error is the integration error on the steady cycle, without the start-up")(
      "steady-tol", po::value<double>()->default_value(3e-4, "3e-4"),
      "with --steady: the periodicity defect of the state found");
}

void add_cases(po::options_description& o) {
  o.add_options()("case,c", po::value<std::vector<std::string>>()->composing(),
                  "case spec \"NAME KEY=V1,V2 KEY=A..B/N ...\", repeatable")(
      "cases", po::value<std::string>(), "file of case specs, one per line ('#' comments)")(
      "repeats", po::value<int>()->default_value(1),
      "runs per case; the wall time (init + integrate) is the minimum");
}

study::Options common_options(const po::variables_map& vm, const std::string& sub) {
  study::Options o;
  if (!vm.count("scene"))
    throw InputError("missing SCENE file (evas study " + sub + " SCENE.yaml [options])");
  o.scene = vm["scene"].as<std::string>();
  if (vm.count("param")) o.params = vm["param"].as<std::vector<std::string>>();
  if (vm.count("t-end")) {
    const double t = vm["t-end"].as<double>();
    if (!std::isfinite(t)) throw InputError("--t-end must be a finite number");
    o.t_end = t;
  }
  if (vm.count("channels")) o.channels = vm["channels"].as<std::string>();
  if (vm.count("window")) o.window = vm["window"].as<std::string>();
  if (vm.count("norm")) o.norm = vm["norm"].as<std::string>();
  if (vm.count("reference")) o.reference = vm["reference"].as<std::string>();
  const bool reference_given = vm.count("reference") && !vm["reference"].defaulted();
  if (vm.count("reference-expr")) {
    o.reference_exprs = vm["reference-expr"].as<std::vector<std::string>>();
    if (reference_given || vm.count("reference-file"))
      throw InputError("give one reference: --reference, --reference-file or --reference-expr");
    if (sub == "stability" || sub == "sweep" || sub == "budget")
      throw InputError("--reference-expr applies to work-precision and convergence");
  }
  if (vm.count("reference-file")) {
    o.reference_file = vm["reference-file"].as<std::string>();
    if (reference_given) throw InputError("give --reference or --reference-file, not both");
  }
  if (vm.count("repeats")) o.repeats = vm["repeats"].as<int>();
  if (vm.count("out")) o.out_dir = vm["out"].as<std::string>();
  o.plot = !vm.count("no-plot");
  if (vm.count("initial")) o.start.initial_file = vm["initial"].as<std::string>();
  o.start.steady = vm.count("steady") > 0;
  if (vm.count("steady-tol")) o.start.tol = vm["steady-tol"].as<double>();
  if (o.start.steady && sub == "sweep")
    throw InputError("--steady: a sweep's points are steady cycles with --periodic");
  if (!vm.count("quiet")) o.log = &std::cerr;
  o.stop = [] { return g_stop != 0; };
  if (vm.count("max-wall")) {
    o.max_wall = vm["max-wall"].as<double>();
    if (!(o.max_wall > 0.0) || !std::isfinite(o.max_wall))
      throw InputError("--max-wall must be a positive number of seconds");
  }
  const int default_jobs = sub == "sweep" ? study::available_cores() : 1;
  const int jobs = vm.count("jobs") ? vm["jobs"].as<int>() : default_jobs;
  if (jobs < 1) throw InputError("--jobs must be >= 1");
  if (mpi_job().active) {
    if (vm.count("jobs"))
      throw InputError("--jobs does not apply under mpirun: the " + std::to_string(mpi_job().size) +
                       " ranks are the workers");
    o.runner = mpi_runner();
  } else if (jobs > 1) {
    // a worker stuck inside one step is killed a while after its task's --max-wall
    o.runner = study::process_runner(jobs);
  }
  study::parse_measure(o.norm);  // bad values are input errors before anything runs
  return o;
}

// Parses a sub-command's options; true when --help or --help-settings was
// answered (the command then ends with 0).
bool parse_or_help(const std::vector<std::string>& args, const po::options_description& opts,
                   po::variables_map& vm) {
  if (parse_args(args, opts, {"scene"}, vm)) return true;
  if (vm.count("help-settings")) {
    std::cout << settings_reference();
    return true;
  }
  return false;
}

std::vector<study::CaseInput> case_inputs(const po::variables_map& vm) {
  std::vector<study::CaseInput> in;
  if (vm.count("case"))
    for (const auto& c : vm["case"].as<std::vector<std::string>>()) in.push_back({c, ""});
  if (vm.count("cases"))
    for (const auto& [spec, where] : study::read_cases_file(vm["cases"].as<std::string>()))
      in.push_back({spec, where});
  return in;
}

void print_files(const study::StudyInfo& info, bool quiet) {
  if (quiet) return;
  for (const auto& f : info.files) std::cerr << "  " << f << "\n";
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// A reference run cut short by a signal is an interrupt (128 + N), else exit 2.
int reference_failed_code() { return g_stop > 0 ? 128 + static_cast<int>(g_stop) : 2; }

int finish(const study::StudyInfo& info, bool quiet) {
  print_files(info, quiet);
  if (info.interrupted) {
    std::cerr << "evas study: interrupted; the outputs hold the cases run so far\n";
    return 128 + (g_stop > 0 ? static_cast<int>(g_stop) : SIGINT);  // 130 for Ctrl-C
  }
  return 0;
}

int work_precision(const std::vector<std::string>& args) {
  po::options_description opts(
      "usage: evas study work-precision SCENE.yaml [--case SPEC]... [options]\n\n"
      "Runs every case of the case grid and the reference on the scene and measures each\n"
      "case's error against the reference, its wall time and all integrator statistics.\n"
      "A failed case is recorded with its message and the study goes on. Writes\n"
      "DIR/study.csv (every setting and statistic), study.md (table), study.h5 (the\n"
      "same table plus the reference channels) after every case, and study.png\n"
      "(gnuplot: error against wall time and against residual evaluations, one curve\n"
      "per integrator family) at the end. Ctrl-C / SIGTERM: stop after the current run,\n"
      "mark the rest 'not run', write the outputs, exit 130.\n\n"
      "Default cases: \"ida rtol=1e-3..1e-8/6\", \"cvode rtol=1e-3..1e-8/6\",\n"
      "\"generalized-alpha step=4e-5,2e-5,1e-5,5e-6\",\n"
      "\"linear-acceleration step=4e-5,2e-5,1e-5,5e-6\".\n\n" +
      std::string(kGrid) +
      "\nExit codes: 0 completed (even with failed cases), 1 bad input, 2 the reference\n"
      "failed, 3 an --expect-error check failed, 128 + N stopped by signal N (130: "
      "Ctrl-C).\n\noptions");
  add_cases(opts);
  opts.add_options()("work", po::value<std::string>()->default_value("residuals"),
                     "the figure's second work axis beside wall time: residuals, steps, "
                     "factorizations, jacobians or iterations")(
      "expect-error", po::value<std::vector<std::string>>()->composing(),
      "CHANNELS<=TOL[@CASE]: a check per case (CASE a glob over the case labels, default "
      "all) that the largest error of the channel globs is at most TOL; exit 3 when one "
      "fails (with --junit: one testcase each), repeatable")(
      "expect-digits", po::value<double>(),
      "problem:NAME only: a check per case that its mescd is at least D");
  add_target_options(opts);
  add_report_options(opts);
  add_common(opts);
  po::variables_map vm;
  if (parse_or_help(args, opts, vm)) return 0;
  if (vm.count("expect-error"))  // malformed expressions before anything runs
    for (const auto& e : vm["expect-error"].as<std::vector<std::string>>()) parse_error_expect(e);
  work_axis(vm["work"].as<std::string>());  // a bad axis is an input error before anything runs
  const auto targets = targets_of(vm, "work-precision");
  SignalGuard guard;
  return run_targets(vm, targets, [&](const Target& t, study::CheckReport& report) {
    if (is_problem(t.scene)) {
      problem_work_precision_study(vm, args, t.scene, t.out, report);
      return 0;
    }
    if (vm.count("expect-digits"))
      throw InputError("--expect-digits applies to problem:NAME (scenes: --expect-error)");
    study::Options o = common_options(vm, "work-precision");
    o.scene = t.scene;
    o.out_dir = t.out;
    o.work = vm["work"].as<std::string>();
    try {
      const auto res = study::work_precision(o, case_inputs(vm));
      std::cout << read_text(res.info.out_dir + "/study.md");
      if (const int code = finish(res.info, vm.count("quiet") > 0)) return code;
      report = study::CheckReport{"work-precision " + res.info.scene_name,
                                  command_line("evas study", args),
                                  res.reference.wall,
                                  {}};
      if (vm.count("expect-error"))
        for (const auto& e : vm["expect-error"].as<std::vector<std::string>>())
          for (auto& c : error_checks(e, res.cases, res.reference.names))
            report.checks.push_back(std::move(c));
      return 0;
    } catch (const study::ReferenceFailed& e) {
      std::cerr << "evas study work-precision: " << t.scene << ": " << e.what() << "\n";
      return reference_failed_code();
    }
  });
}

int convergence(const std::vector<std::string>& args) {
  po::options_description opts(
      "usage: evas study convergence SCENE.yaml --case SPEC [options]\n\n"
      "Runs one family sweeping step or rtol (e.g. --case \"generalized-alpha\n"
      "step_control=fixed step=4e-5..2.5e-6/5\") against the reference and reports the\n"
      "error at every value, the order between successive values, log(e_i/e_(i-1)) /\n"
      "log(x_i/x_(i-1)), and the observed order: the least-squares slope of log(error)\n"
      "against log(step or rtol) over the completed cases. Prints the slope; writes\n"
      "DIR/convergence.csv, convergence.md and convergence.png.\n"
      "With --expect ORDER the exit code is 3 when |slope - ORDER| > --tolerance (or no\n"
      "slope could be fitted), for use in CI.\n\n" +
      std::string(kGrid) +
      "\nExit codes: 0 completed, 1 bad input, 2 the reference failed, 3 --expect not\n"
      "met, 128 + N stopped by signal N (130: Ctrl-C).\n\noptions");
  opts.add_options()("case,c", po::value<std::string>(), "the case family (one spec)")(
      "repeats", po::value<int>()->default_value(1),
      "runs per case; the wall time (init + integrate) is the minimum")(
      "expect", po::value<double>(), "expected order: exit 3 when the slope is off")(
      "tolerance", po::value<double>()->default_value(0.1),
      "allowed |slope - expected order| with --expect");
  add_target_options(opts);
  add_report_options(opts);
  add_common(opts);
  po::variables_map vm;
  if (parse_or_help(args, opts, vm)) return 0;
  if (!vm.count("case")) throw InputError("missing --case SPEC (one family sweeping step or rtol)");
  if (vm.count("tolerance") && !(vm["tolerance"].as<double>() >= 0))
    throw InputError("--tolerance must be >= 0");
  const auto targets = targets_of(vm, "convergence");
  SignalGuard guard;
  return run_targets(vm, targets, [&](const Target& t, study::CheckReport& report) {
    if (is_problem(t.scene)) {
      problem_convergence(vm, args, t.scene, t.out, report);
      return 0;
    }
    study::Options o = common_options(vm, "convergence");
    o.scene = t.scene;
    o.out_dir = t.out;
    try {
      const auto res = study::convergence(o, {vm["case"].as<std::string>(), ""});
      std::cout << "observed order (least-squares slope of log error against log " << res.key
                << ", " << res.points << " points): ";
      if (std::isnan(res.slope))
        std::cout << "none (fewer than two completed cases with a positive error)\n";
      else
        std::cout << study::gnum(res.slope, 4) << "\n";
      if (const int code = finish(res.info, vm.count("quiet") > 0)) return code;
      report = study::CheckReport{"convergence " + res.info.scene_name,
                                  command_line("evas study", args),
                                  res.reference.wall,
                                  {}};
      if (vm.count("expect"))
        report.checks.push_back(order_check(res.family + " over " + res.key, res.slope, res.points,
                                            vm["expect"].as<double>(),
                                            vm["tolerance"].as<double>()));
      return 0;
    } catch (const study::ReferenceFailed& e) {
      std::cerr << "evas study convergence: " << t.scene << ": " << e.what() << "\n";
      return reference_failed_code();
    }
  });
}

int stability(const std::vector<std::string>& args) {
  po::options_description opts(
      "usage: evas study stability SCENE.yaml --case SPEC --step-range HMIN:HMAX [options]\n\n"
      "Finds the largest fixed step h in [HMIN, HMAX] at which one case (generalized-alpha,\n"
      "linear-acceleration or radau; its own step is ignored) completes and stays stable: for\n"
      "every selected channel, max |y| over the run (after the first output) is at most\n"
      "--growth times the reference run's. HMAX is tried first (\"stable up to HMAX\"),\n"
      "then HMIN (\"unstable at HMIN\" if not), then --bisections bisections in log h.\n"
      "With --sweep ITEM.KEY=V1,V2,... (ITEM.KEY as for --param; A..B/N log ranges\n"
      "allowed) the search is repeated on each changed scene, with its own reference\n"
      "run. Use step_control=fixed in the case so that a failed step is not cut.\n"
      "Writes DIR/stability.csv, stability.md and (with --sweep) stability.png, the\n"
      "largest stable step against the swept parameter. --window and --norm do not\n"
      "apply (the whole run is checked).\n\n"
      "Exit codes: 0 completed, 1 bad input, 2 the reference failed (without --sweep;\n"
      "with it the point is marked 'reference failed'), 3 --expect-stable-to not met, 128 + N "
      "stopped by signal N (130: "
      "Ctrl-C).\n\noptions");
  opts.add_options()("case,c", po::value<std::string>(), "the case (one integrator setting)")(
      "step-range", po::value<std::string>(), "HMIN:HMAX, the steps searched [s]")(
      "sweep", po::value<std::string>(),
      "ITEM.KEY=V1,V2,...: repeat the search over a scene parameter")(
      "growth", po::value<double>()->default_value(10.0),
      "largest allowed max|y| / reference max|y| per channel")(
      "bisections", po::value<int>()->default_value(12), "bisections in log h")(
      "expect-stable-to", po::value<double>(),
      "H: a check per sweep point that the largest stable step is at least H; exit 3 when "
      "one fails");
  add_report_options(opts);
  add_common(opts);
  po::variables_map vm;
  if (parse_or_help(args, opts, vm)) return 0;
  if (!vm.count("case")) throw InputError("missing --case SPEC");
  if (!vm.count("step-range")) throw InputError("missing --step-range HMIN:HMAX");
  study::StabilityOptions so;
  {
    const std::string r = vm["step-range"].as<std::string>();
    const auto colon = r.find(':');
    char* e1 = nullptr;
    char* e2 = nullptr;
    const std::string a = colon == std::string::npos ? "" : r.substr(0, colon);
    const std::string b = colon == std::string::npos ? "" : r.substr(colon + 1);
    so.h_min = std::strtod(a.c_str(), &e1);
    so.h_max = std::strtod(b.c_str(), &e2);
    if (a.empty() || b.empty() || *e1 || *e2)
      throw InputError("--step-range '" + r + "': expected HMIN:HMAX in seconds");
  }
  if (vm.count("sweep")) so.sweep = vm["sweep"].as<std::string>();
  so.growth = vm["growth"].as<double>();
  so.bisections = vm["bisections"].as<int>();
  if (vm.count("scene") && is_problem(vm["scene"].as<std::string>())) {
    if (vm.count("sweep")) throw InputError("--sweep applies to scenes, not problem:NAME");
    study::CheckReport report;
    problem_stability(vm, args, vm["scene"].as<std::string>(),
                      vm.count("out") ? vm["out"].as<std::string>() : "", so.h_min, so.h_max,
                      so.growth, so.bisections, report);
    return finish_checks(vm, report);
  }
  const study::Options o = common_options(vm, "stability");
  SignalGuard guard;
  try {
    const auto res = study::stability(o, {vm["case"].as<std::string>(), ""}, so);
    std::cout << read_text(res.info.out_dir + "/stability.md");
    if (const int code = finish(res.info, vm.count("quiet") > 0)) return code;
    study::CheckReport report{
        "stability " + res.info.scene_name, command_line("evas study", args), 0.0, {}};
    if (vm.count("expect-stable-to"))
      report.checks = stable_checks(vm["expect-stable-to"].as<double>(), res);
    return finish_checks(vm, report);
  } catch (const study::ReferenceFailed& e) {
    std::cerr << "evas study stability: " << e.what() << "\n";
    return reference_failed_code();
  }
}

std::vector<double> parse_orders(const std::string& text) {
  std::vector<double> out;
  for (const auto& item : study::split_list(text, ',')) {
    char* end = nullptr;
    const double o = std::strtod(item.c_str(), &end);
    if (item.empty() || *end || !std::isfinite(o))
      throw InputError("--orders '" + text + "': '" + item + "' is not a number");
    if (std::abs(o * 2.0 - std::round(o * 2.0)) > 1e-9)
      throw InputError("--orders '" + text + "': " + item +
                       " is not a multiple of 0.5 (a four-stroke cycle resolves orders in "
                       "steps of 0.5)");
    out.push_back(o);
  }
  return out;
}

int sweep(const std::vector<std::string>& args) {
  po::options_description opts(
      "usage: evas study sweep SCENE.yaml --sweep ITEM.KEY=VALUES [--sweep ...] [options]\n\n"
      "Runs the scene at every point of a grid of scene parameters: each --sweep\n"
      "ITEM.KEY=VALUES changes the scene as --param does (ITEM a glob over the names of\n"
      "bodies, markers and elements), the grid is the cartesian product (first key\n"
      "slowest). VALUES: a comma list, A..B:STEP (linear, B inclusive) or A..B/N (N\n"
      "log-spaced). Each point runs with the scene's integrator, or once per case of\n"
      "--case/--cases. Writes DIR/points/NNNN.h5 (one per run, as it ends),\n"
      "sweep.csv and sweep.md (after every run), sweep.h5 (the grid, every run's\n"
      "status, statistics and channels, order spectra, mean speeds, Campbell data)\n"
      "and, on a crank-angle grid, order_cuts.png, waterfall.png and campbell.png.\n"
      "A failed or timed-out run (--max-wall) is recorded with its reason and the\n"
      "others go on. --resume keeps the completed runs of an interrupted sweep;\n"
      "--point I runs run I alone into DIR/points (a batch array job) and --merge\n"
      "then builds the sweep files.\n\n"
      "Example: evas study sweep validation/engine/engine.yaml --t-end 0.12 \\\n"
      "  --sweep 'crank.lof.speed=157.08..523.6:52.36' --order-channels 'main3.fy'\n\n"
      "Exit codes: 0 completed (even with failed runs), 1 bad input, 128 + N stopped\n"
      "by signal N (130: Ctrl-C).\n\noptions");
  opts.add_options()("sweep,s", po::value<std::vector<std::string>>()->composing(),
                     "ITEM.KEY=VALUES, repeatable")(
      "orders", po::value<std::string>()->default_value("1,2,4"),
      "engine orders of the order cuts (multiples of 0.5)")(
      "max-order", po::value<double>()->default_value(12.0),
      "highest order kept in the spectra and drawn in the Campbell diagram")(
      "cycles", po::value<int>()->default_value(1),
      "engine cycles (720 deg, at the end of each run) per spectrum")(
      "order-channels", po::value<std::string>(),
      "globs of the channels drawn in the order cuts (up to 4) and the waterfall (the first); "
      "default: the first selected channel")(
      "point", po::value<int>(), "run task INDEX only, into DIR/points (batch array jobs)")(
      "merge", "run nothing: build the sweep files from DIR/points")(
      "resume", "continue an interrupted sweep in DIR: completed runs are kept")(
      "periodic", po::value<std::string>()->implicit_value("projected"),
      "every point as its steady cycle (evas periodic, this method: projected, anderson, "
      "fixed-point, newton), not a run from rest to --t-end (docs/periodic.md)")(
      "periodic-tol", po::value<double>()->default_value(3e-4, "3e-4"),
      "with --periodic: the periodicity defect at which a point's cycle is accepted")(
      "cold-start",
      "with --periodic: every point's search from the scene's initial state, not from the "
      "periodic state of the point before it");
  add_cases(opts);
  add_common(opts, false);
  // the options of the error-measuring studies, which a sweep's help leaves out:
  // said by name rather than as unknown
  for (const std::string& a : args)
    for (const char* opt : {"--window", "--norm", "--reference", "--reference-expr",
                            "--reference-file", "--steady", "--steady-tol"})
      if (a == opt || a.rfind(std::string(opt) + "=", 0) == 0)
        throw InputError(std::string(opt) +
                         " does not apply to a sweep (it measures no error; --periodic makes "
                         "every point its steady cycle)");
  po::variables_map vm;
  if (parse_or_help(args, opts, vm)) return 0;
  const study::Options o = common_options(vm, "sweep");
  study::SweepOptions so;
  if (vm.count("sweep")) so.sweeps = vm["sweep"].as<std::vector<std::string>>();
  so.cases = case_inputs(vm);
  so.orders = parse_orders(vm["orders"].as<std::string>());
  so.max_order = vm["max-order"].as<double>();
  so.cycles = vm["cycles"].as<int>();
  if (vm.count("periodic")) so.periodic = vm["periodic"].as<std::string>();
  so.periodic_tol = vm["periodic-tol"].as<double>();
  so.warm_start = !vm.count("cold-start");
  if (vm.count("cold-start") && so.periodic.empty())
    throw InputError("--cold-start: needs --periodic (a transient point starts from the scene)");
  if (vm.count("order-channels")) so.order_channels = vm["order-channels"].as<std::string>();
  if (vm.count("point")) {
    so.point = vm["point"].as<int>();
    if (so.point < 0) throw InputError("--point must be >= 0");
  }
  so.merge = vm.count("merge") > 0;
  so.resume = vm.count("resume") > 0;
  SignalGuard guard;
  const auto res = study::sweep(o, so);
  if (so.point < 0) std::cout << read_text(res.info.out_dir + "/sweep.md");
  if (res.info.interrupted) {
    std::size_t done = 0;
    for (const auto& t : res.tasks) done += t.result.status != study::CaseStatus::not_run;
    std::cerr << "evas study sweep: interrupted after " << done << " of " << res.tasks.size()
              << " tasks; they are kept in " << res.info.out_dir
              << "/points: run the same command with --resume to run the rest\n";
  }
  return finish(res.info, vm.count("quiet") > 0);
}

int budget(const std::vector<std::string>& args) {
  po::options_description opts(
      "usage: evas study budget SCENE.yaml [--richer ITEM.KEY=VALUE]...\n"
      "                         [--finer ITEM.KEY=VALUE]... [options]\n\n"
      "The error budget of the scene's answer as the scene sets it up (its integrator,\n"
      "basis, elements, start): beside that base run, one variation per source of error,\n"
      "each removing it, and per channel the difference over the base's last cycle:\n"
      "  integration  rtol and atol (a fixed step) divided by --tighten;\n"
      "  start-up     the last cycle against the periodic cycle (evas periodic), or\n"
      "               against the cycle before when the search does not converge;\n"
      "  basis        the scene on a richer basis: the --richer edits, else every mode\n"
      "               of the body files that the scene's modes: options leave out;\n"
      "  element      finer element models: the --finer edits, else every journal\n"
      "               bearing on film reynolds (short and finite films are coarser).\n"
      "With each, the variation's wall time and steps against the base's: what removing\n"
      "that source costs; the largest error names the dominant source. Writes\n"
      "DIR/budget.csv (per channel), budget_sources.csv and budget.md; `evas report`\n"
      "shows the budget when budget_sources.csv lies beside the results file (give the\n"
      "run's output folder as --out).\n\n"
      "Exit codes: 0 completed, 1 bad input, 2 the base run failed, 128 + N stopped by\n"
      "signal N (130: Ctrl-C).\n\noptions");
  opts.add_options()("richer", po::value<std::vector<std::string>>()->composing(),
                     "ITEM.KEY=VALUE: the richer basis, as --param (e.g. crank.file=rich.h5), "
                     "repeatable")("finer", po::value<std::vector<std::string>>()->composing(),
                                   "ITEM.KEY=VALUE: the finer element models, as --param (e.g. "
                                   "main1.grid_phi=144), repeatable")(
      "tighten", po::value<double>()->default_value(100.0, "100"),
      "the tighter integration: rtol and atol (or a fixed step) "
      "divided by this")(
      "orders", po::value<double>(),
      "compare the engine orders up to N only (the last cycle's Fourier series; a "
      "crank-angle grid)");
  add_common(opts);
  po::variables_map vm;
  if (parse_or_help(args, opts, vm)) return 0;
  study::Options o = common_options(vm, "budget");
  if (!vm["reference"].defaulted() || vm.count("reference-file"))
    throw InputError("--reference and --reference-file do not apply to a budget");
  if (o.start.steady) throw InputError("--steady does not apply: the budget measures the start-up");
  study::BudgetOptions bo;
  if (vm.count("richer")) bo.richer = vm["richer"].as<std::vector<std::string>>();
  if (vm.count("finer")) bo.finer = vm["finer"].as<std::vector<std::string>>();
  bo.tighten = vm["tighten"].as<double>();
  if (vm.count("orders")) bo.orders = vm["orders"].as<double>();
  if (o.out_dir.empty()) {
    const study::SceneSource src = study::load_scene_source(o.scene, o.params, o.t_end);
    o.out_dir = "out/budget-" + study::probe_scene(src).name;
  }
  SignalGuard guard;
  try {
    const auto res = study::budget(o, bo);
    std::cout << study::budget_markdown(res);
    return finish(res.info, vm.count("quiet") > 0);
  } catch (const study::ReferenceFailed& e) {
    std::cerr << "evas study budget: " << e.what() << "\n";
    return reference_failed_code();
  }
}

}  // namespace

int cmd_study(const std::vector<std::string>& args) {
  if (args.size() < 2 || args[1] == "--help" || args[1] == "-h" || args[1] == "help") {
    std::cout << kOverview;
    return args.size() < 2 ? 1 : 0;
  }
  const std::vector<std::string> sub(args.begin() + 1, args.end());
  if (sub[0] == "work-precision") return work_precision(sub);
  if (sub[0] == "convergence") return convergence(sub);
  if (sub[0] == "stability") return stability(sub);
  if (sub[0] == "sweep") return sweep(sub);
  if (sub[0] == "budget") return budget(sub);
  if (sub[0] == "compare") return study_compare(sub);
  if (sub[0] == "amplification") return study_amplification(sub);
  std::cerr << "evas study: unknown sub-command '" << sub[0] << "'\n\n" << kOverview;
  return 1;
}

}  // namespace evas::cli
