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
    case StabilityStatus::timed_out:
      return "timed out";
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
  csv << csv_field(key) << ",status,h_stable,h_unstable,runs,reference_max,message,interpolation\n";
  for (const auto& p : res.points)
    csv << csv_field(p.value) << "," << csv_field(to_text(p.status)) << "," << gnum(p.h_stable, 9)
        << "," << gnum(p.h_unstable, 9) << "," << p.runs << "," << gnum(p.reference_max, 9) << ","
        << csv_field(p.message) << "," << csv_field(p.interpolation) << "\n";
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
  for (const auto& p : res.points)
    if (!p.interpolation.empty())
      md << "\n- " << (p.value.empty() ? "" : md_cell(p.value) + ": ") << "largest stable step "
         << gnum(p.h_stable, 6) << " s: " << md_cell(p.interpolation, 200) << "\n";
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

// The search at one sweep value: reference run, then HMAX, HMIN and the
// bisections, one run at a time.
struct Search {
  enum class Phase { reference, h_max, h_min, bisect, done };
  SceneSource src;
  SceneInfo info;
  std::string tag;  // "KEY = VALUE: " in progress lines
  Phase phase = Phase::reference;
  double h = 0.0;  // the step of the next trial
  std::vector<double> bound;
  double t_first = 0.0;
  int bisections = 0;
  bool warned_dense = false;  // said once: steps much longer than the output interval
};

// After the reference: the growth bound per channel (growth x the
// reference's max |y| after the first output), then the trial at HMAX.
void start_trials(Search& q, StabilityPoint& p, const Reference& ref, const StabilityOptions& so) {
  const long nc = ref.y.cols();
  q.bound.assign(static_cast<std::size_t>(nc), 0.0);
  double refmax = 0.0;
  for (long c = 0; c < nc; ++c) {
    double m = 0.0;
    for (long r = std::min<long>(1, ref.y.rows() - 1); r < ref.y.rows(); ++r)
      m = std::max(m, std::abs(ref.y(r, c)));
    q.bound[static_cast<std::size_t>(c)] = so.growth * m;
    refmax = std::max(refmax, m);
  }
  p.reference_max = refmax;
  if (!(refmax > 0))
    throw InputError(
        "stability: every selected channel is zero in the reference run (choose "
        "channels that move, --channels)");
  q.t_first = ref.time.empty() ? 0.0 : ref.time.front();
  q.phase = Search::Phase::h_max;
  q.h = so.h_max;
}

// One trial's outcome: HMAX stable ends the search; else HMIN, then bisections
// in log h between the largest stable and the smallest unstable step.
void advance(Search& q, StabilityPoint& p, bool ok, const std::string& why,
             const StabilityOptions& so) {
  ++p.runs;
  auto bisect = [&] {
    if (q.bisections >= so.bisections) {
      q.phase = Search::Phase::done;
      return;
    }
    q.phase = Search::Phase::bisect;
    q.h = std::sqrt(p.h_stable * p.h_unstable);
  };
  switch (q.phase) {
    case Search::Phase::h_max:
      if (ok) {
        p.status = StabilityStatus::stable_to_hmax;
        p.h_stable = so.h_max;
        q.phase = Search::Phase::done;
      } else {
        p.h_unstable = so.h_max;
        p.message = why;
        q.phase = Search::Phase::h_min;
        q.h = so.h_min;
      }
      return;
    case Search::Phase::h_min:
      if (!ok) {
        p.status = StabilityStatus::unstable_at_hmin;
        p.h_unstable = so.h_min;
        p.message = why;
        q.phase = Search::Phase::done;
        return;
      }
      p.h_stable = so.h_min;
      p.status = StabilityStatus::bracketed;
      bisect();
      return;
    case Search::Phase::bisect:
      ++q.bisections;
      if (ok) {
        p.h_stable = q.h;
      } else {
        p.h_unstable = q.h;
        p.message = why;
      }
      bisect();
      return;
    case Search::Phase::reference:
    case Search::Phase::done:
      return;
  }
}

}  // namespace

