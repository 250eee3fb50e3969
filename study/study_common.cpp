// What the `evas study` drivers share (study_common.h): the scene setup, the
// reference run or file, the loop over the cases of work_precision and
// convergence, the case table (CSV, Markdown, HDF5) and the gnuplot helpers.
#include "study/study_common.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "integrators/settings.h"
#include "io/results.h"
#include "plot/gnuplot_process.h"
#include "study/expression.h"
#include "study/report.h"

namespace evas::study::detail {

namespace {

bool same_time(double a, double b, double scale) {
  return std::abs(a - b) <= 1e-9 * std::max({std::abs(a), std::abs(b), scale});
}

CaseResult evaluate(const Case& c, const RunData& d, const Reference& ref,
                    const std::vector<int>& rows, const ErrorMeasure& m,
                    const std::vector<std::string>& units, double scale) {
  CaseResult r;
  r.c = c;
  r.status = d.status;
  r.message = d.message;
  r.wall = d.wall;
  r.rows = d.rows();
  r.stats = d.stats;
  if (d.status != CaseStatus::completed) return r;
  bool same = d.time.size() == ref.time.size();
  for (std::size_t i = 0; same && i < d.time.size(); ++i)
    same = same_time(d.time[i], ref.time[i], scale);
  if (!same) {
    r.status = CaseStatus::failed;
    r.message = "the output times differ from the reference's";
    return r;
  }
  ChannelErrors e = channel_errors(d.y, ref.y, rows, m, units);
  r.error = e.total;
  r.channel_error = std::move(e.error);
  if (e.worst >= 0) r.error_channel = ref.names[static_cast<std::size_t>(e.worst)];
  return r;
}

std::string case_line(std::size_t k, std::size_t n, const CaseResult& r) {
  std::ostringstream os;
  os << "evas study: [" << k << "/" << n << "] " << r.c.label << ": ";
  if (r.status == CaseStatus::completed)
    os << "error " << sci(r.error, 3) << ", " << gnum(r.wall, 3) << " s, " << r.stats.steps
       << " steps, " << r.stats.residual_evals << " residuals";
  else
    os << to_text(r.status) << (r.message.empty() ? "" : ": " + r.message);
  return os.str();
}

}  // namespace

// A settings label without the tokens "KEY=..." of the given keys.
std::string strip_keys(const std::string& label, const std::set<std::string>& keys) {
  std::istringstream is(label);
  std::string word, out;
  while (is >> word) {
    const auto eq = word.find('=');
    if (eq != std::string::npos && keys.count(word.substr(0, eq))) continue;
    out += (out.empty() ? "" : " ") + word;
  }
  return out;
}

void tie_iteration_tolerance(const Options& opt, std::vector<Case>& cases,
                             const IntegratorSettings& base) {
  if (base.balance_tol != IntegratorSettings{}.balance_tol) return;  // the scene chose it
  int tied = 0;
  for (Case& c : cases) {
    if (c.spec.find("balance_tol=") != std::string::npos) continue;
    if (!integrator_capabilities(c.settings.name).reads_setting("balance_tol")) continue;
    if (!integrator_capabilities(c.settings.name).declared) continue;  // a plug-in: its own
    c.settings.balance_tol = kStudyBalanceTol;
    c.label = settings_label(c.settings);
    ++tied;
  }
  if (tied > 0)
    say(opt,
        "evas study: " + std::to_string(tied) +
            " case(s) of linear-acceleration run with balance_tol=" + gnum(kStudyBalanceTol, 3) +
            " (its default 1e-3 is an iteration error that does not shrink with the step; "
            "give balance_tol in the case spec to study the iteration itself)");
}

bool stopped(const Options& o) { return o.stop && o.stop(); }

void say(const Options& o, const std::string& line) {
  if (o.log) *o.log << line << "\n" << std::flush;
}

Setup prepare(const Options& opt) {
  if (opt.repeats < 1) throw InputError("--repeats must be >= 1");
  Setup s;
  s.src = load_scene_source(opt.scene, opt.params, opt.t_end);
  s.params = opt.params.size();
  if (opt.start.steady && opt.t_end)
    throw InputError("--steady runs one period from the periodic state: leave out --t-end");
  s.started = start_from(s.src, opt.start, opt.stop, opt.log);
  s.info = probe_scene(s.src);
  for (const std::string& w : s.info.warnings) say(opt, "evas study: warning: " + w);
  if (!opt.reference_exprs.empty()) {
    // the expressions name the channels compared
    if (!opt.channels.empty())
      throw InputError("--channels and --reference-expr: the expressions name the channels");
    for (const auto& e : opt.reference_exprs) {
      const auto eq = e.find('=');
      const std::string name = eq == std::string::npos ? "" : e.substr(0, eq);
      if (name.empty())
        throw InputError("--reference-expr '" + e +
                         "': expected CHANNEL=EXPR, e.g. "
                         "'c.px=1e-3*sin(2*pi*15*t)'");
      s.channels.push_back(select_channels(s.info.channels, name).front());
      if (s.info.channels[static_cast<std::size_t>(s.channels.back())].name != name)
        throw InputError("--reference-expr '" + e + "': name one channel exactly, not a glob");
    }
  } else {
    s.channels = select_channels(s.info.channels, opt.channels);
  }
  for (int c : s.channels) {
    s.names.push_back(s.info.channels[static_cast<std::size_t>(c)].name);
    s.units.push_back(s.info.channels[static_cast<std::size_t>(c)].unit);
  }
  s.measure = parse_measure(opt.norm);
  if (opt.window.empty()) {
    s.window_default = true;
    if (s.info.crank_channel >= 0) s.window = parse_window("last-cycles=1");
  } else {
    s.window = parse_window(opt.window);
    if (s.window.kind == Window::Kind::LastCycles && s.info.crank_channel < 0)
      throw InputError("--window " + s.window.text() +
                       ": needs a crank-angle output grid; the scene's output is on the " +
                       s.info.grid + " grid (use all or T0:T1)");
    if (!s.info.crank.empty() || s.window.kind != Window::Kind::LastCycles)
      window_rows(s.window, s.info.times, s.info.crank);  // early check, before any run
  }
  if (s.window_default && s.window.kind == Window::Kind::LastCycles && !s.info.crank.empty()) {
    try {
      window_rows(s.window, s.info.times, s.info.crank);
    } catch (const InputError& e) {
      say(opt, std::string("evas study: ") + e.what() + "; the window is all outputs instead");
      s.window = Window{};
    }
  }
  s.out = opt.out_dir.empty() ? fs::path("out") / ("study-" + s.info.name) : fs::path(opt.out_dir);
  std::error_code ec;
  s.created_out = !fs::exists(s.out, ec);
  fs::create_directories(s.out, ec);
  if (ec)
    throw InputError(s.out.string() + ": cannot create the output directory: " + ec.message());
  // the start state as a file of its own: evas run --initial reproduces a case
  if (!s.started.state_text.empty()) write_file_atomic(s.out / "state.yaml", s.started.state_text);
  return s;
}

EmptyOutGuard::~EmptyOutGuard() {
  std::error_code ec;
  if (s_.created_out && fs::is_directory(s_.out, ec) && fs::is_empty(s_.out, ec) && !ec)
    fs::remove(s_.out, ec);
}

StudyInfo make_info(const Setup& s) {
  StudyInfo i;
  // the scene's name, marked when --param changed the scene it names (so that
  // the tables and figures of the changed scene do not carry the plain one's name)
  i.scene_name = s.info.name;
  if (s.params > 0)
    i.scene_name += " with " + std::to_string(s.params) + " --param" + (s.params > 1 ? "s" : "");
  i.scene_path = s.src.path;
  i.scene_text = s.src.text;
  i.grid = s.info.grid;
  i.channels = s.names;
  i.window = s.window.text();
  i.norm = measure_text(s.measure);
  i.error_definition = error_definition(s.measure, s.window);
  i.start = s.started.description;
  i.out_dir = s.out.string();
  return i;
}

// The reference case of a spec on a scene (exactly one case).
Case reference_case(const std::string& spec, const IntegratorSettings& base) {
  std::vector<Case> cases = expand_case(spec, base, "--reference '" + spec + "'");
  if (cases.size() != 1)
    throw InputError("--reference '" + spec + "': must be a single case (it expands to " +
                     std::to_string(cases.size()) + ")");
  return cases.front();
}

Reference run_reference(const Options& opt, const SceneSource& src, const SceneInfo& info,
                        const std::vector<int>& channels, const std::vector<std::string>& names,
                        const std::vector<std::string>& units) {
  const Case c = reference_case(opt.reference, info.integrator);
  say(opt, "evas study: reference " + c.label + " ...");
  Reference r =
      reference_of(c, run_case(src, c.settings, channels, nullptr, opt.stop), info, names, units);
  say(opt, "evas study: reference " + c.label + ": " + std::to_string(r.stats.steps) + " steps, " +
               gnum(r.wall, 3) + " s");
  return r;
}

Reference reference_of(const Case& c, const RunData& d, const SceneInfo& info,
                       const std::vector<std::string>& names,
                       const std::vector<std::string>& units) {
  if (d.status != CaseStatus::completed)
    throw ReferenceFailed("the reference run '" + c.label + "' failed: " + d.message);
  if (d.time.size() != info.times.size())
    throw ReferenceFailed("the reference run '" + c.label + "' gave " +
                          std::to_string(d.time.size()) + " of " +
                          std::to_string(info.times.size()) + " output rows");
  Reference r;
  r.description = c.label;
  r.time = d.time;
  r.crank = d.crank;
  r.y = d.y;
  r.names = names;
  r.units = units;
  r.stats = d.stats;
  r.wall = d.wall;
  return r;
}

Reference read_reference(const Options& opt, const SceneInfo& info,
                         const std::vector<std::string>& names,
                         const std::vector<std::string>& units) {
  const std::string& path = opt.reference_file;
  const ResultsData f = read_results(path);
  Reference r;
  r.description = path + " (" + f.integrator + ", " + f.status + ")";
  std::vector<int> cols;
  for (const auto& n : names) {
    const auto it = std::find(f.names.begin(), f.names.end(), n);
    if (it == f.names.end())
      throw InputError("--reference-file " + path + ": no channel '" + n + "' (the file has: " +
                       [&] {
                         std::string s;
                         for (const auto& x : f.names) s += (s.empty() ? "" : ", ") + x;
                         return s;
                       }() +
                       ")");
    cols.push_back(static_cast<int>(it - f.names.begin()));
  }
  int crank = -1;
  for (std::size_t i = 0; i < f.names.size(); ++i)
    if (f.names[i] == "crank_angle") crank = static_cast<int>(i);
  const double scale = std::abs(info.t_end - info.t_start);
  std::vector<int> rows;
  std::size_t j = 0;
  for (double t : info.times) {
    while (j < f.time.size() && f.time[j] < t && !same_time(f.time[j], t, scale)) ++j;
    if (j >= f.time.size() || !same_time(f.time[j], t, scale))
      throw InputError(
          "--reference-file " + path + ": no output row at t = " + gnum(t, 12) +
          " s of the scene's output grid (the file has " + std::to_string(f.time.size()) + " rows" +
          (f.time.empty()
               ? std::string()
               : ", t = " + gnum(f.time.front(), 9) + " .. " + gnum(f.time.back(), 9) + " s") +
          "; it must come from the same scene, grid and end time)");
    rows.push_back(static_cast<int>(j));
    ++j;
  }
  r.y.resize(static_cast<long>(rows.size()), static_cast<long>(cols.size()));
  for (std::size_t k = 0; k < rows.size(); ++k) {
    r.time.push_back(info.times[k]);
    if (crank >= 0) r.crank.push_back(f.values(rows[k], crank));
    for (std::size_t c = 0; c < cols.size(); ++c)
      r.y(static_cast<long>(k), static_cast<long>(c)) = f.values(rows[k], cols[c]);
  }
  if (r.crank.empty()) r.crank = info.crank;
  r.names = names;
  r.units = units;
  say(opt, "evas study: reference " + r.description);
  return r;
}

// The analytic reference: every expression at the scene's output times.
Reference analytic_reference(const Options& opt, const Setup& s) {
  Reference r;
  r.names = s.names;
  r.units = s.units;
  r.time = s.info.times;
  r.crank = s.info.crank;
  r.y.resize(static_cast<long>(r.time.size()), static_cast<long>(s.names.size()));
  std::string desc;
  for (std::size_t c = 0; c < opt.reference_exprs.size(); ++c) {
    const std::string& e = opt.reference_exprs[c];
    const Expression f(e.substr(e.find('=') + 1), "--reference-expr " + s.names[c]);
    for (std::size_t k = 0; k < r.time.size(); ++k) {
      const double v = f(r.time[k]);
      if (!std::isfinite(v))
        throw InputError("--reference-expr '" + e + "': not finite at t = " + gnum(r.time[k], 9) +
                         " s");
      r.y(static_cast<long>(k), static_cast<long>(c)) = v;
    }
    desc += (desc.empty() ? "" : "; ") + s.names[c] + " = " + f.text();
  }
  r.description = "analytic: " + desc;
  say(opt, "evas study: reference " + r.description);
  return r;
}

Reference make_reference(const Options& opt, const Setup& s) {
  if (!opt.reference_exprs.empty()) return analytic_reference(opt, s);
  if (!opt.reference_file.empty()) return read_reference(opt, s.info, s.names, s.units);
  return run_reference(opt, s.src, s.info, s.channels, s.names, s.units);
}

// Window rows on the reference (falls back to all for a default window that does not fit).
std::vector<int> reference_rows(const Options& opt, Setup& s, const Reference& ref) {
  try {
    return window_rows(s.window, ref.time, ref.crank);
  } catch (const InputError& e) {
    if (!s.window_default) throw;
    say(opt, std::string("evas study: ") + e.what() + "; the window is all outputs instead");
    s.window = Window{};
    return window_rows(s.window, ref.time, ref.crank);
  }
}

std::vector<TaskSpec> case_tasks(const Options& opt, const Setup& s,
                                 const std::vector<Case>& cases) {
  std::vector<TaskSpec> tasks;
  for (const auto& c : cases) {
    TaskSpec t;
    t.src = s.src;
    t.settings = c.settings;
    t.channels = s.channels;
    t.repeats = opt.repeats;
    t.max_wall = opt.max_wall;
    tasks.push_back(std::move(t));
  }
  return tasks;
}

TaskRunner& runner_of(const Options& opt) {
  static const std::unique_ptr<TaskRunner> serial = serial_runner();
  return opt.runner ? *opt.runner : *serial;
}

void run_cases(const Options& opt, const Setup& s, const std::vector<Case>& cases,
               const Reference& ref, const std::vector<int>& rows, std::vector<CaseResult>& results,
               StudyInfo& info, const std::function<void()>& on_case_done) {
  const double scale = std::abs(s.info.t_end - s.info.t_start);
  const std::vector<TaskSpec> tasks = case_tasks(opt, s, cases);
  std::vector<int> todo(cases.size());
  for (std::size_t k = 0; k < cases.size(); ++k) todo[k] = static_cast<int>(k);
  runner_of(opt).run(
      tasks, todo,
      [&](const TaskEnd& e) {
        const auto k = static_cast<std::size_t>(e.index);
        results[k] = evaluate(cases[k], e.run, ref, rows, s.measure, s.units, scale);
        say(opt, case_line(k + 1, cases.size(), results[k]));
        on_case_done();
      },
      opt.stop);
  if (stopped(opt)) info.interrupted = true;
}

// --- tables ------------------------------------------------------------------

std::vector<Column> case_columns(const std::vector<CaseResult>& rows) {
  std::vector<Column> cols;
  auto text = [&](const std::string& name, const std::string& h5,
                  const std::function<std::string(const CaseResult&)>& f) {
    Column c{name, h5, Column::Kind::Text, {}, {}};
    for (const auto& r : rows) c.text.push_back(f(r));
    cols.push_back(std::move(c));
  };
  auto num = [&](const std::string& name, const std::string& h5, Column::Kind kind,
                 const std::function<double(const CaseResult&)>& f) {
    Column c{name, h5, kind, {}, {}};
    for (const auto& r : rows) c.num.push_back(f(r));
    cols.push_back(std::move(c));
  };
  std::set<std::string> keys;
  text("label", "label", [](const CaseResult& r) { return r.c.label; });
  text("integrator", "integrator", [](const CaseResult& r) { return r.c.settings.name; });
  for (const auto& info : integrator_settings()) {
    if (info.key == "name") continue;
    keys.insert(info.key);
    text(info.key, "settings/" + info.key,
         [&](const CaseResult& r) { return get_integrator_setting(r.c.settings, info.key); });
  }
  text("status", "status", [](const CaseResult& r) { return std::string(to_text(r.status)); });
  text("message", "message", [](const CaseResult& r) { return r.message; });
  num("error", "error", Column::Kind::Real, [](const CaseResult& r) { return r.error; });
  num("wall", "wall", Column::Kind::Real, [](const CaseResult& r) { return r.wall; });
  num("rows", "rows", Column::Kind::Integer, [](const CaseResult& r) { return double(r.rows); });
  text("error_channel", "error_channel", [](const CaseResult& r) { return r.error_channel; });
  for (const auto& f : stat_fields()) {
    const std::string name = keys.count(f.name) ? std::string(f.name) + "_taken" : f.name;
    const auto get = f.get;
    num(name, std::string("stats/") + f.name,
        f.integer ? Column::Kind::Integer : Column::Kind::Real, [get](const CaseResult& r) {
          return r.status == CaseStatus::not_run ? kNaN : get(r.stats);
        });
  }
  return cols;
}

std::string columns_csv(const std::vector<Column>& cols, std::size_t nrows) {
  std::ostringstream os;
  for (std::size_t i = 0; i < cols.size(); ++i) os << (i ? "," : "") << csv_field(cols[i].csv);
  os << "\n";
  for (std::size_t r = 0; r < nrows; ++r) {
    for (std::size_t i = 0; i < cols.size(); ++i) {
      const Column& c = cols[i];
      os << (i ? "," : "");
      if (c.kind == Column::Kind::Text)
        os << csv_field(c.text[r]);
      else if (c.kind == Column::Kind::Integer)
        os << inum(c.num[r]);
      else
        os << gnum(c.num[r], 9);
    }
    os << "\n";
  }
  return os.str();
}

void write_columns_h5(hid_t group, const std::vector<Column>& cols) {
  for (const Column& c : cols) {
    const auto slash = c.h5.find('/');
    hid_t loc = group;
    h5::Handle sub;
    if (slash != std::string::npos) {
      const std::string g = c.h5.substr(0, slash);
      sub = h5::exists(group, g) ? h5::open_group(group, g) : h5::create_group(group, g);
      loc = sub.get();
    }
    const std::string name = slash == std::string::npos ? c.h5 : c.h5.substr(slash + 1);
    const std::vector<hsize_t> dims = {c.kind == Column::Kind::Text ? c.text.size() : c.num.size()};
    if (c.kind == Column::Kind::Text) {
      h5::write_strings(loc, name, c.text);
    } else if (c.kind == Column::Kind::Integer) {
      std::vector<long long> v;
      for (double x : c.num) v.push_back(std::isnan(x) ? -1 : static_cast<long long>(x));
      h5::write_int64s(loc, name, dims, v.data());
    } else {
      h5::write_doubles(loc, name, dims, c.num.data());
    }
  }
}

std::string join(const std::vector<std::string>& v, const std::string& sep) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : sep) + x;
  return s;
}

