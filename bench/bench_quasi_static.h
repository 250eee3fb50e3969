// evas_bench, quasi-static modes on the paper's engine (docs/theory.md section
// 11, issue 40): Case 1 with the elastic modes of both bodies above a
// threshold taken as quasi-static (`modes: {quasi_static_above: F}`), against
// the full (all-dynamic) model's reference (IDA, KLU, rtol 1e-9, atol 1e-12).
// Per threshold:
//  - the model's error alone: the quasi-static model run tight (IDA,
//    second-order solver, rtol 1e-8, atol 1e-11) against the full reference;
//  - the integrators at their settings of the engine table (generalized-alpha
//    at 1/6 deg and 1/2 deg per step with the increment test at rtol 3e-5;
//    IDA with the second-order solver at rtol 7e-5): wall time (minimum of 3,
//    repeats interleaved), real-time factor, steps, Jacobians and the error
//    per channel (the measure of bench_engine.h) against the full reference.
#pragma once

#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include "bench_engine.h"

namespace evas::bench {

/// The scene text with `modes: {quasi_static_above: F}` on every body that has
/// a damping_ratio line (both bodies of engine.yaml); F <= 0: unchanged.
inline std::string with_quasi_static(const std::string& text, double above) {
  if (above <= 0.0) return text;
  std::ostringstream m;
  m << "    modes: {quasi_static_above: " << above << "}\n";
  std::string out;
  std::size_t pos = 0;
  int changed = 0;
  while (true) {
    const std::size_t k = text.find("\n    damping_ratio:", pos);
    if (k == std::string::npos) break;
    out += text.substr(pos, k + 1 - pos) + m.str();
    pos = k + 1;
    ++changed;
  }
  out += text.substr(pos);
  if (changed != 2) throw InputError("bench: expected two bodies with a damping_ratio line");
  return out;
}

inline std::string quasi_static_table(const std::string& path) {
  const EngineCase c = engine_cases(path).front();  // Case 1
  const study::SceneInfo info = study::probe_scene(c.src);
  const std::vector<int> channels = bearing_channels(info);
  const study::RunData ref = reference_run(c.src, info, channels, "Case 1");
  const double span = info.t_end - info.t_start;
  const double sixth = M_PI / 180.0 / 314.159 / 6.0;
  struct Run {
    std::string label, name;
    double rtol, atol, step;
  };
  const std::vector<Run> runs = {
      {"ida, rtol 1e-8 (the model's error)", "ida", 1e-8, 1e-11, 0.0},
      {"generalized-alpha, 1/6 deg", "generalized-alpha", 3e-5, 1e-9, sixth},
      {"generalized-alpha, 1/2 deg", "generalized-alpha", 3e-5, 1e-9, 3.0 * sixth},
      {"ida, rtol 7e-5", "ida", 7e-5, 7e-9, 0.0}};
  const std::vector<double> thresholds = {0.0, 2400.0, 2000.0, 1500.0, 1000.0};
  std::ostringstream os;
  os << "| quasi-static above [Hz] | quasi-static modes | run | real-time factor | wall [s] | "
        "steps "
        "| Jacobians | error per channel |\n|---:|---:|---|---:|---:|---:|---:|---:|\n";
  for (double above : thresholds) {
    study::SceneSource src = c.src;
    src.text = with_quasi_static(c.src.text, above);
    int count = 0;
    {
      Scene scene = src.parse();
      for (const Body& b : scene.model->bodies()) count += static_cast<int>(b.quasi_static.size());
    }
    std::vector<study::RunData> best(runs.size());
    for (int rep = 0; rep < 3; ++rep)
      for (std::size_t k = 0; k < runs.size(); ++k) {
        if (rep > 0 && k == 0) continue;  // (the tight run once: its error is the point)
        const Run& r = runs[k];
        IntegratorSettings t = info.integrator;
        t.name = r.name;
        t.linear_solver = "second-order";
        t.rtol = r.rtol;
        t.atol = r.atol;
        if (r.step > 0.0) t.step = r.step;
        set_integrator_setting(t, "step_control", "substep");
        study::RunData d = study::run_case(src, t, channels);
        if (rep > 0) d.wall = std::min(d.wall, best[k].wall);
        best[k] = std::move(d);
      }
    for (std::size_t k = 0; k < runs.size(); ++k) {
      const study::RunData& d = best[k];
      os << "| " << (above > 0.0 ? std::to_string(static_cast<int>(above)) : "- (all dynamic)")
         << " | " << count << " | " << runs[k].label << " | ";
      if (d.status != study::CaseStatus::completed) {
        os << "failed: " << d.message.substr(0, 120) << " | | | | |\n";
        continue;
      }
      os << std::fixed << std::setprecision(2) << d.wall / span << " | " << d.wall << " | "
         << d.stats.steps << " | " << d.stats.jacobian_evals << " | " << std::scientific
         << std::setprecision(1) << channel_error(d, ref) << " |\n";
    }
    std::cerr << "quasi-static above " << above << " done\n";
  }
  return os.str();
}

}  // namespace evas::bench