StabilityResult stability(const Options& opt, const CaseInput& spec, const StabilityOptions& so) {
  if (!(so.h_min > 0) || !(so.h_max > so.h_min) || !std::isfinite(so.h_max))
    throw InputError("--step-range HMIN:HMAX: need 0 < HMIN < HMAX");
  if (!(so.growth > 1)) throw InputError("--growth must be > 1");
  if (so.bisections < 0 || so.bisections > 60) throw InputError("--bisections must be in [0, 60]");
  Setup s = prepare(opt);
  const EmptyOutGuard no_empty_folder(s);
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
    ParamSweep sw = parse_sweep(so.sweep);
    res.sweep_key = sw.key;
    values = std::move(sw.values);
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

  // The searches at the sweep values are independent: they advance in rounds,
  // one run per unfinished value in each round, through the study's runner
  // (--jobs, MPI). Each search's runs, and so its result, are those of a
  // search on its own.
  const Case ref_case =
      opt.reference_file.empty() ? reference_case(opt.reference, s.info.integrator) : Case{};
  std::vector<Search> searches;
  for (std::size_t k = 0; k < values.size(); ++k) {
    Search q;
    q.src =
        res.sweep_key.empty() ? s.src : edited(s.src, {res.sweep_key + "=" + values[k]}, "--sweep");
    q.tag = res.sweep_key.empty() ? "" : res.sweep_key + " = " + values[k] + ": ";
    q.info = res.sweep_key.empty() ? s.info : probe_scene(q.src);
    if (!opt.reference_file.empty()) {
      start_trials(q, res.points[k], read_reference(opt, q.info, s.names, s.units), so);
    } else {
      say(opt, "evas study: " + q.tag + "reference " + ref_case.label + " ...");
    }
    searches.push_back(std::move(q));
  }
  while (!stopped(opt)) {
    std::vector<TaskSpec> tasks;
    std::vector<int> todo, owner;
    for (std::size_t k = 0; k < searches.size(); ++k) {
      Search& q = searches[k];
      if (q.phase == Search::Phase::done) continue;
      TaskSpec t;
      t.src = q.src;
      t.channels = s.channels;
      if (q.phase != Search::Phase::reference && q.info.times.size() >= 2) {
        const double dt = q.info.times[1] - q.info.times[0];
        if (q.h > 10.0 * dt && !q.warned_dense) {
          q.warned_dense = true;
          say(opt, "evas study: " + q.tag + "warning: steps of " + gnum(q.h, 4) + " s span " +
                       gnum(q.h / dt, 3) +
                       " output intervals; stability is judged at the step points (the outputs "
                       "between them are interpolated and may swing far beyond)");
        }
      }
      if (q.phase == Search::Phase::reference) {
        // --max-wall limits the trials, not the reference: a tight-tolerance
        // run is meant to take long
        t.settings = ref_case.settings;
      } else {
        t.max_wall = opt.max_wall;
        t.settings = res.c.settings;
        t.settings.step = q.h;
        t.limit = q.bound;
        t.limit_names = s.names;
        t.limit_after = q.t_first;
        t.growth = so.growth;
      }
      todo.push_back(static_cast<int>(tasks.size()));
      owner.push_back(static_cast<int>(k));
      tasks.push_back(std::move(t));
    }
    if (tasks.empty()) break;
    std::vector<RunData> runs(tasks.size());
    std::vector<bool> ran(tasks.size(), false);
    runner_of(opt).run(
        tasks, todo,
        [&](const TaskEnd& e) {
          runs[static_cast<std::size_t>(e.index)] = e.run;
          ran[static_cast<std::size_t>(e.index)] = true;
        },
        opt.stop);
    for (std::size_t i = 0; i < tasks.size(); ++i) {
      if (!ran[i]) continue;  // cut short by the interrupt
      const auto k = static_cast<std::size_t>(owner[i]);
      Search& q = searches[k];
      StabilityPoint& p = res.points[k];
      if (q.phase == Search::Phase::reference) {
        try {
          const Reference ref = reference_of(ref_case, runs[i], q.info, s.names, s.units);
          say(opt, "evas study: " + q.tag + "reference " + ref_case.label + ": " +
                       std::to_string(ref.stats.steps) + " steps, " + gnum(ref.wall, 3) + " s");
          start_trials(q, p, ref, so);
        } catch (const ReferenceFailed& e) {
          if (res.sweep_key.empty()) throw;
          p.status = StabilityStatus::reference_failed;
          p.message = e.what();
          q.phase = Search::Phase::done;
          say(opt, "evas study: " + q.tag + e.what());
        }
        continue;
      }
      const RunData& d = runs[i];
      if (d.status == CaseStatus::failed && d.message.rfind("timed out", 0) == 0) {
        // neither stable nor unstable: the search ends, its bracket kept
        ++p.runs;
        if (p.status == StabilityStatus::not_run || p.status == StabilityStatus::bracketed)
          p.status = StabilityStatus::timed_out;
        p.message = "h = " + gnum(q.h, 6) + " s: " + d.message;
        q.phase = Search::Phase::done;
        say(opt, "evas study: " + q.tag + p.message);
        continue;
      }
      const bool ok = d.status == CaseStatus::completed;
      say(opt, "evas study: " + q.tag + "h = " + gnum(q.h, 6) + " s: " +
                   (ok ? std::string("stable") + (d.message.empty() ? "" : "; " + d.message)
                       : "unstable: " + d.message));
      if (ok) p.interpolation = d.message;  // a stable trial's step is the largest so far
      advance(q, p, ok, d.message, so);
      if (q.phase == Search::Phase::done)
        say(opt,
            "evas study: " + q.tag + to_text(p.status) + ", largest stable step " +
                gnum(p.h_stable, 6) + " s" +
                (std::isnan(p.h_unstable) ? "" : ", unstable at " + gnum(p.h_unstable, 6) + " s"));
    }
    write_stability(opt, res, so, false);
  }
  // an interrupted search keeps its bracket so far
  for (std::size_t k = 0; k < searches.size(); ++k)
    if (searches[k].phase != Search::Phase::done && res.points[k].runs > 0)
      res.points[k].status = StabilityStatus::interrupted;
  if (stopped(opt)) res.info.interrupted = true;
  write_stability(opt, res, so, true);
  return res;
}

}  // namespace evas::study