std::string md_header(const std::string& title, const StudyInfo& info, const Options& opt,
                      const Reference& ref) {
  std::ostringstream md;
  md << "# " << title << ": " << info.scene_name << "\n\n";
  md << "- scene: `" << info.scene_path << "`";
  if (!opt.params.empty()) md << " with " << md_cell(join(opt.params));
  if (opt.t_end) md << ", end time " << gnum(*opt.t_end, 9) << " s";
  md << " (" << info.grid << " grid)\n";
  md << "- reference: " << md_cell(ref.description);
  if (!std::isnan(ref.wall))
    md << " (" << ref.stats.steps << " steps, " << gnum(ref.wall, 3) << " s)";
  md << "\n";
  md << "- channels: " << md_cell(join(info.channels)) << "\n";
  if (!info.start.empty())
    md << "- every run starts from " << md_cell(info.start) << " (state.yaml)\n";
  md << "- " << info.error_definition << "\n";
  md << "- wall: init + integrate [s], minimum over " << opt.repeats << " run"
     << (opt.repeats > 1 ? "s" : "") << "\n";
  if (info.interrupted) md << "- **interrupted**: the cases marked `not run` were not run\n";
  md << "\n";
  return md.str();
}

std::string status_cell(const CaseResult& r) {
  if (r.status == CaseStatus::failed) return "failed: " + md_cell(r.message, 70);
  return to_text(r.status);
}

