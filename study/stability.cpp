// `evas study` stability (study.h): the largest stable fixed step of one case,
// found by bisection in log h, optionally over a parameter sweep;
// stability.csv/.md/.png.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "integrators/settings.h"
#include "study/report.h"
#include "study/study.h"
#include "study/study_common.h"

namespace evas::study {

using namespace detail;

const char* to_text(StabilityStatus s) {
  switch (s) {
    case StabilityStatus::bracketed:
      return "bracketed";
    case StabilityStatus::stable_to_hmax:
      return "stable up to HMAX";
    case StabilityStatus::unstable_at_hmin:
      return "unstable at HMIN";
    case StabilityStatus::reference_failed:
      return "reference failed";
    case StabilityStatus::interrupted:
      return "interrupted";
    case StabilityStatus::not_run:
      break;
  }
  return "not run";
}

// --- stability ------------------------------------------------------------------

namespace {

void write_stability(const Options& opt, StabilityResult& res, const StabilityOptions& so,
                     bool final) {
  StudyInfo& info = res.info;
  const fs::path dir = info.out_dir;
  info.files.clear();
  const std::string key = res.sweep_key.empty() ? "sweep" : res.sweep_key;
  std::ostringstream csv;
  csv << csv_field(key) << ",status,h_stable,h_unstable,runs,reference_max,message\n";
  for (const auto& p : res.points)
    csv << csv_field(p.value) << "," << csv_field(to_text(p.status)) << "," << gnum(p.h_stable, 9)
        << "," << gnum(p.h_unstable, 9) << "," << p.runs << "," << gnum(p.reference_max, 9) << ","
        << csv_field(p.message) << "\n";
  write_file_atomic(dir / "stability.csv", csv.str());
  info.files.push_back((dir / "stability.csv").string());

  std::ostringstream md;
  md << "# Stability study: " << info.scene_name << "\n\n"
     << "- scene: `" << info.scene_path << "`";
  if (!opt.params.empty()) md << " with " << md_cell(join(opt.params));
  md << " (" << info.grid << " grid)\n"
     << "- case: " << md_cell(res.c.label) << " (its step is searched)\n"
     << "- steps searched: " << gnum(so.h_min, 6) << " .. " << gnum(so.h_max, 6) << " s, "
     << so.bisections << " bisections in log h\n"
     << "- stable: the run completes and, for every selected channel, max |y| after the first "
        "output <= "
     << gnum(so.growth, 4) << " x that of the reference run ("
     << md_cell(opt.reference_file.empty() ? opt.reference : opt.reference_file) << ")\n"
     << "- channels: " << md_cell(join(info.channels)) << "\n";
  if (info.interrupted) md << "- **interrupted**\n";
  md << "\n| " << md_cell(key)
     << " | status | largest stable step [s] | smallest unstable step [s] | runs | why unstable |\n"
     << "|---|---|---:|---:|---:|---|\n";
  for (const auto& p : res.points)
    md << "| " << md_cell(p.value) << " | " << to_text(p.status) << " | " << gnum(p.h_stable, 6)
       << " | " << gnum(p.h_unstable, 6) << " | " << p.runs << " | " << md_cell(p.message, 90)
       << " |\n";
  write_file_atomic(dir / "stability.md", md.str());
  info.files.push_back((dir / "stability.md").string());

  if (!final || res.sweep_key.empty()) return;
  std::ostringstream data;
  bool numeric = true;
  std::vector<double> xs;
  int n = 0;
  for (const auto& p : res.points) {
    char* end = nullptr;
    const double x = std::strtod(p.value.c_str(), &end);
    if (end == p.value.c_str() || *end != '\0') numeric = false;
    xs.push_back(x);
  }
  for (std::size_t i = 0; i < res.points.size(); ++i) {
    const auto& p = res.points[i];
    if (std::isnan(p.h_stable)) continue;
    std::string label = p.value;  // a data-file string: double quotes, none inside
    std::replace(label.begin(), label.end(), '"', '\'');
    data << (numeric ? gnum(xs[i], 12) : std::to_string(i)) << " " << gnum(p.h_stable, 12) << " \""
         << label << "\"\n";
    ++n;
  }
  if (n == 0) return;
  bool logx = numeric;
  if (numeric) {
    const auto [lo, hi] = std::minmax_element(xs.begin(), xs.end());
    logx = *lo > 0 && *hi / *lo >= 10;
  }
  const fs::path png = dir / "stability.png";
  std::ostringstream gp;
  gp << "# stability figure of " << info.scene_name << " (evas study)\n"
     << gp_terminal(png, 900, 600) << "$D << EOD\n"
     << data.str() << "EOD\n"
     << "set logscale y\nset grid\nset key off\nset offsets graph 0.05, graph 0.05, 0, 0\n"
     << (logx ? "set logscale x\n" : "") << "set xlabel " << gp_quote(res.sweep_key) << "\n"
     << "set ylabel 'largest stable step [s]'\n"
     << "set title " << gp_quote("stability: " + res.c.label) << "\n"
     << (numeric ? "plot $D using 1:2 with linespoints pt 7\n"
                 : "plot $D using 1:2:xtic(3) with linespoints pt 7\n");
  plot(opt, dir / "stability.gp", gp.str(), info, png);
}

}  // namespace

StabilityResult stability(const Options& opt, const CaseInput& spec, const StabilityOptions& so) {
  if (!(so.h_min > 0) || !(so.h_max > so.h_min) || !std::isfinite(so.h_max))
    throw InputError("--step-range HMIN:HMAX: need 0 < HMIN < HMAX");
  if (!(so.growth > 1)) throw InputError("--growth must be > 1");
  if (so.bisections < 0 || so.bisections > 60) throw InputError("--bisections must be in [0, 60]");
  Setup s = prepare(opt);
  const std::string where = spec.where.empty() ? "--case '" + spec.spec + "'" : spec.where;
  const std::vector<Case> cases = expand_case(spec.spec, s.info.integrator, spec.where);
  if (cases.size() != 1) {
    bool only_step = cases.front().swept.size() == 1 && cases.front().swept.front() == "step";
    if (!only_step)
      throw InputError(where + ": a stability study takes one integrator setting (it expands to " +
                       std::to_string(cases.size()) + " cases)");
  }
  StabilityResult res;
  res.c = cases.front();
  if (!has_fixed_step(res.c.settings.name))
    throw InputError(where +
                     ": a stability study searches the fixed step of generalized-alpha, "
                     "linear-acceleration or radau, not " +
                     res.c.settings.name);
  if (opt.reference_file.empty())
    reference_case(opt.reference, s.info.integrator);
  else if (!so.sweep.empty())
    throw InputError(
        "--reference-file cannot serve a --sweep (each swept scene needs its own "
        "reference run; use --reference)");

  std::vector<std::string> values = {""};
  if (!so.sweep.empty()) {
    const auto eq = so.sweep.find('=');
    if (eq == std::string::npos || eq == 0)
      throw InputError("--sweep '" + so.sweep + "': expected ITEM.KEY=V1,V2,...");
    res.sweep_key = so.sweep.substr(0, eq);
    values.clear();
    for (const auto& item : split_list(so.sweep.substr(eq + 1), ',')) {
      if (item.empty()) throw InputError("--sweep '" + so.sweep + "': empty value");
      if (item.find("..") != std::string::npos && item.find('/') != std::string::npos) {
        for (auto& v : log_range("--sweep " + res.sweep_key, item, "number")) values.push_back(v);
      } else {
        values.push_back(item);
      }
    }
    // every swept scene must read: check them all before the first run
    for (const auto& v : values) edited(s.src, {res.sweep_key + "=" + v}, "--sweep").parse();
  }
  res.info = make_info(s);
  for (const auto& v : values) {
    StabilityPoint p;
    p.value = v;
    res.points.push_back(p);
  }
  say(opt, "evas study: stability of " + res.c.label + ", h in [" + gnum(so.h_min, 4) + ", " +
               gnum(so.h_max, 4) + "] s" +
               (res.sweep_key.empty()
                    ? ""
                    : ", " + std::to_string(values.size()) + " values of " + res.sweep_key) +
               " -> " + s.out.string());
  write_stability(opt, res, so, false);

  for (std::size_t k = 0; k < values.size(); ++k) {
    if (stopped(opt)) {
      res.info.interrupted = true;
      break;
    }
    StabilityPoint& p = res.points[k];
    const SceneSource src =
        res.sweep_key.empty() ? s.src : edited(s.src, {res.sweep_key + "=" + values[k]}, "--sweep");
    const std::string tag = res.sweep_key.empty() ? "" : res.sweep_key + " = " + values[k] + ": ";
    SceneInfo info = res.sweep_key.empty() ? s.info : probe_scene(src);
    Reference ref;
    try {
      ref = !opt.reference_file.empty()
                ? read_reference(opt, info, s.names, s.units)
                : run_reference(opt, src, info, s.channels, s.names, s.units);
    } catch (const ReferenceFailed& e) {
      if (res.sweep_key.empty()) throw;
      p.status = StabilityStatus::reference_failed;
      p.message = e.what();
      say(opt, "evas study: " + tag + e.what());
      write_stability(opt, res, so, false);
      continue;
    }
    // bound per channel: growth x the reference's max |y| after the first output
    const long nc = ref.y.cols();
    std::vector<double> bound(static_cast<std::size_t>(nc), 0.0);
    double refmax = 0.0;
    for (long c = 0; c < nc; ++c) {
      double m = 0.0;
      for (long r = std::min<long>(1, ref.y.rows() - 1); r < ref.y.rows(); ++r)
        m = std::max(m, std::abs(ref.y(r, c)));
      bound[static_cast<std::size_t>(c)] = so.growth * m;
      refmax = std::max(refmax, m);
    }
    p.reference_max = refmax;
    if (!(refmax > 0))
      throw InputError(
          "stability: every selected channel is zero in the reference run (choose "
          "channels that move, --channels)");
    const double t_first = ref.time.empty() ? 0.0 : ref.time.front();
    std::string why;
    auto trial = [&](double h) {
      IntegratorSettings st = res.c.settings;
      st.step = h;
      int row = 0;
      RowCheck check = [&](double t, const double* y) {
        if (row++ == 0 && t <= t_first) return;
        for (long c = 0; c < nc; ++c) {
          const double b = bound[static_cast<std::size_t>(c)];
          if (b > 0 && std::abs(y[c]) > b)
            throw RunError("|" + s.names[static_cast<std::size_t>(c)] +
                           "| = " + sci(std::abs(y[c]), 3) + " > " + gnum(so.growth, 4) +
                           " x reference max " + sci(b / so.growth, 3) + " at t = " + gnum(t, 6) +
                           " s");
        }
      };
      const RunData d = run_case(src, st, s.channels, check, opt.stop);
      ++p.runs;
      const bool ok = d.status == CaseStatus::completed;
      why = ok ? "" : d.message;
      say(opt, "evas study: " + tag + "h = " + gnum(h, 6) +
                   " s: " + (ok ? std::string("stable") : "unstable: " + d.message));
      return ok;
    };
    if (trial(so.h_max)) {
      p.status = StabilityStatus::stable_to_hmax;
      p.h_stable = so.h_max;
    } else {
      p.h_unstable = so.h_max;
      p.message = why;
      if (stopped(opt)) {
        p.status = StabilityStatus::interrupted;
      } else if (!trial(so.h_min)) {
        p.status = StabilityStatus::unstable_at_hmin;
        p.h_unstable = so.h_min;
        p.message = why;
      } else {
        p.h_stable = so.h_min;
        p.status = StabilityStatus::bracketed;
        for (int i = 0; i < so.bisections; ++i) {
          if (stopped(opt)) {
            p.status = StabilityStatus::interrupted;
            break;
          }
          const double mid = std::sqrt(p.h_stable * p.h_unstable);
          if (trial(mid)) {
            p.h_stable = mid;
          } else {
            p.h_unstable = mid;
            p.message = why;
          }
          write_stability(opt, res, so, false);
        }
      }
    }
    say(opt, "evas study: " + tag + to_text(p.status) + ", largest stable step " +
                 gnum(p.h_stable, 6) + " s" +
                 (std::isnan(p.h_unstable) ? "" : ", unstable at " + gnum(p.h_unstable, 6) + " s"));
    write_stability(opt, res, so, false);
  }
  if (stopped(opt)) res.info.interrupted = true;
  write_stability(opt, res, so, true);
  return res;
}

}  // namespace evas::study
