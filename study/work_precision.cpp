// `evas study` work-precision (study.h): a grid of cases against one
// reference; the table study.csv/.md/.h5 and the figure study.png.
#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

#include "integrators/settings.h"
#include "study/report.h"
#include "study/study.h"
#include "study/study_common.h"

namespace evas::study {

using namespace detail;

namespace {

std::vector<Case> expand_all(const std::vector<CaseInput>& specs, const IntegratorSettings& base) {
  std::vector<Case> cases;
  for (const auto& in : specs)
    for (auto& c : expand_case(in.spec, base, in.where)) cases.push_back(std::move(c));
  return cases;
}

// Family of a case for the plots: its label without the precision knobs, so
// one curve joins the cases that differ only in tolerance or step.
std::string family_of(const Case& c) {
  static const std::set<std::string> knobs = {"rtol",        "atol",     "step",
                                              "balance_tol", "max_step", "min_step"};
  return strip_keys(settings_label(c.settings), knobs);
}

void plot_work_precision(const Options& opt, const WorkPrecisionResult& res, StudyInfo& info) {
  std::map<std::string, std::vector<const CaseResult*>> fam;
  std::vector<std::string> order;
  for (const auto& r : res.cases) {
    if (r.status != CaseStatus::completed || !(r.error > 0.0) || !std::isfinite(r.error)) continue;
    const std::string f = family_of(r.c);
    if (!fam.count(f)) order.push_back(f);
    fam[f].push_back(&r);
  }
  if (order.empty()) return;
  // settings every curve shares (e.g. the scene's linear solver) go to the
  // title, so that the legend stays short enough not to cover the curves
  std::vector<std::string> common;  // "key=value" in every family
  std::set<std::string> common_keys;
  if (order.size() > 1) {
    std::istringstream first(order.front());
    std::string word;
    first >> word;  // the integrator's name
    while (first >> word) {
      bool all = true;
      for (const auto& f : order)
        all = all && (" " + f + " ").find(" " + word + " ") != std::string::npos;
      if (all) {
        common.push_back(word);
        common_keys.insert(word.substr(0, word.find('=')));
      }
    }
  }
  std::vector<std::string> legend;
  for (const auto& f : order) legend.push_back(strip_keys(f, common_keys));
  // one legend for both panels, in two columns below them
  const int key_rows = static_cast<int>((order.size() + 1) / 2);
  const fs::path png = fs::path(info.out_dir) / "study.png";
  std::ostringstream gp;
  gp << "# work-precision figure of " << info.scene_name << " (evas study)\n"
     << gp_terminal(png, 1400, 560 + 18 * key_rows);
  for (std::size_t i = 0; i < order.size(); ++i) {
    auto pts = fam[order[i]];
    std::sort(pts.begin(), pts.end(),
              [](const CaseResult* a, const CaseResult* b) { return a->error > b->error; });
    gp << "$F" << i << " << EOD\n";
    for (const auto* p : pts)
      gp << gnum(p->wall, 9) << " " << gnum(p->error, 9) << " " << p->stats.residual_evals << "\n";
    gp << "EOD\n";
  }
  gp << "set multiplot layout 1,2 title "
     << gp_quote("work-precision: " + info.scene_name + " (" + info.window + ", norm " + info.norm +
                 ")" + (common.empty() ? "" : "; all curves: " + join(common, " ")))
     << "\n"
     << "set logscale xy\nset format y '1e%L'\nset grid\nset bmargin " << key_rows + 5 << "\n"
     << "set key at screen 0.02,screen 0.01 left bottom vertical maxrows " << key_rows
     << " Left reverse samplen 2 width -4\n"
     << "set ylabel 'error (relative to each channel amplitude)'\n";
  auto curves = [&](const char* using_) {
    gp << "plot ";
    for (std::size_t i = 0; i < order.size(); ++i)
      gp << (i ? ", " : "") << "$F" << i << " using " << using_ << " with linespoints pt "
         << (i < 8 ? 7 : 5) << " title " << gp_quote(legend[i]);  // past 8 the colours repeat
    gp << "\n";
  };
  gp << "set xlabel 'wall time [s]'\n";
  curves("1:2");
  gp << "set xlabel 'residual evaluations'\nunset key\n";
  curves("3:2");
  gp << "unset multiplot\n";
  plot(opt, fs::path(info.out_dir) / "study.gp", gp.str(), info, png);
}

void write_work_precision(const Options& opt, WorkPrecisionResult& res,
                          const std::vector<int>& rows) {
  StudyInfo& info = res.info;
  const fs::path dir = info.out_dir;
  info.files.clear();
  const std::vector<Column> cols = case_columns(res.cases);
  write_file_atomic(dir / "study.csv", columns_csv(cols, res.cases.size()));
  info.files.push_back((dir / "study.csv").string());

  std::ostringstream md;
  md << md_header("Work-precision study", info, opt, res.reference);
  md << "| case | status | error | wall [s] | steps | residuals | Jacobians | factorisations | "
        "iterations | rejected steps | substeps |\n"
        "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const auto& r : res.cases) {
    const bool ran = r.status != CaseStatus::not_run;
    auto n = [&](long v) { return ran ? std::to_string(v) : std::string(); };
    md << "| " << md_cell(r.c.label) << " | " << status_cell(r) << " | " << sci(r.error, 2) << " | "
       << gnum(r.wall, 4) << " | " << n(r.stats.steps) << " | " << n(r.stats.residual_evals)
       << " | " << n(r.stats.jacobian_evals) << " | " << n(r.stats.linear_setups) << " | "
       << n(r.stats.nonlinear_iterations) << " | "
       << n(r.stats.error_test_failures + r.stats.convergence_failures) << " | "
       << n(r.stats.substeps) << " |\n";
  }
  md << "\nrejected steps = error-test plus convergence failures; factorisations = linear "
        "setups; iterations = nonlinear iterations. All statistics: study.csv, study.h5.\n";
  write_file_atomic(dir / "study.md", md.str());
  info.files.push_back((dir / "study.md").string());