std::string errors_csv(const std::vector<CaseResult>& cases, const Reference& ref,
                       const std::vector<int>& rows, const StudyInfo& info) {
  const ChannelErrors scales =
      channel_errors(ref.y, ref.y, rows, parse_measure(info.norm), ref.units);
  std::ostringstream os;
  os << "case,label,channel,unit,scale,error,sets_error\n";
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const CaseResult& r = cases[k];
    for (std::size_t c = 0; c < ref.names.size(); ++c) {
      const double e = c < r.channel_error.size() ? r.channel_error[c] : kNaN;
      os << k << "," << csv_field(r.c.label) << "," << csv_field(ref.names[c]) << ","
         << csv_field(c < ref.units.size() ? ref.units[c] : "") << "," << gnum(scales.scale[c], 9)
         << "," << gnum(e, 9) << "," << (!std::isnan(e) && ref.names[c] == r.error_channel ? 1 : 0)
         << "\n";
    }
  }
  return os.str();
}

void write_channel_errors_h5(hid_t g, const std::vector<CaseResult>& cases, std::size_t channels) {
  std::vector<double> v(cases.size() * channels, kNaN);
  for (std::size_t k = 0; k < cases.size(); ++k)
    for (std::size_t c = 0; c < channels && c < cases[k].channel_error.size(); ++c)
      v[k * channels + c] = cases[k].channel_error[c];
  h5::write_doubles(g, "channel_error", {cases.size(), channels}, v.data());
}

