// evas_bench, scaling of the engine's cost per step: against the number of
// modal coordinates (the crankshaft's and the block's elastic modes cut to a
// quarter and a half by the scene's `modes: {elastic: N}`, and doubled by
// rebuilding both bodies through the FE chain) and against the
// number of force elements (each engine mount split into m parallel mounts of
// k/m, c/m at the same markers: the same loads from more elements), with the
// exponent of a least-squares power law, and the peak memory of each run (an
// `evas run` child, as its summary.json reports it). IDA with the second-order solver, rtol
// 1e-5, atol 1e-9, the first 0.06 s (one and a half 720 deg cycles).
#pragma once

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include "study/run_case.h"
#include "study/scene_edit.h"

extern char** environ;

namespace evas::bench {

struct ScalingPoint {
  std::string label;
  int n = 0, elements = 0;
  double us_per_step = 0, wall = 0, peak_mb = 0;
  long steps = 0;
};

/// Slope of log(y) against log(x), least squares.
inline double power_exponent(const std::vector<double>& x, const std::vector<double>& y) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double m = static_cast<double>(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double lx = std::log(x[i]), ly = std::log(y[i]);
    sx += lx;
    sy += ly;
    sxx += lx * lx;
    sxy += lx * ly;
  }
  return (m * sxy - sx * sy) / (m * sxx - sx * sx);
}

/// Runs `args` (args[0] the program) as a child process; throws when it fails.
inline void run_child(std::vector<std::string> args) {
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawn(&pid, args[0].c_str(), nullptr, nullptr, argv.data(), environ) != 0)
    throw RunError("cannot start " + args[0]);
  int status = 0;
  if (waitpid(pid, &status, 0) < 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw RunError(args[0] + " " + args[1] + " " + args[2] + " failed");
}

/// Peak resident memory [MB] of `evas run SCENE` in a child process, as the
/// run reports it in summary.json (VmHWM of its own memory map: the child's
/// rusage would count the parent's pages it was forked with).
inline double run_peak_mb(const std::string& evas, const std::string& scene,
                          const std::string& out) {
  run_child({evas, "run", scene, "--out", out, "--quiet"});
  std::ifstream f(out + "/summary.json");
  std::stringstream ss;
  ss << f.rdbuf();
  const std::string text = ss.str(), key = "\"peak_memory_mb\": ";
  const auto p = text.find(key);
  if (p == std::string::npos) throw RunError(out + "/summary.json: no peak_memory_mb");
  return std::stod(text.substr(p + key.size()));
}

inline std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (std::size_t p = s.find(from); p != std::string::npos; p = s.find(from, p + to.size()))
    s.replace(p, from.size(), to);
  return s;
}

/// The folder `name` beside the folder of the scene at scene_path (absolute, with
/// a closing slash): where the engine's ../bodies/ and ../data/ paths point.
inline std::string sibling_dir(const std::string& scene_path, const std::string& name) {
  const std::filesystem::path dir = std::filesystem::absolute(scene_path).parent_path();
  return (dir / ".." / name).lexically_normal().string() + "/";
}

/// A scene's text with its ../bodies/ and ../data/ paths made absolute, so that
/// it can be written to another folder.
inline std::string with_absolute_paths(const std::string& text, const std::string& scene_path) {
  return replace_all(replace_all(text, "../bodies/", sibling_dir(scene_path, "bodies")), "../data/",
                     sibling_dir(scene_path, "data"));
}

