// `evas study sweep` (sweep.h): the grid, its tasks and their runs.
#include "study/sweep.h"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <set>

#include "integrators/settings.h"
#include "io/run_lock.h"
#include "plot/gnuplot_process.h"
#include "run/periodic.h"
#include "study/report.h"
#include "study/sweep_chains.h"
#include "study/sweep_detail.h"

namespace evas::study {

using namespace detail;

std::string task_file_name(int i) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "points/%04d.h5", i);
  return buf;
}

namespace {

// User + system processor time of this process alone (not of its children) [s].
double process_cpu_seconds() {
  rusage u{};
  ::getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

// The cartesian product of the sweeps' values, the first key slowest.
std::vector<std::vector<std::string>> grid_points(const std::vector<ParamSweep>& sw) {
  std::vector<std::vector<std::string>> pts = {{}};
  for (const auto& s : sw) {
    std::vector<std::vector<std::string>> next;
    for (const auto& p : pts)
      for (const auto& v : s.values) {
        next.push_back(p);
        next.back().push_back(v);
      }
    pts = std::move(next);
  }
  return pts;
}

// What identifies a task in its file: the point's assignments and the case.
std::string task_key(const std::vector<std::string>& keys, const std::vector<std::string>& values,
                     const Case& c) {
  std::string k;
  for (std::size_t j = 0; j < keys.size(); ++j) k += keys[j] + "=" + values[j] + "; ";
  return k + "case: " + c.label;
}

// The selected channels' indices in a point's scene, by name.
std::vector<int> channels_by_name(const SceneInfo& info, const std::vector<std::string>& names) {
  std::vector<int> idx;
  for (const auto& n : names) {
    int found = -1;
    for (std::size_t i = 0; i < info.channels.size(); ++i)
      if (info.channels[i].name == n) found = static_cast<int>(i);
    if (found < 0) throw InputError("the changed scene has no output channel '" + n + "'");
    idx.push_back(found);
  }
  return idx;
}

// Several workers: the tasks with the most output rows first (on a crank-angle
// grid the rows, like the steps, grow with the speed; on a time grid they are
// equal and the order stays), so that the costliest runs do not start last and
// leave one worker running alone at the end: longest processing time first,
// Graham (1969), SIAM J. Appl. Math. 17(2), 416-429.
void longest_first(std::vector<int>& todo, const std::vector<std::size_t>& rows) {
  std::stable_sort(todo.begin(), todo.end(), [&](int a, int b) {
    return rows[static_cast<std::size_t>(a)] > rows[static_cast<std::size_t>(b)];
  });
}

}  // namespace

SweepResult sweep(const Options& opt, const SweepOptions& so) {
  if (so.sweeps.empty()) throw InputError("missing --sweep ITEM.KEY=VALUES (repeatable)");
  if (so.merge && (so.point >= 0 || so.resume))
    throw InputError("--merge runs nothing: give it without --point and --resume");
  if (!(so.max_order > 0.0) || so.max_order > 1000.0)
    throw InputError("--max-order must be in (0, 1000]");
  if (so.cycles < 1) throw InputError("--cycles must be >= 1");
  if (!so.periodic.empty()) {
    run::periodic_method(so.periodic);  // an unknown method is refused here
    if (so.cycles != 1)
      throw InputError("--periodic: a point is one steady cycle; --cycles must be 1");
    if (!(so.periodic_tol > 0.0)) throw InputError("--periodic-tol must be positive");
  }
  for (double o : so.orders)
    if (!(o >= 0.0) || o > so.max_order)
      throw InputError("--orders: " + gnum(o, 6) + " is not in [0, --max-order " +
                       gnum(so.max_order, 6) + "]");
  if (!opt.reference_file.empty())
    throw InputError("--reference-file does not apply to a sweep (no errors are measured)");
  if (!opt.window.empty() || opt.norm != kDefaultNorm)
    throw InputError("--window and --norm do not apply to a sweep (it measures no error)");
  Options probe_opt = opt;
  probe_opt.window = "all";  // no error window: nothing to check or say about it
  using Clock = std::chrono::steady_clock;
  const auto started = Clock::now();
  const double cpu_started = process_cpu_seconds();
  auto since = [](Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
  };
  // the figures' gnuplot starts now and loads while the scene is read and
  // the points run (a --point task draws nothing)
  std::unique_ptr<GnuplotProcess> gnuplot;
  if (opt.plot && so.point < 0) gnuplot = std::make_unique<GnuplotProcess>();
  Setup s = prepare(probe_opt);
  const EmptyOutGuard no_empty_folder(s);
  const double setup_seconds = since(started);

  SweepData d;
  SweepResult& res = d.res;
  std::vector<ParamSweep> sweeps;
  for (const auto& a : so.sweeps) {
    sweeps.push_back(parse_sweep(a));
    for (std::size_t j = 0; j + 1 < sweeps.size(); ++j)
      if (sweeps[j].key == sweeps.back().key)
        throw InputError("--sweep '" + a + "': " + sweeps.back().key + " is swept twice");
    res.keys.push_back(sweeps.back().key);
  }
  const auto points = grid_points(sweeps);
  if (so.cases.empty()) {
    Case c;
    c.settings = s.info.integrator;
    c.label = settings_label(c.settings);
    c.spec = "(the scene's integrator)";
    res.cases.push_back(c);
  } else {
    for (const auto& in : so.cases)
      for (auto& c : expand_case(in.spec, s.info.integrator, in.where))
        res.cases.push_back(std::move(c));
  }
  d.names = s.names;
  d.units = s.units;
  d.crank_grid = s.info.crank_channel >= 0;
  for (double o = 0.0; o <= so.max_order + 1e-9; o += 0.5) d.orders.push_back(o);
  d.figure_channels = so.order_channels.empty() ? std::vector<int>{0} : [&] {
    std::vector<Channel> sel;
    for (std::size_t i = 0; i < s.names.size(); ++i) sel.push_back({s.names[i], s.units[i]});
    // in the order the patterns are given (the waterfall draws the first asked
    // for, not the first in file order), each channel once
    std::vector<int> out;
    for (const auto& p : split_list(so.order_channels, ','))
      for (int c : p.empty() ? std::vector<int>{} : select_channels(sel, p, "--order-channels"))
        if (std::find(out.begin(), out.end(), c) == out.end()) out.push_back(c);
    return out;
  }();

  // every point's scene must read and give the same channels: checked before any run
  std::vector<TaskSpec> tasks;
  std::vector<std::size_t> output_rows;  // per task: its cost estimate
  for (std::size_t p = 0; p < points.size(); ++p) {
    std::vector<std::string> assign;
    std::string where = "--sweep point " + std::to_string(p);
    for (std::size_t j = 0; j < res.keys.size(); ++j) {
      assign.push_back(res.keys[j] + "=" + points[p][j]);
      where += (j ? ", " : " (") + assign.back();
    }
    where += ")";
    SceneSource src;
    std::vector<int> idx;
    std::size_t rows = 0;
    try {
      src = edited(s.src, assign, "--sweep");
      const SceneInfo info = probe_scene(src);
      idx = channels_by_name(info, s.names);
      rows = info.times.size();
      // the checks evas run makes on its scene, for every point (a speed in rpm
      // where rad/s are read, a step in the wrong unit)
      for (const auto& w : info.warnings)
        if (std::find(s.info.warnings.begin(), s.info.warnings.end(), w) == s.info.warnings.end())
          res.warnings.push_back(where.substr(8) + ": " + w);
    } catch (const InputError& e) {
      throw InputError(where + ": " + e.what());
    }
    for (std::size_t c = 0; c < res.cases.size(); ++c) {
      TaskSpec t;
      t.src = src;
      t.settings = res.cases[c].settings;
      t.channels = idx;
      t.repeats = opt.repeats;
      t.max_wall = opt.max_wall;
      t.periodic = so.periodic;
      t.periodic_tol = so.periodic_tol;
      tasks.push_back(std::move(t));
      output_rows.push_back(rows);
      SweepTask st;
      st.point = static_cast<int>(p);
      st.case_index = static_cast<int>(c);
      st.values = points[p];
      st.result.c = res.cases[c];
      res.tasks.push_back(std::move(st));
    }
  }
  for (const auto& w : res.warnings) say(opt, "evas study sweep: warning: " + w);
  const double check_seconds = since(started) - setup_seconds;
  d.amplitude.assign(res.tasks.size(), {});
  res.info = make_info(s);
  res.setup_seconds = setup_seconds;
  res.check_seconds = check_seconds;
  res.info.window = so.periodic.empty()
                        ? "last " + std::to_string(so.cycles) + " cycle(s) per spectrum"
                        : "the periodic cycle of every point (evas periodic, " + so.periodic +
                              ", defect " + gnum(so.periodic_tol, 3) +
                              (so.warm_start ? ", each search from the periodic state of the "
                                               "point before it"
                                             : ", every search from the scene's initial state") +
                              ")";
  const fs::path dir = s.out;
  auto key_of = [&](std::size_t k) {
    return task_key(res.keys, res.tasks[k].values,
                    res.cases[static_cast<std::size_t>(res.tasks[k].case_index)]);
  };
  auto print_of = [&](std::size_t k) { return task_fingerprint(tasks[k]); };
  auto record = [&](std::size_t k, const RunData& run, const std::string& worker) {
    SweepTask& t = res.tasks[k];
    t.data = run;
    t.worker = worker;
    t.result.status = run.status;
    t.result.message = run.message;
    t.result.wall = run.wall;
    t.result.rows = run.rows();
    t.result.stats = run.stats;
    analyse_task(d, so, k);
  };
  std::error_code ec;
  fs::create_directories(dir / "points", ec);
  if (ec)
    throw InputError((dir / "points").string() + ": cannot create the folder: " + ec.message());

  // --point I: one task into the folder, as a batch array job does
  if (so.point >= 0) {
    if (so.point >= static_cast<int>(tasks.size()))
      throw InputError("--point " + std::to_string(so.point) + ": the sweep has " +
                       std::to_string(tasks.size()) + " tasks (0 to " +
                       std::to_string(tasks.size() - 1) + ")");
    const auto k = static_cast<std::size_t>(so.point);
    const RunData run = run_task(tasks[k], opt.stop);
    if (stopped(opt)) {
      res.info.interrupted = true;
      return res;
    }
    record(k, run, "this process (--point)");
    write_task_file(dir / task_file_name(so.point), d, k, key_of(k), print_of(k));
    res.info.files.push_back((dir / task_file_name(so.point)).string());
    res.runner = "one task (--point)";
    say(opt, "evas study sweep: task " + std::to_string(k) + " " + to_text(run.status));
    return res;
  }

  RunLock lock(dir);
  const bool earlier = fs::exists(dir / "sweep.h5") || !fs::is_empty(dir / "points");
  if (earlier && !so.resume && !so.merge)
    throw InputError(dir.string() +
                     ": holds a sweep already (sweep.h5 or points/); --resume continues it, "
                     "--merge rebuilds its files, or choose another --out");
  std::vector<int> todo;
  for (std::size_t k = 0; k < tasks.size(); ++k) {
    const fs::path f = dir / task_file_name(static_cast<int>(k));
    if ((so.resume || so.merge) && fs::exists(f) &&
        read_task_file(f, d, k, key_of(k), print_of(k))) {
      analyse_task(d, so, k);
      if (so.merge || res.tasks[k].result.status == CaseStatus::completed) {
        ++res.resumed;
        continue;
      }
    }
    if (!so.merge) todo.push_back(static_cast<int>(k));
  }
  TaskRunner& runner = runner_of(opt);
  if (runner.width() > 1) longest_first(todo, output_rows);
  res.runner = so.merge ? "merged from points/" : runner.describe();
  say(opt, "evas study sweep: scene '" + s.info.name + "', " + std::to_string(points.size()) +
               " points x " + std::to_string(res.cases.size()) + " case(s), " +
               std::to_string(todo.size()) + " to run (" + res.runner + ") -> " + dir.string());
  write_sweep_tables(opt, d);
  // the coordinator's own time: everything but waiting for the runs (the
  // serial share of a parallel sweep, docs/performance.md)
  res.coordinator_seconds = since(started);
  auto last_h5 = Clock::now();
  std::size_t finished = 0;
  auto done = [&](const TaskEnd& e) {
    const auto busy = Clock::now();
    const auto k = static_cast<std::size_t>(e.index);
    record(k, e.run, e.worker);
    write_task_file(dir / task_file_name(e.index), d, k, key_of(k), print_of(k));
    ++finished;
    say(opt, "[" + std::to_string(finished) + "/" + std::to_string(todo.size()) + "] task " +
                 std::to_string(k) + " (" + key_of(k) + "): " + to_text(e.run.status) +
                 (e.run.status == CaseStatus::failed ? ": " + e.run.message : "") + ", " +
                 gnum(e.run.wall, 4) + " s" +
                 (res.tasks[k].start.empty() ? "" : ", started from " + res.tasks[k].start));
    write_sweep_tables(opt, d);
    // the big file at most every 10 s; the task files are the record
    if (std::chrono::duration<double>(Clock::now() - last_h5).count() > 10.0) {
      write_sweep_h5(opt, d, so);
      last_h5 = Clock::now();
    }
    res.coordinator_seconds += since(busy);
  };
  // periodic points in warm-start chains (sweep_chains.h): wave by wave, each
  // task from its predecessor's periodic state when that one converged
  const std::vector<int> pred =
      !so.periodic.empty() && so.warm_start
          ? warm_predecessors(points.size(), res.cases.size(), runner.width())
          : std::vector<int>(tasks.size(), -1);
  const std::vector<int> wave_of = chain_waves(pred);
  const int waves = wave_of.empty() ? 0 : *std::max_element(wave_of.begin(), wave_of.end()) + 1;
  for (int w = 0; w < waves && !stopped(opt); ++w) {
    std::vector<int> wave;
    for (int k : todo)
      if (wave_of[static_cast<std::size_t>(k)] == w) wave.push_back(k);
    for (int k : wave) {
      const auto ku = static_cast<std::size_t>(k);
      tasks[ku].initial.clear();
      res.tasks[ku].start.clear();
      const int j = pred[ku];
      if (j < 0) continue;
      const SweepTask& before = res.tasks[static_cast<std::size_t>(j)];
      if (before.result.status == CaseStatus::completed && !before.data.state.empty()) {
        tasks[ku].initial = before.data.state;
        res.tasks[ku].start = "point " + std::to_string(before.point);
      }
    }
    if (!wave.empty()) runner.run(tasks, wave, done, opt.stop);
  }
  const auto after = Clock::now();
  if (stopped(opt)) res.info.interrupted = true;
  d.natural = campbell_frequencies(s.src, d, so);
  assembled_campbell(tasks, d, so);
  write_campbell_csv(fs::path(res.info.out_dir) / "campbell.csv", d);
  write_sweep_h5(opt, d, so);
  plot_sweep(opt, d, so, gnuplot.get());
  res.finish_seconds = since(after);
  res.coordinator_seconds += res.finish_seconds;
  // the coordinator's own processor time: the runs of forked workers and of
  // other ranks are not in it (in one process they are, so none is given)
  if (!so.merge && runner.width() > 1)
    res.coordinator_cpu_seconds = process_cpu_seconds() - cpu_started;
  write_sweep_tables(opt, d);  // with the coordinator's time
  return res;
}

}  // namespace evas::study
