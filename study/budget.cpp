// The error budget of a scene's answer, see budget.h.
#include "study/budget.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <map>
#include <sstream>
#include <string>

#include "integrators/settings.h"
#include "study/budget_files.h"
#include "study/report.h"
#include "study/study_common.h"

namespace evas::study {

namespace {

using detail::kNaN;

}  // namespace

Vec low_orders(const Vec& x, double orders) {
  const Eigen::Index n = x.size();
  Vec out = Vec::Zero(n);
  const int kmax = static_cast<int>(std::floor(2.0 * orders + 1e-9));
  for (int k = 0; k <= kmax && 2 * k <= n; ++k) {
    double re = 0.0, im = 0.0;
    for (Eigen::Index i = 0; i < n; ++i) {
      const double a = 2.0 * M_PI * k * static_cast<double>(i) / static_cast<double>(n);
      re += x[i] * std::cos(a);
      im -= x[i] * std::sin(a);
    }
    const double w = (k == 0 || 2 * k == n) ? 1.0 : 2.0;
    for (Eigen::Index i = 0; i < n; ++i) {
      const double a = 2.0 * M_PI * k * static_cast<double>(i) / static_cast<double>(n);
      out[i] += w * (re * std::cos(a) - im * std::sin(a)) / static_cast<double>(n);
    }
  }
  return out;
}

namespace {

/// The budget is per channel, each on its own amplitude: the RMS measures
/// (rms, l2) give rms, every other --norm the max over the window.
Norm norm_of(const detail::Setup& s) {
  return s.measure.norm == Norm::Rms || s.measure.norm == Norm::L2 ? Norm::Rms : Norm::Max;
}

/// Error of every channel of y against ref over `rows` (NaN for a channel
/// that is constant in ref). With orders > 0 the rows are one cycle (a last
/// row one period after the first is left out) and both are first reduced to
/// their engine orders up to `orders`; the amplitude stays ref's own.
std::vector<double> budget_errors(const Mat& y, const Mat& ref, const std::vector<int>& rows,
                                  Norm norm, double orders) {
  std::vector<double> e(static_cast<std::size_t>(ref.cols()), kNaN);
  if (orders <= 0.0) {
    for (Eigen::Index c = 0; c < ref.cols(); ++c)
      e[static_cast<std::size_t>(c)] = relative_error(Mat(y.col(c)), Mat(ref.col(c)), rows, norm);
    return e;
  }
  const std::size_t n = rows.size() % 2 == 1 ? rows.size() - 1 : rows.size();  // 721 -> 720
  const std::vector<double> amp = amplitudes(ref, rows);
  for (Eigen::Index c = 0; c < ref.cols(); ++c) {
    const double a = amp[static_cast<std::size_t>(c)];
    if (!(a > 0.0)) continue;
    Vec yc(static_cast<Eigen::Index>(n)), rc(yc.size());
    for (std::size_t i = 0; i < n; ++i) {
      yc[static_cast<Eigen::Index>(i)] = y(rows[i], c);
      rc[static_cast<Eigen::Index>(i)] = ref(rows[i], c);
    }
    const Vec d = low_orders(yc, orders) - low_orders(rc, orders);
    e[static_cast<std::size_t>(c)] =
        (norm == Norm::Max ? d.cwiseAbs().maxCoeff()
                           : std::sqrt(d.squaredNorm() / static_cast<double>(d.size()))) /
        a;
  }
  return e;
}

void set_errors(BudgetSource& src, std::vector<double> e) {
  src.channel_error = std::move(e);
  src.error = kNaN;
  src.channel = -1;
  for (std::size_t c = 0; c < src.channel_error.size(); ++c) {
    const double x = src.channel_error[c];
    if (std::isfinite(x) && (src.channel < 0 || x > src.error)) {
      src.error = x;
      src.channel = static_cast<int>(c);
    }
  }
  src.measured = src.channel >= 0;
  if (!src.measured && src.note.empty()) src.note = "every channel is constant in the variation";
}

void not_measured(BudgetSource& src, std::size_t channels, const std::string& why) {
  src.measured = false;
  src.note = why;
  src.channel_error.assign(channels, kNaN);
}

/// A run of a variation: completed with every output row, else the reason.
std::string run_problem(const RunData& d, long rows) {
  if (d.status != CaseStatus::completed) return "the run failed: " + d.message;
  if (d.rows() < rows)
    return "the run gave " + std::to_string(d.rows()) + " of " + std::to_string(rows) +
           " output rows";
  return "";
}

/// The source measured as the base against the variation's run `v` (its
/// rows the base's output times), or not measured when `v` failed.
void against(BudgetSource& src, const RunData& v, const RunData& base, const std::vector<int>& rows,
             Norm norm, double orders, const std::string& what, const std::string& how) {
  if (const std::string p = run_problem(v, base.rows()); !p.empty()) {
    not_measured(src, static_cast<std::size_t>(base.y.cols()), what + ": " + p);
    return;
  }
  src.note = how;
  src.wall = v.wall;
  src.steps = v.stats.steps;
  set_errors(src, budget_errors(base.y, v.y, rows, norm, orders));
}

/// Key of a crank angle within the 720-deg cycle (1e-6 deg resolution).
long long cycle_key(double deg) {
  double a = std::fmod(deg, 720.0);
  if (a < 0) a += 720.0;
  long long k = std::llround(a * 1e6);
  return k == 720000000LL ? 0 : k;
}

void measure_startup(const Options& opt, const detail::Setup& s, const RunData& base,
                     const std::vector<int>& rows, double orders, BudgetSource& src) {
  const std::size_t nc = s.channels.size();
  if (s.info.crank_channel < 0) {
    not_measured(src, nc, "the output is not on a crank-angle grid: no cycle to settle");
    return;
  }
  detail::say(opt, "budget: start-up, the periodic cycle (evas periodic, projected)");
  const RunData p =
      run_periodic_case(s.src, s.info.integrator, s.channels, "projected", opt.start.tol, opt.stop);
  if (p.status == CaseStatus::completed && p.rows() > 0) {
    std::map<long long, Eigen::Index> at;
    for (Eigen::Index r = 0; r < p.rows(); ++r)
      at[cycle_key(p.crank[static_cast<std::size_t>(r)])] = r;
    std::vector<Eigen::Index> rb, rp;
    for (int r : rows) {
      const auto it = at.find(cycle_key(base.crank[static_cast<std::size_t>(r)]));
      if (it != at.end()) rb.push_back(r), rp.push_back(it->second);
    }
    if (!rb.empty()) {
      Mat yb(static_cast<Eigen::Index>(rb.size()), base.y.cols()), yp(yb.rows(), yb.cols());
      for (std::size_t i = 0; i < rb.size(); ++i) {
        yb.row(static_cast<Eigen::Index>(i)) = base.y.row(rb[i]);
        yp.row(static_cast<Eigen::Index>(i)) = p.y.row(rp[i]);
      }
      std::vector<int> all(rb.size());
      for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
      src.variation =
          "the periodic cycle (evas periodic, projected, defect " + gnum(opt.start.tol, 3) + ")";
      src.note = "the base's last cycle against the periodic cycle, " + std::to_string(rb.size()) +
                 " rows matched by crank angle";
      src.wall = p.wall;
      src.steps = p.stats.steps;
      set_errors(src, budget_errors(yb, yp, all, norm_of(s), orders));
      return;
    }
  }
  // Fallback: the last cycle against the one before.
  const std::string why = p.status == CaseStatus::completed ? "no crank angle of the periodic "
                                                              "cycle matched the output's"
                                                            : p.message;
  std::vector<int> two;
  try {
    two = window_rows(Window{Window::Kind::LastCycles, 2.0, 0, 0}, base.time, base.crank);
  } catch (const InputError&) {
    not_measured(src, nc,
                 "the periodic search failed (" + why + ") and the output holds no two cycles");
    return;
  }
  const std::size_t half = two.size() / 2;
  const Eigen::Index n = static_cast<Eigen::Index>(half);
  Mat prev(n, base.y.cols()), last(n, base.y.cols());
  for (Eigen::Index i = 0; i < n; ++i) {
    prev.row(i) = base.y.row(two[static_cast<std::size_t>(i)]);
    last.row(i) = base.y.row(two[two.size() - half + static_cast<std::size_t>(i)]);
  }
  std::vector<int> all(half);
  for (std::size_t i = 0; i < half; ++i) all[i] = static_cast<int>(i);
  src.variation = "the cycle before the last";
  src.note = "the periodic search failed (" + why + "): the last cycle against the one before";
  src.wall = 0.0;
  src.steps = 0;
  set_errors(src, budget_errors(last, prev, all, norm_of(s), orders));
}

}  // namespace

std::string without_mode_cuts(const std::string& text, std::string& changed) {
  changed.clear();
  YAML::Node root = YAML::Load(text);
  const YAML::Node bodies = root["bodies"];
  if (!bodies || !bodies.IsSequence()) return text;
  for (YAML::Node b : bodies) {
    YAML::Node m = b["modes"];
    if (!m || !m.IsMap()) continue;
    bool cut = false;
    for (const char* k : {"max_frequency", "elastic", "quasi_static_above"})
      if (m[k]) cut = m.remove(k) || cut;
    if (cut) changed += (changed.empty() ? "" : ", ") + b["name"].as<std::string>("?");
  }
  if (changed.empty()) return text;
  YAML::Emitter e;
  e << root;
  return e.c_str();
}

std::vector<std::string> finer_element_edits(const std::string& text, std::string& changed) {
  changed.clear();
  std::vector<std::string> edits;
  const YAML::Node root = YAML::Load(text);
  const YAML::Node elements = root["elements"];
  if (!elements || !elements.IsSequence()) return edits;
  for (const YAML::Node& e : elements) {
    if (!e.IsMap() || e["type"].as<std::string>("") != "journal-bearing") continue;
    const std::string name = e["name"].as<std::string>(""),
                      film = e["film"].as<std::string>("short");
    if (name.empty() || (film != "short" && film != "finite")) continue;
    const bool table = e["cavitation"].as<std::string>("swift-stieber") != "none";
    edits.push_back(name + ".film=reynolds");
    edits.push_back(name + ".solve=" + std::string(table ? "table" : "grid"));
    changed += (changed.empty() ? "" : ", ") + name;
  }
  return edits;
}

BudgetResult budget(const Options& opt_in, const BudgetOptions& bo) {
  if (!(bo.tighten > 1.0) || !std::isfinite(bo.tighten))
    throw InputError("--tighten must be a number > 1");
  if (!(bo.orders >= 0.0) || !std::isfinite(bo.orders))
    throw InputError("--orders must be a number >= 0");
  if (!opt_in.window.empty())
    throw InputError("--window does not apply to a budget: it measures the last cycle");
  Options opt = opt_in;
  detail::Setup s = detail::prepare(opt);
  const detail::EmptyOutGuard no_empty_folder(s);
  if (bo.orders > 0.0 && s.info.crank_channel < 0)
    throw InputError("--orders needs a crank-angle grid (output: {grid: crank-angle})");
  BudgetResult res;
  res.info = detail::make_info(s);
  res.info.norm = norm_text(norm_of(s));
  res.units = s.units;
  const IntegratorSettings base_set = s.info.integrator;
  res.base_label = settings_label(base_set);
  res.orders = bo.orders;
  const long nrows = static_cast<long>(s.info.times.size());
  const std::size_t nc = s.channels.size();

  detail::say(opt, "budget: the base run (" + res.base_label + ")");
  const RunData base = run_case(s.src, base_set, s.channels, nullptr, opt.stop);
  if (const std::string p = run_problem(base, nrows); !p.empty())
    throw ReferenceFailed("the base run (" + res.base_label + "): " + p);
  res.base_wall = base.wall;
  res.base_steps = base.stats.steps;
  const Window w = s.info.crank_channel >= 0 ? Window{Window::Kind::LastCycles, 1.0, 0, 0}
                                             : Window{Window::Kind::All, 1.0, 0, 0};
  const std::vector<int> rows = window_rows(w, base.time, base.crank);
  res.info.window = w.text();
  res.info.error_definition = error_definition(ErrorMeasure{norm_of(s), 0.0}, w);

  // integration
  BudgetSource integ;
  integ.name = "integration";
  IntegratorSettings tight = base_set;
  // 12 digits: the label reads 1e-11, not 1.0000000000000001e-11
  const auto divided = [&](double x) { return std::stod(gnum(x / bo.tighten, 12)); };
  if (takes_fixed_steps(tight)) {
    tight.step = divided(tight.step);
  } else {
    tight.rtol = divided(tight.rtol);
    tight.atol = divided(tight.atol);
  }
  integ.variation = settings_label(tight);
  detail::say(opt, "budget: integration (" + integ.variation + ")");
  against(integ, run_case(s.src, tight, s.channels, nullptr, opt.stop), base, rows, norm_of(s),
          bo.orders, "the tighter run",
          "the base against the integrator tightened " + gnum(bo.tighten, 3) + "x");
  res.sources.push_back(integ);

  // start-up
  BudgetSource start;
  start.name = "start-up";
  if (detail::stopped(opt))
    not_measured(start, nc, "interrupted");
  else
    measure_startup(opt, s, base, rows, bo.orders, start);
  res.sources.push_back(start);

  // basis
  BudgetSource basis;
  basis.name = "basis";
  SceneSource rich = s.src;
  if (!bo.richer.empty()) {
    rich = edited(s.src, bo.richer, "--richer");
    basis.variation = "--richer " + detail::join(bo.richer, " --richer ");
  } else {
    std::string changed;
    rich.text = without_mode_cuts(s.src.text, changed);
    rich.edited = true;
    if (changed.empty())
      basis.note =
          "the scene keeps every mode of its body files: give --richer ITEM.KEY=VALUE (e.g. "
          "crank.file=richer.h5, a body file with more modes) for a richer basis";
    else
      basis.variation = "every mode of the body files of " + changed;
  }
  if (basis.variation.empty() || detail::stopped(opt)) {
    not_measured(basis, nc, basis.note.empty() ? "interrupted" : basis.note);
  } else {
    detail::say(opt, "budget: basis (" + basis.variation + ")");
    against(basis, run_case(rich, base_set, s.channels, nullptr, opt.stop), base, rows, norm_of(s),
            bo.orders, "the richer basis", "the base against the same run on the richer basis");
  }
  res.sources.push_back(basis);

  // element models
  BudgetSource elem;
  elem.name = "element";
  std::vector<std::string> finer = bo.finer;
  if (!finer.empty()) {
    elem.variation = "--finer " + detail::join(finer, " --finer ");
  } else {
    std::string changed;
    finer = finer_element_edits(s.src.text, changed);
    if (!finer.empty())
      elem.variation = "film reynolds (Swift-Stieber) on the journal bearings " + changed;
  }
  if (elem.variation.empty() || detail::stopped(opt)) {
    not_measured(elem, nc,
                 elem.variation.empty()
                     ? "no element of the scene has a finer model in evas (journal bearings: "
                       "film reynolds is the finest; give --finer ITEM.KEY=VALUE, e.g. "
                       "main1.grid_phi=144)"
                     : "interrupted");
  } else {
    detail::say(opt, "budget: element (" + elem.variation + ")");
    against(elem,
            run_case(edited(s.src, finer, "--finer"), base_set, s.channels, nullptr, opt.stop),
            base, rows, norm_of(s), bo.orders, "the finer element models",
            "the base against the same run with the finer element models");
  }
  res.sources.push_back(elem);

  for (std::size_t k = 0; k < res.sources.size(); ++k)
    if (res.sources[k].measured &&
        (res.dominant < 0 || res.sources[k].error > res.sources[res.dominant].error))
      res.dominant = static_cast<int>(k);
  res.info.interrupted = detail::stopped(opt);
  write_budget_files(s.out, res, res.info);
  return res;
}

}  // namespace evas::study