/// The mounts block of engine.yaml with each mount split into m copies.
inline std::string split_mounts(const std::string& text, int m) {
  const auto b = text.find("# MOUNTS BEGIN"), e = text.find("# MOUNTS END");
  if (b == std::string::npos || e == std::string::npos)
    throw InputError("engine scene: no '# MOUNTS BEGIN' ... '# MOUNTS END' block");
  std::ostringstream block;
  block << "# MOUNTS BEGIN\n";
  for (int i = 1; i <= 4; ++i)
    for (int j = 0; j < m; ++j) {
      const std::string s = std::to_string(i);
      block << "  - {name: mount" << s << (j ? "_" + std::to_string(j) : std::string())
            << ", type: engine-mount, markers: [g" << s << ", m" << s << "], k_x: [" << 1.5e5 / m
            << "], k_y: [" << 1.5e5 / m << "],\n     k_z: [" << 3e5 / m << "], damping: ["
            << 1000.0 / m << ", " << 1000.0 / m << ", " << 1000.0 / m << "]}\n";
    }
  return text.substr(0, b) + block.str() + "  " + text.substr(e);
}

/// The validation body `name` (validation/bodies/NAME.yaml) rebuilt through the
/// FE chain (gmsh, CalculiX, `evas modal build`) with `elastic` elastic modes
/// and no frequency cap, into dir/NAME.h5; returns that path.
inline std::string rebuilt_body(const std::string& evas, const std::filesystem::path& bodies_dir,
                                const std::string& name, int elastic,
                                const std::filesystem::path& dir) {
  const std::filesystem::path yaml = bodies_dir / (name + ".yaml");
  std::ifstream f(yaml);
  if (!f) throw InputError(yaml.string() + ": cannot be read");
  std::stringstream ss;
  ss << f.rdbuf();
  std::string t = ss.str();
  const auto m = t.find("\nmodes: {elastic: "), e = t.find("damping_ratio:", m);
  if (m == std::string::npos || e == std::string::npos)
    throw InputError(yaml.string() + ": no 'modes: {elastic: ..., damping_ratio: ...}' line");
  t.replace(m, e - m, "\nmodes: {elastic: " + std::to_string(elastic) + ", max_frequency: 1e6, ");
  const std::string geometry = (bodies_dir / ".." / "geometry").lexically_normal().string();
  t = replace_all(t, "../geometry", geometry);
  const auto w = t.find("\nwork_dir: ");
  if (w != std::string::npos)
    t.replace(w, t.find('\n', w + 1) - w, "\nwork_dir: " + (dir / ("fe-" + name)).string());
  const std::filesystem::path edited = dir / (name + ".yaml");
  std::ofstream(edited) << t;
  run_child({evas, "modal", "build", edited.string(), "--out", dir.string()});
  return (dir / (name + ".h5")).string();
}