void write_reference_h5(hid_t file, const Reference& ref, const std::vector<int>& rows) {
  h5::Handle g = h5::create_group(file, "reference");
  h5::write_attribute(g, "description", ref.description);
  const hsize_t nt = ref.time.size(), nc = static_cast<hsize_t>(ref.y.cols());
  h5::write_doubles(g, "time", {nt}, ref.time.data());
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> y = ref.y;
  h5::write_doubles(g, "values", {nt, nc}, y.data());
  h5::write_strings(g, "names", ref.names);
  h5::write_strings(g, "units", ref.units);
  if (!ref.crank.empty()) h5::write_doubles(g, "crank_angle", {nt}, ref.crank.data());
  std::vector<long long> w(rows.begin(), rows.end());
  h5::write_int64s(g, "window_rows", {w.size()}, w.data());
  const std::vector<double> amp = amplitudes(ref.y, rows);
  h5::write_doubles(g, "amplitude", {amp.size()}, amp.data());
  if (!std::isnan(ref.wall)) {
    h5::write_attribute(g, "wall", ref.wall);
    h5::write_attribute(g, "steps", static_cast<long long>(ref.stats.steps));
  }
}

void write_h5_atomic(const fs::path& path, const std::function<void(hid_t)>& body) {
  const fs::path tmp = path.string() + ".tmp";
  {
    h5::Quiet quiet;
    try {
      h5::Handle f = h5::create_file(tmp.string());
      body(f);
    } catch (const h5::Failure& e) {
      throw RunError(path.string() + ": " + e.what());
    }
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) throw RunError(path.string() + ": cannot replace: " + ec.message());
}

