// `evas study` convergence (study.h): one family sweeping step or rtol, the
// observed order (log_log_slope); convergence.csv/.md/.png.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "integrators/settings.h"
#include "plot/study_figures.h"
#include "study/report.h"
#include "study/study.h"
#include "study/study_common.h"

namespace evas::study {

using namespace detail;

// --- convergence ----------------------------------------------------------------

namespace {

void write_convergence(const Options& opt, ConvergenceResult& res, const std::vector<int>& rows,
                       bool final) {
  StudyInfo& info = res.info;
  const fs::path dir = info.out_dir;
  info.files.clear();
  // CSV: the swept value and orders in front of the full case table
  std::vector<Column> cols = case_columns(res.cases);
  // the swept value as a number (the settings column `step` or `rtol` holds it as text)
  Column x{"swept_" + res.key, "swept_" + res.key, Column::Kind::Real, {}, res.x};
  Column po{"order", "order", Column::Kind::Real, {}, res.pair_order};
  cols.insert(cols.begin() + 1, po);
  cols.insert(cols.begin() + 1, x);
  write_file_atomic(dir / "convergence.csv", columns_csv(cols, res.cases.size()));
  info.files.push_back((dir / "convergence.csv").string());
  write_file_atomic(dir / "errors.csv", errors_csv(res.cases, res.reference, rows, info));
  info.files.push_back((dir / "errors.csv").string());

  std::ostringstream md;
  md << md_header("Convergence study", info, opt, res.reference);
  md << "| case | " << res.key
     << " | status | error | set by | order | wall [s] | steps | "
        "residuals |\n"
     << "|---|---:|---|---:|---|---:|---:|---:|---:|\n";
  for (std::size_t i = 0; i < res.cases.size(); ++i) {
    const auto& r = res.cases[i];
    const bool ran = r.status != CaseStatus::not_run;
    md << "| " << md_cell(r.c.label) << " | " << gnum(res.x[i], 6) << " | " << status_cell(r)
       << " | " << sci(r.error, 3) << " | " << md_cell(r.error_channel) << " | "
       << gnum(res.pair_order[i], 3) << " | " << gnum(r.wall, 4) << " | "
       << (ran ? std::to_string(r.stats.steps) : "") << " | "
       << (ran ? std::to_string(r.stats.residual_evals) : "") << " |\n";
  }
  md << "\norder: log(e_i / e_(i-1)) / log(" << res.key << "_i / " << res.key
     << "_(i-1)) between successive cases.\n\n";
  md << "**observed order** (least-squares slope of log error against log " << res.key << ", "
     << res.points << " points): "
     << (std::isnan(res.slope) ? std::string("not enough points") : gnum(res.slope, 4)) << "\n";
  write_file_atomic(dir / "convergence.md", md.str());
  info.files.push_back((dir / "convergence.md").string());

  if (!final) return;
  // drawn by the code of plot/study_figures.h
  std::vector<double> errors;
  for (const auto& r : res.cases)
    errors.push_back(r.status == CaseStatus::completed ? r.error : kNaN);
  const fs::path png = dir / "convergence.png";
  const std::string gp =
      convergence_script(info.scene_name, res.family,
                         "--norm " + info.norm + ", reference " + res.reference.description,
                         res.key, res.x, errors, res.slope, png);
  if (!gp.empty()) plot(opt, dir / "convergence.gp", gp, info, png);
}

}  // namespace

double log_log_slope(const std::vector<double>& x, const std::vector<double>& e, int* used) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (std::size_t i = 0; i < x.size() && i < e.size(); ++i) {
    if (!(x[i] > 0) || !(e[i] > 0) || !std::isfinite(x[i]) || !std::isfinite(e[i])) continue;
    const double lx = std::log(x[i]), ly = std::log(e[i]);
    sx += lx;
    sy += ly;
    sxx += lx * lx;
    sxy += lx * ly;
    ++n;
  }
  if (used) *used = n;
  if (n < 2) return kNaN;
  const double den = n * sxx - sx * sx;
  if (!(std::abs(den) > 0)) return kNaN;
  return (n * sxy - sx * sy) / den;
}

ConvergenceResult convergence(const Options& opt, const CaseInput& spec) {
  Setup s = prepare(opt);
  const EmptyOutGuard no_empty_folder(s);
  std::vector<Case> cases = expand_case(spec.spec, s.info.integrator, spec.where);
  tie_iteration_tolerance(opt, cases, s.info.integrator);
  const std::string where = spec.where.empty() ? "--case '" + spec.spec + "'" : spec.where;
  if (cases.empty() || cases.front().swept.size() != 1)
    throw InputError(where + ": a convergence study sweeps exactly one key, step or rtol (" +
                     (cases.empty() || cases.front().swept.empty()
                          ? std::string("none is swept")
                          : "it sweeps " + join(cases.front().swept)) +
                     ")");
  ConvergenceResult res;
  res.key = cases.front().swept.front();
  if (res.key != "step" && res.key != "rtol")
    throw InputError(where + ": a convergence study sweeps step or rtol, not " + res.key);
  auto value = [&](const Case& c) {
    return std::strtod(get_integrator_setting(c.settings, res.key).c_str(), nullptr);
  };
  std::stable_sort(cases.begin(), cases.end(),
                   [&](const Case& a, const Case& b) { return value(a) > value(b); });
  if (opt.reference_file.empty()) reference_case(opt.reference, s.info.integrator);
  res.family = strip_keys(settings_label(cases.front().settings), {res.key});

  say(opt, "evas study: convergence of " + res.family + " over " + res.key + ", " +
               std::to_string(cases.size()) + " cases -> " + s.out.string());
  res.reference = make_reference(opt, s);
  const std::vector<int> rows = reference_rows(opt, s, res.reference);
  res.info = make_info(s);
  for (const auto& c : cases) {
    CaseResult r;
    r.c = c;
    res.cases.push_back(r);
    res.x.push_back(value(c));
    res.pair_order.push_back(kNaN);
  }
  auto update = [&] {
    std::vector<double> e;
    int last = -1;
    for (std::size_t i = 0; i < res.cases.size(); ++i) {
      const double err = res.cases[i].status == CaseStatus::completed ? res.cases[i].error : kNaN;
      e.push_back(err);
      res.pair_order[i] = kNaN;
      if (!(err > 0) || !std::isfinite(err)) continue;
      if (last >= 0)
        res.pair_order[i] = std::log(err / e[static_cast<std::size_t>(last)]) /
                            std::log(res.x[i] / res.x[static_cast<std::size_t>(last)]);
      last = static_cast<int>(i);
    }
    res.slope = log_log_slope(res.x, e, &res.points);
  };
  write_convergence(opt, res, rows, false);
  run_cases(opt, s, cases, res.reference, rows, res.cases, res.info, [&] {
    update();
    write_convergence(opt, res, rows, false);
  });
  update();
  write_convergence(opt, res, rows, true);
  return res;
}

}  // namespace evas::study
