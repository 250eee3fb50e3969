// `evas study` work-precision (study.h): a grid of cases against one
// reference; the table study.csv/.md/.h5 and the figure study.png.
#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

#include "integrators/settings.h"
#include "plot/study_figures.h"
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

// Family of a case for the plots: its label without the accuracy knobs (rtol,
// atol, step: what moves a point along its curve) and without the other
// precision knobs its spec sweeps, so that one curve joins the cases that
// differ only in tolerance or step, and cases that differ in any other
// setting (a fixed balance_tol, max_step, a plug-in's own setting) are curves
// of their own.
std::string family_of(const Case& c) {
  static const std::set<std::string> knobs = {"balance_tol", "max_step", "min_step"};
  std::set<std::string> strip = {"rtol", "atol", "step"};
  for (const auto& k : c.swept)
    if (knobs.count(k)) strip.insert(k);
  return strip_keys(settings_label(c.settings), strip);
}

// The figure study.png, drawn by the code `evas plot work-precision` uses
// (plot/study_figures.h).
void plot_work_precision(const Options& opt, const WorkPrecisionResult& res, StudyInfo& info) {
  WorkPrecisionData d;
  d.scene_name = info.scene_name;
  d.window = info.window;
  d.norm = info.norm;
  d.reference = res.reference.description;
  d.work = opt.work;
  const std::string field = work_axis(opt.work).field;
  for (const auto& r : res.cases)
    if (r.status == CaseStatus::completed)
      for (const auto& f : stat_fields())
        if (field == f.name) d.points.push_back({family_of(r.c), r.wall, r.error, f.get(r.stats)});
  const fs::path png = fs::path(info.out_dir) / "study.png";
  const std::string gp = work_precision_script(d, png);
  if (!gp.empty()) plot(opt, fs::path(info.out_dir) / "study.gp", gp, info, png);
}

void write_work_precision(const Options& opt, WorkPrecisionResult& res,
                          const std::vector<int>& rows) {
  StudyInfo& info = res.info;
  const fs::path dir = info.out_dir;
  info.files.clear();
  const std::vector<Column> cols = case_columns(res.cases);
  write_file_atomic(dir / "study.csv", columns_csv(cols, res.cases.size()));
  info.files.push_back((dir / "study.csv").string());
  write_file_atomic(dir / "errors.csv", errors_csv(res.cases, res.reference, rows, info));
  info.files.push_back((dir / "errors.csv").string());

  std::ostringstream md;
  md << md_header("Work-precision study", info, opt, res.reference);
  md << "| case | status | error | set by | wall [s] | steps | residuals | Jacobians | "
        "factorisations | iterations | rejected steps | substeps |\n"
        "|---|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const auto& r : res.cases) {
    const bool ran = r.status != CaseStatus::not_run;
    auto n = [&](long v) { return ran ? std::to_string(v) : std::string(); };
    md << "| " << md_cell(r.c.label) << " | " << status_cell(r) << " | " << sci(r.error, 2) << " | "
       << md_cell(r.error_channel) << " | " << gnum(r.wall, 4) << " | " << n(r.stats.steps) << " | "
       << n(r.stats.residual_evals) << " | " << n(r.stats.jacobian_evals) << " | "
       << n(r.stats.linear_setups) << " | " << n(r.stats.nonlinear_iterations) << " | "
       << n(r.stats.error_test_failures + r.stats.convergence_failures) << " | "
       << n(r.stats.substeps) << " |\n";
  }
  md << "\nrejected steps = error-test plus convergence failures; factorisations = linear "
        "setups; iterations = nonlinear iterations; set by = the channel whose error is the "
        "case's. "
        "All statistics: study.csv, study.h5; every channel's error: errors.csv.\n";
  write_file_atomic(dir / "study.md", md.str());
  info.files.push_back((dir / "study.md").string());

  write_h5_atomic(dir / "study.h5", [&](hid_t f) {
    write_info_attributes(f, "work-precision", info, opt);
    h5::write_attribute(f, "work", opt.work);
    h5::Handle g = h5::create_group(f, "cases");
    write_columns_h5(g, cols);
    write_channel_errors_h5(g, res.cases, res.reference.names.size());
    // each case's family (a curve of the figure: evas plot work-precision)
    std::vector<std::string> families;
    for (const auto& r : res.cases) families.push_back(family_of(r.c));
    h5::write_strings(g, "family", families);
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
  const EmptyOutGuard no_empty_folder(s);
  std::vector<CaseInput> specs = specs_in;
  if (specs.empty())
    for (const auto& d : default_work_precision_cases()) specs.push_back({d, ""});
  std::vector<Case> cases = expand_all(specs, s.info.integrator);
  tie_iteration_tolerance(opt, cases, s.info.integrator);
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
