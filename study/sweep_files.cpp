// The files of `evas study sweep` (sweep.h): task files, sweep.h5/.csv/.md,
// and the analysis behind the figures (order spectra, mean speed).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

#include "io/scene.h"
#include "solver/system.h"
#include "study/report.h"
#include "study/sweep_detail.h"

namespace evas::study::detail {

namespace {

constexpr double kDegPerSecPerRpm = 6.0;  // 1 rpm = 360 deg / 60 s

std::vector<double> row_major(const Mat& y) {
  std::vector<double> v(static_cast<std::size_t>(y.size()));
  for (long r = 0; r < y.rows(); ++r)
    for (long c = 0; c < y.cols(); ++c) v[static_cast<std::size_t>(r * y.cols() + c)] = y(r, c);
  return v;
}

// Written plain (not compressed): deflate took 0.2 s of the coordinator's
// time per 8 MB (an 8-point engine sweep), which the workers wait for.
void write_channels(hid_t g, const RunData& run) {
  constexpr bool compress = false;
  h5::write_doubles(g, "time", {run.time.size()}, run.time.data(), compress);
  h5::write_doubles(g, "crank_angle", {run.crank.size()}, run.crank.data(), compress);
  const std::vector<double> v = row_major(run.y);
  h5::write_doubles(g, "values",
                    {static_cast<hsize_t>(run.y.rows()), static_cast<hsize_t>(run.y.cols())},
                    v.data(), compress);
}

// The statistics' bytes (exact) as a little int32 array, beside readable attributes.
void write_stats(hid_t g, const IntegratorStats& s) {
  const std::string raw = stats_to_bytes(s);
  std::vector<int> bytes;
  for (char c : raw) bytes.push_back(static_cast<unsigned char>(c));
  h5::write_int32s(g, "stats_bytes", {bytes.size()}, bytes.data(), false);
  for (const auto& f : stat_fields())
    h5::write_attribute(g, std::string("stats.") + f.name, f.get(s));
}

}  // namespace

void analyse_task(SweepData& d, const SweepOptions& so, std::size_t k) {
  SweepTask& t = d.res.tasks[k];
  const RunData& run = t.data;
  d.amplitude[k].clear();
  t.rpm = kNaN;
  if (!d.crank_grid || run.crank.size() < 2) return;
  t.rpm = (run.crank.back() - run.crank.front()) / (run.time.back() - run.time.front()) /
          kDegPerSecPerRpm;
  if (t.result.status != CaseStatus::completed) return;
  std::vector<std::vector<double>> cols(static_cast<std::size_t>(run.y.cols()));
  std::vector<const std::vector<double>*> ys;
  for (long c = 0; c < run.y.cols(); ++c) {
    auto& y = cols[static_cast<std::size_t>(c)];
    y.assign(run.y.col(c).data(), run.y.col(c).data() + run.y.rows());
    ys.push_back(&y);
  }
  try {
    for (const OrderSpectrum& sp : order_spectra(run.crank, ys, so.cycles, 720.0, so.max_order)) {
      std::vector<double> amp(d.orders.size(), kNaN);
      for (std::size_t i = 0; i < sp.order.size(); ++i)
        for (std::size_t j = 0; j < d.orders.size(); ++j)
          if (std::abs(sp.order[i] - d.orders[j]) < 1e-9) amp[j] = sp.amplitude[i];
      d.amplitude[k].push_back(std::move(amp));
    }
  } catch (const InputError&) {
    // a record shorter than the cycles asked for, or a grid that does not
    // divide the cycle: no spectrum (NaN in sweep.h5)
    d.amplitude[k].clear();
  }
}

void write_task_file(const fs::path& path, const SweepData& d, std::size_t k,
                     const std::string& key, const std::string& fingerprint) {
  const SweepTask& t = d.res.tasks[k];
  write_h5_atomic(path, [&](hid_t f) {
    h5::write_attribute(f, "task", key);
    h5::write_attribute(f, "fingerprint", fingerprint);
    h5::write_attribute(f, "index", static_cast<long long>(k));
    h5::write_attribute(f, "status", std::string(to_text(t.result.status)));
    h5::write_attribute(f, "message", t.result.message);
    h5::write_attribute(f, "wall", t.result.wall);
    h5::write_attribute(f, "worker", t.worker);
    h5::write_strings(f, "names", d.names);
    h5::write_strings(f, "units", d.units);
    write_channels(f, t.data);
    write_stats(f, t.result.stats);
    // a periodic point's cycle start state: the next point's warm start on --resume
    if (!t.data.state.empty())
      h5::write_doubles(f, "state", {t.data.state.size()}, t.data.state.data(), false);
    if (!t.data.cycle_t.empty()) {
      h5::write_doubles(f, "cycle_t", {t.data.cycle_t.size()}, t.data.cycle_t.data(), false);
      h5::write_doubles(f, "cycle_states", {t.data.cycle_states.size()}, t.data.cycle_states.data(),
                        false);
    }
    if (!t.start.empty()) h5::write_attribute(f, "start", t.start);
  });
}

bool read_task_file(const fs::path& path, SweepData& d, std::size_t k, const std::string& key,
                    const std::string& fingerprint) {
  try {
    h5::Quiet quiet;
    h5::Handle f = h5::open_file(path.string());
    if (h5::read_string_attribute(f, "task") != key) return false;
    if (h5::read_string_attribute(f, "fingerprint") != fingerprint) return false;
    if (h5::read_strings(f, "names") != d.names) return false;
    RunData run;
    const std::string status = h5::read_string_attribute(f, "status");
    run.status = status == "completed" ? CaseStatus::completed
                 : status == "failed"  ? CaseStatus::failed
                                       : CaseStatus::not_run;
    run.message = h5::read_string_attribute(f, "message");
    run.wall = h5::read_double_attribute(f, "wall");
    std::vector<hsize_t> dims;
    run.time = h5::read_doubles(f, "time", dims);
    run.crank = h5::read_doubles(f, "crank_angle", dims);
    const std::vector<double> v = h5::read_doubles(f, "values", dims);
    // a run that failed before its first output has no rows (and as a
    // worker's failure no columns either: 0 x 0, as it was sent)
    if (dims.size() != 2 || dims[0] != run.time.size() ||
        (dims[1] != d.names.size() && dims[0] != 0))
      return false;
    run.y.resize(static_cast<long>(dims[0]), static_cast<long>(dims[1]));
    for (long r = 0; r < run.y.rows(); ++r)
      for (long c = 0; c < run.y.cols(); ++c)
        run.y(r, c) = v[static_cast<std::size_t>(r * run.y.cols() + c)];
    const std::vector<long long> bytes = h5::read_int64s(f, "stats_bytes", dims);
    std::string raw;
    for (long long b : bytes) raw += static_cast<char>(static_cast<unsigned char>(b));
    run.stats = stats_from_bytes(raw);  // throws on a wrong size: the task runs again
    if (h5::exists(f, "state")) run.state = h5::read_doubles(f, "state", dims);
    if (h5::exists(f, "cycle_t")) {
      run.cycle_t = h5::read_doubles(f, "cycle_t", dims);
      run.cycle_states = h5::read_doubles(f, "cycle_states", dims);
    }
    SweepTask& t = d.res.tasks[k];
    if (h5::has_attribute(f, "start")) t.start = h5::read_string_attribute(f, "start");
    t.data = std::move(run);
    t.worker = h5::read_string_attribute(f, "worker") + " (earlier run)";
    t.result.status = t.data.status;
    t.result.message = t.data.message;
    t.result.wall = t.data.wall;
    t.result.rows = t.data.rows();
    t.result.stats = t.data.stats;
    return true;
  } catch (const std::exception&) {
    return false;  // unreadable (e.g. cut short by a crash): the task runs again
  }
}

std::vector<NaturalFrequency> campbell_frequencies(const SceneSource& src, const SweepData& d,
                                                   const SweepOptions& so) {
  double top_rpm = 0.0;
  for (const auto& t : d.res.tasks)
    if (std::isfinite(t.rpm)) top_rpm = std::max(top_rpm, std::abs(t.rpm));
  if (!(top_rpm > 0.0)) return {};
  const Scene scene = src.parse();
  return natural_frequencies(*scene.model, 1.2 * so.max_order * top_rpm / 60.0);
}

void assembled_campbell(const std::vector<TaskSpec>& tasks, SweepData& d, const SweepOptions& so) {
  d.assembled.clear();
  d.assembled_note.clear();
  double top_rpm = 0.0;
  for (const auto& t : d.res.tasks)
    if (std::isfinite(t.rpm)) top_rpm = std::max(top_rpm, std::abs(t.rpm));
  if (!(top_rpm > 0.0)) return;
  const double f_max = 1.2 * so.max_order * top_rpm / 60.0;
  std::vector<std::string> notes;
  for (std::size_t k = 0; k < d.res.tasks.size() && k < tasks.size(); ++k) {
    const SweepTask& t = d.res.tasks[k];
    if (t.result.status != CaseStatus::completed) continue;
    if (t.data.cycle_t.empty()) {
      notes.push_back("task " + std::to_string(k) +
                      ": no steady cycle to linearize about (--periodic gives one)");
      continue;
    }
    try {
      const Scene scene = tasks[k].src.parse();
      System sys(*scene.model);
      const std::size_t m = t.data.cycle_t.size(), w = t.data.cycle_states.size() / m;
      std::vector<Vec> qv;
      for (std::size_t i = 0; i < m; ++i)
        qv.push_back(Eigen::Map<const Vec>(t.data.cycle_states.data() + i * w,
                                           static_cast<Eigen::Index>(w)));
      const AssembledModes am = assembled_modes(sys, *scene.model, t.data.cycle_t, qv, f_max);
      if (!am.reason.empty()) notes.push_back("task " + std::to_string(k) + ": " + am.reason);
      for (const AssembledMode& mode : am.modes) d.assembled.push_back({k, t.rpm, mode});
    } catch (const std::exception& e) {
      notes.push_back("task " + std::to_string(k) + ": " + e.what());
    }
  }
  if (!notes.empty())
    d.assembled_note =
        notes.front() +
        (notes.size() > 1 ? " (and " + std::to_string(notes.size() - 1) + " more)" : "");
}

void write_campbell_csv(const fs::path& path, const SweepData& d) {
  std::ostringstream os;
  os << "speed,frequency_hz,label,where,damping_ratio,point,case_index\n";
  for (const auto& a : d.assembled) {
    const SweepTask& t = d.res.tasks[a.task];
    os << gnum(a.rpm, 8) << "," << gnum(a.mode.hz, 8) << "," << csv_field(a.mode.label) << ","
       << a.mode.where << "," << gnum(a.mode.damping_ratio, 6) << "," << t.point << ","
       << t.case_index << "\n";
  }
  write_file_atomic(path, os.str());
}

// --- tables ------------------------------------------------------------------

namespace {

std::vector<CaseResult> task_results(const SweepData& d) {
  std::vector<CaseResult> rows;
  for (const auto& t : d.res.tasks) rows.push_back(t.result);
  return rows;
}

}  // namespace

void write_sweep_tables(const Options& opt, SweepData& d) {
  const SweepResult& res = d.res;
  const fs::path dir = res.info.out_dir;
  std::vector<Column> cols;
  {
    Column point{"point", "point", Column::Kind::Integer, {}, {}};
    for (const auto& t : res.tasks) point.num.push_back(t.point);
    cols.push_back(point);
    for (std::size_t j = 0; j < res.keys.size(); ++j) {
      Column c{res.keys[j], "grid/value" + std::to_string(j), Column::Kind::Text, {}, {}};
      for (const auto& t : res.tasks) c.text.push_back(t.values[j]);
      cols.push_back(c);
    }
    Column rpm{"mean_rpm", "mean_rpm", Column::Kind::Real, {}, {}};
    for (const auto& t : res.tasks) rpm.num.push_back(t.rpm);
    cols.push_back(rpm);
  }
  for (auto& c : case_columns(task_results(d))) {
    if (c.csv == "error") continue;  // a sweep has no reference
    cols.push_back(std::move(c));
  }
  write_file_atomic(dir / "sweep.csv", columns_csv(cols, res.tasks.size()));

  std::ostringstream md;
  md << "# Sweep: " << res.info.scene_name << "\n\n"
     << "- scene: `" << res.info.scene_path << "`\n"
     << "- swept: " << join(res.keys, " x ") << " (" << res.tasks.size() / res.cases.size()
     << " points), cases: " << res.cases.size() << "\n"
     << "- runner: " << res.runner
     << (res.resumed ? ", " + std::to_string(res.resumed) + " task(s) from an earlier run"
                     : std::string())
     << "\n- coordinator: " << gnum(res.coordinator_seconds, 3) << " s of its own: setup "
     << gnum(res.setup_seconds, 2) << " s, checking the points' scenes "
     << gnum(res.check_seconds, 2) << " s, after the runs (sweep.h5, figures) "
     << gnum(res.finish_seconds, 2) << " s, the rest files as results came in"
     << (std::isnan(res.coordinator_cpu_seconds)
             ? std::string()
             : "; processor time " + gnum(res.coordinator_cpu_seconds, 3) + " s")
     << "\n- channels: " << res.info.channels.size() << "; order spectra over "
     << (res.info.window.rfind("the periodic cycle", 0) == 0 ? res.info.window
                                                             : "the last cycle(s) of each run")
     << ", orders 0 to " << gnum(d.orders.back(), 4) << " in steps of 0.5\n";
  for (const auto& w : res.warnings) md << "- **warning**: " << md_cell(w) << "\n";
  md << "\n| task | ";
  for (const auto& k : res.keys) md << md_cell(k) << " | ";
  md << "case | status | mean speed [rpm] | wall [s] | steps |\n|---:|";
  for (std::size_t j = 0; j < res.keys.size(); ++j) md << "---|";
  md << "---|---|---:|---:|---:|\n";
  for (std::size_t k = 0; k < res.tasks.size(); ++k) {
    const SweepTask& t = res.tasks[k];
    md << "| " << k << " | ";
    for (const auto& v : t.values) md << md_cell(v) << " | ";
    md << md_cell(t.result.c.label) << " | " << status_cell(t.result) << " | " << gnum(t.rpm, 6)
       << " | " << gnum(t.result.wall, 4) << " | "
       << (t.result.status == CaseStatus::not_run ? "" : std::to_string(t.result.stats.steps))
       << " |\n";
  }
  write_file_atomic(dir / "sweep.md", md.str());
  (void)opt;
}

void write_sweep_h5(const Options& opt, SweepData& d, const SweepOptions& so) {
  SweepResult& res = d.res;
  StudyInfo& info = res.info;
  const fs::path dir = info.out_dir;
  write_h5_atomic(dir / "sweep.h5", [&](hid_t f) {
    write_info_attributes(f, "sweep", info, opt);
    h5::write_attribute(f, "runner", res.runner);
    h5::write_attribute(f, "keys", join(res.keys, ", "));
    h5::write_attribute(f, "cycles_per_spectrum", static_cast<long long>(so.cycles));
    h5::Handle grid = h5::create_group(f, "grid");
    h5::write_strings(grid, "keys", res.keys);
    const std::size_t np = res.tasks.size() / res.cases.size();
    for (std::size_t j = 0; j < res.keys.size(); ++j) {
      std::vector<std::string> text;
      std::vector<double> num;
      for (std::size_t p = 0; p < np; ++p) {
        const std::string& v = res.tasks[p * res.cases.size()].values[j];
        text.push_back(v);
        char* end = nullptr;
        const double x = std::strtod(v.c_str(), &end);
        num.push_back(!v.empty() && !*end ? x : kNaN);
      }
      h5::write_strings(grid, "value" + std::to_string(j), text);
      h5::write_doubles(grid, "number" + std::to_string(j), {num.size()}, num.data());
    }
    std::vector<std::string> labels;
    for (const auto& c : res.cases) labels.push_back(c.label);
    h5::write_strings(f, "case_labels", labels);

    h5::Handle tasks = h5::create_group(f, "tasks");
    std::vector<long long> point, cs;
    std::vector<double> rpm;
    std::vector<std::string> worker;
    for (const auto& t : res.tasks) {
      point.push_back(t.point);
      cs.push_back(t.case_index);
      rpm.push_back(t.rpm);
      worker.push_back(t.worker);
    }
    h5::write_int64s(tasks, "point", {point.size()}, point.data());
    h5::write_int64s(tasks, "case", {cs.size()}, cs.data());
    h5::write_doubles(tasks, "mean_rpm", {rpm.size()}, rpm.data());
    h5::write_strings(tasks, "worker", worker);
    std::vector<Column> cols = case_columns(task_results(d));
    cols.erase(
        std::remove_if(cols.begin(), cols.end(), [](const Column& c) { return c.csv == "error"; }),
        cols.end());
    write_columns_h5(tasks, cols);

    h5::Handle ch = h5::create_group(f, "channels");
    h5::write_strings(ch, "names", d.names);
    h5::write_strings(ch, "units", d.units);
    for (std::size_t k = 0; k < res.tasks.size(); ++k) {
      std::string name = std::to_string(k);
      name.insert(0, name.size() < 4 ? 4 - name.size() : 0, '0');
      h5::Handle g = h5::create_group(ch, name);
      write_channels(g, res.tasks[k].data);
    }

    h5::Handle ord = h5::create_group(f, "orders");
    h5::write_doubles(ord, "order", {d.orders.size()}, d.orders.data());
    // amplitude[task][channel][order]; NaN where a task has no spectrum
    const std::size_t nt = res.tasks.size(), nc = d.names.size(), no = d.orders.size();
    std::vector<double> amp(nt * nc * no, kNaN);
    for (std::size_t k = 0; k < nt; ++k)
      for (std::size_t c = 0; c < d.amplitude[k].size(); ++c)
        for (std::size_t o = 0; o < no; ++o) amp[(k * nc + c) * no + o] = d.amplitude[k][c][o];
    h5::write_doubles(ord, "amplitude", {nt, nc, no}, amp.data());

    h5::Handle cb = h5::create_group(f, "campbell");
    std::vector<double> hz;
    std::vector<std::string> body, kind, dir_;
    for (const auto& n : d.natural) {
      hz.push_back(n.hz);
      body.push_back(n.body);
      kind.push_back(n.kind);
      dir_.push_back(n.direction);
    }
    h5::write_doubles(cb, "frequency", {hz.size()}, hz.data());
    h5::write_strings(cb, "body", body);
    h5::write_strings(cb, "kind", kind);
    h5::write_strings(cb, "direction", dir_);
    // the assembled system's modes per periodic point (post/assembled_modes.h)
    h5::Handle as = h5::create_group(f, "assembled");
    std::vector<double> arpm, ahz, azeta;
    std::vector<long long> atask;
    std::vector<std::string> alabel, awhere;
    for (const auto& a : d.assembled) {
      arpm.push_back(a.rpm);
      ahz.push_back(a.mode.hz);
      azeta.push_back(a.mode.damping_ratio);
      atask.push_back(static_cast<long long>(a.task));
      alabel.push_back(a.mode.label);
      awhere.push_back(a.mode.where);
    }
    h5::write_doubles(as, "speed", {arpm.size()}, arpm.data());
    h5::write_doubles(as, "frequency", {ahz.size()}, ahz.data());
    h5::write_doubles(as, "damping_ratio", {azeta.size()}, azeta.data());
    h5::write_int64s(as, "task", {atask.size()}, atask.data());
    h5::write_strings(as, "label", alabel);
    h5::write_strings(as, "where", awhere);
    h5::write_attribute(as, "note", d.assembled_note);
  });
}

}  // namespace evas::study::detail
