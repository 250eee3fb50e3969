// A study's runs from one state (steady_start.h).
#include "study/steady_start.h"

#include "io/initial_state.h"
#include "io/scene.h"
#include "run/period.h"
#include "study/report.h"
#include "study/run_case.h"

namespace evas::study {

StartedFrom start_from(SceneSource& src, const SteadyStart& how, const std::function<bool()>& stop,
                       std::ostream* log) {
  StartedFrom from;
  if (how.initial_file.empty() && !how.steady) return from;
  if (!(how.tol > 0.0)) throw InputError("--steady-tol must be positive");
  Scene scene = src.parse();
  const Model& model = *scene.model;
  std::vector<std::string> edits;
  long total = 0;
  for (const Body& b : model.bodies()) total += b.n();
  if (!how.initial_file.empty()) {
    apply_initial_state(*scene.model, how.initial_file);
    from.description = "the state of " + how.initial_file;
    from.state.assign(static_cast<std::size_t>(2 * total), 0.0);
    for (const Body& b : model.bodies())
      for (int i = 0; i < b.n(); ++i) {
        from.state[static_cast<std::size_t>(b.offset + i)] = b.q0[i];
        from.state[static_cast<std::size_t>(total + b.offset + i)] = b.v0[i];
      }
  }
  if (how.steady) {
    const run::ScenePeriod per = run::scene_period(scene, "");
    if (how.initial_file.empty()) {
      if (log) *log << "evas study: the periodic state (" << per.basis << ") ..." << std::endl;
      const RunData d = run_periodic_case(src, scene.integrator, {}, "projected", how.tol, stop);
      if (d.status != CaseStatus::completed)
        throw InputError("--steady: the scene's periodic state was not found: " + d.message);
      from.state = d.state;
      from.description = "the periodic state (evas periodic, projected, defect " +
                         gnum(how.tol, 3) + ", " + std::to_string(d.stats.steps) + " steps, " +
                         gnum(d.wall, 3) + " s)";
    }
    from.description += ", one period: " + per.basis;
    edits.push_back("time.end=" + gnum(scene.t_start + per.seconds, 17));
  }
  // every body's state in the text (the system's q then v, by the bodies' offsets)
  if (static_cast<long>(from.state.size()) != 2 * total)
    throw InputError("the start state has " + std::to_string(from.state.size()) +
                     " numbers; the scene's bodies have " + std::to_string(2 * total));
  const Vec q = Eigen::Map<const Vec>(from.state.data(), total);
  const Vec v = Eigen::Map<const Vec>(from.state.data() + total, total);
  for (const Body& b : model.bodies()) {
    edits.push_back(b.name + ".initial.q=" + exact_list_text(q.data() + b.offset, b.n()));
    edits.push_back(b.name + ".initial.v=" + exact_list_text(v.data() + b.offset, b.n()));
  }
  from.state_text =
      initial_state_text(model, q, v, scene.name, scene.t_start, "evas study: " + from.description);
  src = edited(src, edits, how.steady ? "--steady" : "--initial");
  return from;
}

}  // namespace evas::study