inline std::string scaling_table(const std::string& engine_path, const std::string& evas) {
  namespace fs = std::filesystem;
  const std::string bodies = sibling_dir(engine_path, "bodies");
  std::ifstream f(engine_path);
  if (!f) throw InputError(engine_path + ": cannot be read");
  std::stringstream ss;
  ss << f.rdbuf();
  const std::string base = ss.str();
  char tmpl[] = "/tmp/evas-bench.XXXXXX";
  if (!mkdtemp(tmpl)) throw RunError("cannot create a temporary folder");
  const fs::path tmp(tmpl);

  IntegratorSettings s;
  s.name = "ida";
  s.linear_solver = "second-order";
  s.rtol = 1e-5;
  s.atol = 1e-9;
  auto measure = [&](const std::string& label, const std::string& text) {
    // the edited scene with absolute body and data paths, end time 0.06 s
    std::string t = with_absolute_paths(text, engine_path);
    const auto pos = t.find("time: {start: 0, end: 0.24}");
    if (pos == std::string::npos)
      throw InputError(engine_path + ": no 'time: {start: 0, end: 0.24}'");
    t.replace(pos, 27, "time: {start: 0, end: 0.06}");
    const fs::path scene = tmp / (label + ".yaml");
    std::ofstream(scene) << t;
    study::SceneSource src{scene.string(), t, false};
    ScalingPoint p;
    p.label = label;
    {
      Scene sc = src.parse();
      p.elements = static_cast<int>(sc.model->elements().size());
      p.n = sc.model->size();
    }
    const study::RunData d = study::run_case_repeated(src, s, {}, 2);
    if (d.status != study::CaseStatus::completed) throw RunError(label + ": " + d.message);
    p.wall = d.wall;
    p.steps = d.stats.steps;
    p.us_per_step = d.wall / static_cast<double>(d.stats.steps) * 1e6;
    p.peak_mb = run_peak_mb(evas, scene.string(), (tmp / (label + "-out")).string());
    std::cerr << "scaling " << label << " done\n";
    return p;
  };
  auto truncated = [&](int crank, int block) {
    std::string t = replace_all(
        base, "file: ../bodies/crankshaft.h5\n",
        "file: ../bodies/crankshaft.h5\n    modes: {elastic: " + std::to_string(crank) + "}\n");
    return replace_all(
        t, "file: ../bodies/block.h5\n",
        "file: ../bodies/block.h5\n    modes: {elastic: " + std::to_string(block) + "}\n");
  };
  std::vector<ScalingPoint> modes, elements;
  {
    Scene sc = study::SceneSource{engine_path, base, false}.parse();
    int ce = 0, be = 0;
    for (const auto& b : sc.model->bodies())
      for (ModeKind k : b.data->kinds)
        if (k != ModeKind::Rigid) ++(b.name == "crank" ? ce : be);
    for (int div : {4, 2, 1})
      modes.push_back(measure("modes-" + std::to_string(div), truncated(ce / div, be / div)));
    // twice the elastic modes: both bodies rebuilt through the FE chain
    const fs::path bdir = fs::path(bodies);
    std::cerr << "scaling: rebuilding the bodies with twice the elastic modes (FE chain, ~2 min)\n";
    const std::string crank2 = rebuilt_body(evas, bdir, "crankshaft", 2 * ce, tmp);
    const std::string block2 = rebuilt_body(evas, bdir, "block", 2 * be, tmp);
    modes.push_back(
        measure("modes-x2", replace_all(replace_all(base, "../bodies/crankshaft.h5", crank2),
                                        "../bodies/block.h5", block2)));
  }
  for (int m : {1, 2, 4, 8})
    elements.push_back(measure("mounts-" + std::to_string(m), split_mounts(base, m)));
  fs::remove_all(tmp);

  std::ostringstream os;
  auto table = [&](const std::vector<ScalingPoint>& pts) {
    os << "| run | modal coordinates n | elements | steps | wall [s] | us per step | peak memory "
          "[MB] |\n|---|---:|---:|---:|---:|---:|---:|\n";
    for (const auto& p : pts)
      os << "| " << p.label << " | " << p.n << " | " << p.elements << " | " << p.steps << " | "
         << std::fixed << std::setprecision(2) << p.wall << " | " << std::setprecision(1)
         << p.us_per_step << " | " << std::setprecision(0) << p.peak_mb << " |\n";
  };
  auto section = [&](const std::vector<ScalingPoint>& pts, bool by_modes, const char* caption) {
    std::vector<double> x, y;
    for (const auto& p : pts) {
      x.push_back(by_modes ? p.n : p.elements);
      y.push_back(p.us_per_step);
    }
    os << caption << "\n\n";
    table(pts);
    os << "\nFitted: us per step ~ " << (by_modes ? "n" : "elements") << "^" << std::fixed
       << std::setprecision(2) << power_exponent(x, y) << ".\n\n";
  };
  section(modes, true,
          "Against the number of modal coordinates (elastic modes of both bodies cut to 1/4, "
          "1/2, all; the rigid modes kept; x2: both bodies rebuilt through the FE chain "
          "(gmsh, CalculiX, `evas modal build`, validation/bodies/*.yaml) with twice the "
          "elastic modes and no frequency cap, so the highest modes rise from 2.5 kHz to about "
          "4 kHz (block) and 5 kHz (crankshaft), and the steps with them):");
  section(elements, false,
          "Against the number of force elements (each mount split into m = 1, 2, 4, 8 "
          "parallel mounts):");
  return os.str();
}

}  // namespace evas::bench