void write_info_attributes(hid_t f, const std::string& kind, const StudyInfo& info,
                           const Options& opt) {
  h5::write_attribute(f, "study", kind);
  h5::write_attribute(f, "scene_name", info.scene_name);
  h5::write_attribute(f, "scene_path", info.scene_path);
  h5::write_attribute(f, "scene", info.scene_text);
  h5::write_attribute(f, "grid", info.grid);
  h5::write_attribute(f, "channels", join(info.channels, ","));
  h5::write_attribute(f, "window", info.window);
  h5::write_attribute(f, "norm", info.norm);
  h5::write_attribute(f, "error_definition", info.error_definition);
  if (!info.start.empty()) h5::write_attribute(f, "start", info.start);
  h5::write_attribute(f, "repeats", static_cast<long long>(opt.repeats));
  h5::write_attribute(f, "status", info.interrupted ? "interrupted" : "completed");
}

// --- gnuplot ------------------------------------------------------------------

bool plot(const Options& opt, const fs::path& script, const std::string& text, StudyInfo& info,
          const fs::path& png) {
  write_file_atomic(script, text);
  info.files.push_back(script.string());
  if (!opt.plot || !have_gnuplot()) return false;
  if (!draw_figure(script, png)) {
    say(opt, "evas study: gnuplot failed on " + script.string());
    return false;
  }
  info.files.push_back(png.string());
  return true;
}

void plot_all(const Options& opt, const std::vector<Figure>& figures, StudyInfo& info,
              GnuplotProcess* started) {
  std::vector<fs::path> scripts;
  for (const Figure& f : figures) {
    write_file_atomic(f.script, f.text);
    info.files.push_back(f.script.string());
    scripts.push_back(f.script);
  }
  if (!opt.plot || !have_gnuplot()) return;
  std::error_code ec;
  for (const Figure& f : figures) fs::remove(f.png, ec);  // no stale figure passes for a new one
  if (started && started->ready())
    started->draw(scripts);
  else
    run_gnuplot(scripts);
  for (const Figure& f : figures) {
    if (!fs::exists(f.png) && (!run_gnuplot(f.script) || !fs::exists(f.png))) {
      say(opt, "evas study: gnuplot failed on " + f.script.string());
      continue;
    }
    info.files.push_back(f.png.string());
  }
}

}  // namespace evas::study::detail
