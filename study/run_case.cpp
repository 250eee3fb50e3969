// One run of a study case (run_case.h).
#include "study/run_case.h"

#include <chrono>
#include <cmath>
#include <memory>

#include "dae/consistent.h"
#include "io/outputs.h"
#include "solver/system.h"
#include "study/report.h"

namespace evas::study {

SceneInfo probe_scene(const SceneSource& src) {
  Scene scene = src.parse();
  System sys(*scene.model);
  OutputSet out(scene.output, sys, scene.t_start, scene.t_end);
  if (out.times().empty())
    throw InputError(scene.path + ": output: the grid has no output time in [" +
                     gnum(scene.t_start, 6) + ", " + gnum(scene.t_end, 6) + "] s");
  SceneInfo info;
  info.name = scene.name;
  info.grid = scene.output.grid;
  info.channels = out.channels();
  info.times = out.times();
  info.integrator = scene.integrator;
  info.t_start = scene.t_start;
  info.t_end = scene.t_end;
  if (scene.output.grid == "crank-angle")
    for (std::size_t i = 0; i < info.channels.size(); ++i)
      if (info.channels[i].name == "crank_angle") info.crank_channel = static_cast<int>(i);
  // The angle is kinematic (the crank body's LOF): read from it alone, not by
  // evaluating every channel at every output time.
  if (info.crank_channel >= 0 && out.has_crank_angle())
    for (double t : info.times) info.crank.push_back(out.crank_angle(t));
  return info;
}

RunData run_case(const SceneSource& src, const IntegratorSettings& settings,
                 const std::vector<int>& channels, const RowCheck& check,
                 const std::function<bool()>& stop) {
  RunData d;
  std::unique_ptr<Integrator> integ;
  std::vector<double> rows;  // row-major, channels.size() per row
  std::chrono::steady_clock::time_point t0;
  bool timing = false;
  try {
    Scene scene = src.parse();
    System sys(*scene.model);
    OutputSet out(scene.output, sys, scene.t_start, scene.t_end);
    int crank = -1;
    if (scene.output.grid == "crank-angle")
      for (int i = 0; i < out.size(); ++i)
        if (out.channels()[static_cast<std::size_t>(i)].name == "crank_angle") crank = i;
    std::vector<double> row(static_cast<std::size_t>(out.size()));
    std::vector<double> sel(channels.size());
    auto record = [&](double t, const double* q, const double* v) {
      out.values(t, q, v, row.data());
      for (std::size_t k = 0; k < channels.size(); ++k) {
        sel[k] = row[static_cast<std::size_t>(channels[k])];
        if (!std::isfinite(sel[k]))
          throw RunError("channel '" + out.channels()[static_cast<std::size_t>(channels[k])].name +
                         "' is not finite at t = " + std::to_string(t) + " s");
      }
      d.time.push_back(t);
      if (crank >= 0) d.crank.push_back(row[static_cast<std::size_t>(crank)]);
      rows.insert(rows.end(), sel.begin(), sel.end());
      if (check) check(t, sel.data());
    };
    integ = make_integrator(settings.name);
    if (stop)
      integ->set_step_monitor([&stop](double t, double) {
        if (stop()) throw RunError("interrupted at t = " + std::to_string(t) + " s");
      });
    Vec q0, v0;
    sys.initial_state(q0, v0);
    if (sys.constraint_count() > 0) {  // a constrained scene starts consistent (evas run too)
      const dae::ConsistentState cs = dae::consistent_state(sys, scene.t_start, q0, v0);
      q0 = cs.q;
      v0 = cs.v;
    }
    start_internal_states(sys, scene.t_start, q0, v0);
    std::vector<double> times = out.times();
    t0 = std::chrono::steady_clock::now();
    timing = true;
    const double eps = 1e-12 * std::max(1.0, std::abs(scene.t_start));
    if (!times.empty() && times.front() <= scene.t_start + eps) {
      record(scene.t_start, q0.data(), v0.data());
      times.erase(times.begin());
    }
    integ->init(sys, scene.t_start, q0, v0, settings);
    integrate(*integ, sys, scene.t_start, times,
              [&](double t, const Vec& q, const Vec& v) { record(t, q.data(), v.data()); });
    d.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    d.status = "completed";
  } catch (const std::exception& e) {
    d.status = "failed";
    d.message = e.what();
    if (timing)
      d.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  if (integ) d.stats = integ->stats();
  const long nr = d.rows();
  const long nc = static_cast<long>(channels.size());
  d.y.resize(nr, nc);
  for (long r = 0; r < nr; ++r)
    for (long c = 0; c < nc; ++c) d.y(r, c) = rows[static_cast<std::size_t>(r * nc + c)];
  return d;
}

RunData run_case_repeated(const SceneSource& src, const IntegratorSettings& settings,
                          const std::vector<int>& channels, int repeats,
                          const std::function<bool()>& stop) {
  RunData best = run_case(src, settings, channels, nullptr, stop);
  for (int k = 1; k < repeats && best.status == "completed"; ++k) {
    if (stop && stop()) break;
    RunData again = run_case(src, settings, channels, nullptr, stop);
    if (again.status != "completed") return again;
    again.wall = std::min(again.wall, best.wall);
    best = std::move(again);
  }
  return best;
}

}  // namespace evas::study