  write_h5_atomic(dir / "study.h5", [&](hid_t f) {
    write_info_attributes(f, "work-precision", info, opt);
    h5::Handle g = h5::create_group(f, "cases");
    write_columns_h5(g, cols);
    write_reference_h5(f, res.reference, rows);
  });
  info.files.push_back((dir / "study.h5").string());
}

}  // namespace

std::vector<std::string> default_work_precision_cases() {
  return {"ida rtol=1e-3..1e-8/6", "cvode rtol=1e-3..1e-8/6",
          "generalized-alpha step=4e-5,2e-5,1e-5,5e-6",
          "linear-acceleration step=4e-5,2e-5,1e-5,5e-6"};
}

// --- work-precision -------------------------------------------------------------

WorkPrecisionResult work_precision(const Options& opt, const std::vector<CaseInput>& specs_in) {
  Setup s = prepare(opt);
  std::vector<CaseInput> specs = specs_in;
  if (specs.empty())
    for (const auto& d : default_work_precision_cases()) specs.push_back({d, ""});
  const std::vector<Case> cases = expand_all(specs, s.info.integrator);
  if (opt.reference_file.empty()) reference_case(opt.reference, s.info.integrator);

  WorkPrecisionResult res;
  say(opt, "evas study: scene '" + s.info.name + "', " + std::to_string(cases.size()) + " cases, " +
               std::to_string(s.names.size()) + " channels, " +
               std::to_string(s.info.times.size()) + " output times -> " + s.out.string());
  res.reference = make_reference(opt, s);
  const std::vector<int> rows = reference_rows(opt, s, res.reference);
  res.info = make_info(s);
  for (const auto& c : cases) {
    CaseResult r;
    r.c = c;
    res.cases.push_back(r);
  }
  write_work_precision(opt, res, rows);
  run_cases(opt, s, cases, res.reference, rows, res.cases, res.info,
            [&] { write_work_precision(opt, res, rows); });
  write_work_precision(opt, res, rows);
  plot_work_precision(opt, res, res.info);
  return res;
}

}  // namespace evas::study
