// `evas study` drivers (study.h): work-precision, convergence and stability.
#include "study/study.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include "integrators/settings.h"
#include "io/hdf5_util.h"
#include "io/results.h"
#include "study/report.h"

namespace evas::study {

namespace fs = std::filesystem;

namespace {

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

const double kNaN = std::numeric_limits<double>::quiet_NaN();

bool stopped(const Options& o) { return o.stop && o.stop(); }

void say(const Options& o, const std::string& line) {
  if (o.log) *o.log << line << "\n" << std::flush;
}

// Everything a study shares once the scene is read.
struct Setup {
  SceneSource src;
  SceneInfo info;
  std::vector<int> channels;
  std::vector<std::string> names, units;
  Window window;
  bool window_default = false;
  Norm norm = Norm::Max;
  fs::path out;
};

Setup prepare(const Options& opt) {
  if (opt.repeats < 1) throw InputError("--repeats must be >= 1");
  Setup s;
  s.src = load_scene_source(opt.scene, opt.params, opt.t_end);
  s.info = probe_scene(s.src);
  s.channels = select_channels(s.info.channels, opt.channels);
  for (int c : s.channels) {
    s.names.push_back(s.info.channels[static_cast<std::size_t>(c)].name);
    s.units.push_back(s.info.channels[static_cast<std::size_t>(c)].unit);
  }
  s.norm = parse_norm(opt.norm);
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
  fs::create_directories(s.out, ec);
  if (ec)
    throw InputError(s.out.string() + ": cannot create the output directory: " + ec.message());
  return s;
}

StudyInfo make_info(const Setup& s) {
  StudyInfo i;
  i.scene_name = s.info.name;
  i.scene_path = s.src.path;
  i.scene_text = s.src.text;
  i.grid = s.info.grid;
  i.channels = s.names;
  i.window = s.window.text();
  i.norm = norm_text(s.norm);
  i.error_definition = error_definition(s.norm, s.window);
  i.out_dir = s.out.string();
  return i;
}

bool same_time(double a, double b, double scale) {
  return std::abs(a - b) <= 1e-9 * std::max({std::abs(a), std::abs(b), scale});
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
  RunData d = run_case(src, c.settings, channels, nullptr, opt.stop);
  if (d.status != "completed")
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
  say(opt, "evas study: reference " + c.label + ": " + std::to_string(d.stats.steps) + " steps, " +
               gnum(d.wall, 3) + " s");
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

Reference make_reference(const Options& opt, const Setup& s) {
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

CaseResult evaluate(const Case& c, const RunData& d, const Reference& ref,
                    const std::vector<int>& rows, Norm norm, double scale) {
  CaseResult r;
  r.c = c;
  r.status = d.status;
  r.message = d.message;
  r.wall = d.wall;
  r.rows = d.rows();
  r.stats = d.stats;
  if (d.status != "completed") return r;
  bool same = d.time.size() == ref.time.size();
  for (std::size_t i = 0; same && i < d.time.size(); ++i)
    same = same_time(d.time[i], ref.time[i], scale);
  if (!same) {
    r.status = "failed";
    r.message = "the output times differ from the reference's";
    return r;
  }
  r.error = relative_error(d.y, ref.y, rows, norm);
  return r;
}

std::vector<Case> expand_all(const std::vector<CaseInput>& specs, const IntegratorSettings& base) {
  std::vector<Case> cases;
  for (const auto& in : specs)
    for (auto& c : expand_case(in.spec, base, in.where)) cases.push_back(std::move(c));
  return cases;
}

std::string case_line(std::size_t k, std::size_t n, const CaseResult& r) {
  std::ostringstream os;
  os << "evas study: [" << k << "/" << n << "] " << r.c.label << ": ";
  if (r.status == "completed")
    os << "error " << sci(r.error, 3) << ", " << gnum(r.wall, 3) << " s, " << r.stats.steps
       << " steps, " << r.stats.residual_evals << " residuals";
  else
    os << r.status << (r.message.empty() ? "" : ": " + r.message);
  return os.str();
}

// --- tables ------------------------------------------------------------------

struct Column {
  enum class Kind { Text, Real, Integer };
  std::string csv;  // CSV header
  std::string h5;   // dataset path below /cases
  Kind kind = Kind::Text;
  std::vector<std::string> text;
  std::vector<double> num;
};

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
  text("status", "status", [](const CaseResult& r) { return r.status; });
  text("message", "message", [](const CaseResult& r) { return r.message; });
  num("error", "error", Column::Kind::Real, [](const CaseResult& r) { return r.error; });
  num("wall", "wall", Column::Kind::Real, [](const CaseResult& r) { return r.wall; });
  num("rows", "rows", Column::Kind::Integer, [](const CaseResult& r) { return double(r.rows); });
  for (const auto& f : stat_fields()) {
    const std::string name = keys.count(f.name) ? std::string(f.name) + "_taken" : f.name;
    const auto get = f.get;
    num(name, std::string("stats/") + f.name,
        f.integer ? Column::Kind::Integer : Column::Kind::Real,
        [get](const CaseResult& r) { return r.status == "not run" ? kNaN : get(r.stats); });
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

std::string join(const std::vector<std::string>& v, const std::string& sep = ", ") {
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
  md << "- " << info.error_definition << "\n";
  md << "- wall: init + integrate [s], minimum over " << opt.repeats << " run"
     << (opt.repeats > 1 ? "s" : "") << "\n";
  if (info.interrupted) md << "- **interrupted**: the cases marked `not run` were not run\n";
  md << "\n";
  return md.str();
}

std::string status_cell(const CaseResult& r) {
  if (r.status == "failed") return "failed: " + md_cell(r.message, 70);
  return r.status;
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
  h5::write_attribute(f, "repeats", static_cast<long long>(opt.repeats));
  h5::write_attribute(f, "status", info.interrupted ? "interrupted" : "completed");
}

// --- gnuplot ------------------------------------------------------------------

// Family of a case for the plots: its label without the precision knobs, so
// one curve joins the cases that differ only in tolerance or step.
std::string family_of(const Case& c) {
  static const std::set<std::string> knobs = {"rtol",        "atol",     "step",
                                              "balance_tol", "max_step", "min_step"};
  return strip_keys(settings_label(c.settings), knobs);
}

bool plot(const Options& opt, const fs::path& script, const std::string& text, StudyInfo& info,
          const fs::path& png) {
  write_file_atomic(script, text);
  info.files.push_back(script.string());
  if (!opt.plot || !have_gnuplot()) return false;
  std::error_code ec;
  fs::remove(png, ec);  // a stale figure must not pass for a new one
  if (!run_gnuplot(script) || !fs::exists(png)) {
    say(opt, "evas study: gnuplot failed on " + script.string());
    return false;
  }
  info.files.push_back(png.string());
  return true;
}

std::string gp_terminal(const fs::path& png, int w, int h) {
  std::ostringstream gp;
  gp << "set terminal pngcairo noenhanced size " << w << "," << h << "\n"
     << "set output " << gp_quote(png.filename().string()) << "\n";
  return gp.str();
}

void plot_work_precision(const Options& opt, const WorkPrecisionResult& res, StudyInfo& info) {
  std::map<std::string, std::vector<const CaseResult*>> fam;
  std::vector<std::string> order;
  for (const auto& r : res.cases) {
    if (r.status != "completed" || !(r.error > 0.0) || !std::isfinite(r.error)) continue;
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
    const bool ran = r.status != "not run";
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
  const double scale = std::abs(s.info.t_end - s.info.t_start);
  write_work_precision(opt, res, rows);
  for (std::size_t k = 0; k < cases.size(); ++k) {
    if (stopped(opt)) {
      res.info.interrupted = true;
      break;
    }
    const RunData d =
        run_case_repeated(s.src, cases[k].settings, s.channels, opt.repeats, opt.stop);
    if (stopped(opt)) break;  // cut short by the interrupt: left "not run"
    res.cases[k] = evaluate(cases[k], d, res.reference, rows, s.norm, scale);
    say(opt, case_line(k + 1, cases.size(), res.cases[k]));
    write_work_precision(opt, res, rows);
  }
  if (stopped(opt)) res.info.interrupted = true;
  write_work_precision(opt, res, rows);
  plot_work_precision(opt, res, res.info);
  return res;
}

// --- convergence ----------------------------------------------------------------

namespace {

void write_convergence(const Options& opt, ConvergenceResult& res, bool final) {
  StudyInfo& info = res.info;
  const fs::path dir = info.out_dir;
  info.files.clear();
  // CSV: the swept value and orders in front of the full case table
  std::vector<Column> cols = case_columns(res.cases);
  Column x{res.key, res.key, Column::Kind::Real, {}, res.x};
  Column po{"order", "order", Column::Kind::Real, {}, res.pair_order};
  cols.insert(cols.begin() + 1, po);
  cols.insert(cols.begin() + 1, x);
  write_file_atomic(dir / "convergence.csv", columns_csv(cols, res.cases.size()));
  info.files.push_back((dir / "convergence.csv").string());

  std::ostringstream md;
  md << md_header("Convergence study", info, opt, res.reference);
  md << "| case | " << res.key << " | status | error | order | wall [s] | steps | residuals |\n"
     << "|---|---:|---|---:|---:|---:|---:|---:|\n";
  for (std::size_t i = 0; i < res.cases.size(); ++i) {
    const auto& r = res.cases[i];
    const bool ran = r.status != "not run";
    md << "| " << md_cell(r.c.label) << " | " << gnum(res.x[i], 6) << " | " << status_cell(r)
       << " | " << sci(r.error, 3) << " | " << gnum(res.pair_order[i], 3) << " | "
       << gnum(r.wall, 4) << " | " << (ran ? std::to_string(r.stats.steps) : "") << " | "
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
  std::ostringstream data;
  double sx = 0, sy = 0;
  int n = 0;
  for (std::size_t i = 0; i < res.cases.size(); ++i) {
    const double e = res.cases[i].error;
    if (res.cases[i].status != "completed" || !(e > 0) || !std::isfinite(e)) continue;
    data << gnum(res.x[i], 12) << " " << gnum(e, 12) << "\n";
    sx += std::log(res.x[i]);
    sy += std::log(e);
    ++n;
  }
  if (n == 0) return;
  const fs::path png = dir / "convergence.png";
  std::ostringstream gp;
  gp << "# convergence figure of " << info.scene_name << " (evas study)\n"
     << gp_terminal(png, 900, 600) << "$D << EOD\n"
     << data.str() << "EOD\n"
     << "set logscale xy\nset format y '1e%L'\nset grid\nset key top left\n"
     << "set xlabel " << gp_quote(res.key) << "\n"
     << "set ylabel 'error (relative to each channel amplitude)'\n"
     << "set title " << gp_quote("convergence: " + res.family + " on " + info.scene_name) << "\n";
  if (!std::isnan(res.slope)) {
    const double b = sy / n - res.slope * sx / n;  // the fit passes through the centroid
    gp << "f(x) = exp(" << gnum(b, 12) << ") * x**(" << gnum(res.slope, 12) << ")\n"
       << "plot $D using 1:2 with linespoints pt 7 title 'error', f(x) with lines dt 2 title "
       << gp_quote("slope " + gnum(res.slope, 3)) << "\n";
  } else {
    gp << "plot $D using 1:2 with linespoints pt 7 title 'error'\n";
  }
  plot(opt, dir / "convergence.gp", gp.str(), info, png);
}

}  // namespace

ConvergenceResult convergence(const Options& opt, const CaseInput& spec) {
  Setup s = prepare(opt);
  std::vector<Case> cases = expand_case(spec.spec, s.info.integrator, spec.where);
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
  const double scale = std::abs(s.info.t_end - s.info.t_start);
  auto update = [&] {
    std::vector<double> e;
    int last = -1;
    for (std::size_t i = 0; i < res.cases.size(); ++i) {
      const double err = res.cases[i].status == "completed" ? res.cases[i].error : kNaN;
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
  write_convergence(opt, res, false);
  for (std::size_t k = 0; k < cases.size(); ++k) {
    if (stopped(opt)) {
      res.info.interrupted = true;
      break;
    }
    const RunData d =
        run_case_repeated(s.src, cases[k].settings, s.channels, opt.repeats, opt.stop);
    if (stopped(opt)) break;  // cut short by the interrupt: left "not run"
    res.cases[k] = evaluate(cases[k], d, res.reference, rows, s.norm, scale);
    say(opt, case_line(k + 1, cases.size(), res.cases[k]));
    update();
    write_convergence(opt, res, false);
  }
  if (stopped(opt)) res.info.interrupted = true;
  update();
  write_convergence(opt, res, true);
  return res;
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
    csv << csv_field(p.value) << "," << csv_field(p.status) << "," << gnum(p.h_stable, 9) << ","
        << gnum(p.h_unstable, 9) << "," << p.runs << "," << gnum(p.reference_max, 9) << ","
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
    md << "| " << md_cell(p.value) << " | " << p.status << " | " << gnum(p.h_stable, 6) << " | "
       << gnum(p.h_unstable, 6) << " | " << p.runs << " | " << md_cell(p.message, 90) << " |\n";
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
      p.status = "reference failed";
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
      const bool ok = d.status == "completed";
      why = ok ? "" : d.message;
      say(opt, "evas study: " + tag + "h = " + gnum(h, 6) +
                   " s: " + (ok ? std::string("stable") : "unstable: " + d.message));
      return ok;
    };
    if (trial(so.h_max)) {
      p.status = "stable up to HMAX";
      p.h_stable = so.h_max;
    } else {
      p.h_unstable = so.h_max;
      p.message = why;
      if (stopped(opt)) {
        p.status = "interrupted";
      } else if (!trial(so.h_min)) {
        p.status = "unstable at HMIN";
        p.h_unstable = so.h_min;
        p.message = why;
      } else {
        p.h_stable = so.h_min;
        p.status = "bracketed";
        for (int i = 0; i < so.bisections; ++i) {
          if (stopped(opt)) {
            p.status = "interrupted";
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
    say(opt, "evas study: " + tag + p.status + ", largest stable step " + gnum(p.h_stable, 6) +
                 " s" +
                 (std::isnan(p.h_unstable) ? "" : ", unstable at " + gnum(p.h_unstable, 6) + " s"));
    write_stability(opt, res, so, false);
  }
  if (stopped(opt)) res.info.interrupted = true;
  write_stability(opt, res, so, true);
  return res;
}

}  // namespace evas::study
