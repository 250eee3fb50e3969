// One run of a study case (run_case.h).
#include "study/run_case.h"

#include <cmath>

#include "io/outputs.h"
#include "run/period.h"
#include "run/periodic.h"
#include "run/run.h"
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
  info.warnings = scene.warnings;
  if (scene.output.grid == "crank-angle")
    for (std::size_t i = 0; i < info.channels.size(); ++i)
      if (info.channels[i].name == "crank_angle") info.crank_channel = static_cast<int>(i);
  // The angle is kinematic (the crank body's LOF): read from it alone, not by
  // evaluating every channel at every output time.
  if (info.crank_channel >= 0 && out.has_crank_angle())
    for (double t : info.times) info.crank.push_back(out.crank_angle(t));
  return info;
}

namespace {

// The chosen channels of every row, the crank angle of each row, and the
// study's check and stop request.
class CaseSink : public run::RowSink {
 public:
  CaseSink(const std::vector<int>& channels, int crank, const RowCheck& check,
           const std::function<bool()>& stop, RunData& d)
      : channels_(channels), crank_(crank), check_(check), stop_(stop), d_(d) {
    sel_.resize(channels.size());
  }
  void begin(const std::vector<Channel>&, const Integrator&) override {}
  void between_steps(double t, double) override {
    if (stop_ && stop_()) throw RunError("interrupted at t = " + std::to_string(t) + " s");
  }
  void row(double t, const double* values) override {
    for (std::size_t k = 0; k < channels_.size(); ++k) sel_[k] = values[channels_[k]];
    d_.time.push_back(t);
    if (crank_ >= 0) d_.crank.push_back(values[crank_]);
    rows_.insert(rows_.end(), sel_.begin(), sel_.end());
    if (check_) check_(t, sel_.data());
  }
  const std::vector<double>& rows() const { return rows_; }

 private:
  const std::vector<int>& channels_;
  int crank_;
  const RowCheck& check_;
  const std::function<bool()>& stop_;
  RunData& d_;
  std::vector<double> sel_, rows_;  // rows_: row-major, channels.size() per row
};

}  // namespace

const char* to_text(CaseStatus s) {
  switch (s) {
    case CaseStatus::completed:
      return "completed";
    case CaseStatus::failed:
      return "failed";
    case CaseStatus::not_run:
      break;
  }
  return "not run";
}

RunData run_case(const SceneSource& src, const IntegratorSettings& settings,
                 const std::vector<int>& channels, const RowCheck& check,
                 const std::function<bool()>& stop) {
  RunData d;
  std::vector<double> rows;
  try {
    Scene scene = src.parse();
    run::SceneRun sr(scene, scene.t_end);
    int crank = -1;
    if (scene.output.grid == "crank-angle")
      for (int i = 0; i < sr.outputs().size(); ++i)
        if (sr.outputs().channels()[static_cast<std::size_t>(i)].name == "crank_angle") crank = i;
    CaseSink sink(channels, crank, check, stop, d);
    const run::Outcome o = sr.perform(settings, sink);
    d.status = o.completed() ? CaseStatus::completed : CaseStatus::failed;
    d.message = o.message;
    d.stats = o.stats;
    d.wall = o.wall;
    rows = sink.rows();
  } catch (const std::exception& e) {
    d.status = CaseStatus::failed;
    d.message = e.what();
  }
  const long nr = d.rows();
  const long nc = static_cast<long>(channels.size());
  d.y.resize(nr, nc);
  for (long r = 0; r < nr; ++r)
    for (long c = 0; c < nc; ++c) d.y(r, c) = rows[static_cast<std::size_t>(r * nc + c)];
  return d;
}

namespace {

// Ends the search when the study asks (stop).
class StopAsked : public run::CycleObserver {
 public:
  explicit StopAsked(const std::function<bool()>& stop) : stop_(stop) {}
  void state(double, const Vec&, const Vec&) override {}
  void between_steps(double t, double) override {
    if (stop_ && stop_()) throw RunError("interrupted at t = " + std::to_string(t) + " s");
  }

 private:
  const std::function<bool()>& stop_;
};

}  // namespace

RunData run_periodic_case(const SceneSource& src, const IntegratorSettings& settings,
                          const std::vector<int>& channels, const std::string& method, double tol,
                          const std::function<bool()>& stop, const std::vector<double>& initial) {
  RunData d;
  try {
    Scene scene = src.parse();
    const run::ScenePeriod per = run::scene_period(scene, "");
    const double t0 = scene.t_start, T = per.seconds;
    run::SceneRun sr(scene, t0 + T);
    std::vector<double> samples;
    for (double t : sr.outputs().times())
      if (t < t0 + T * (1.0 - 1e-9)) samples.push_back(t);
    StopAsked watch(stop);
    Vec q0, v0;
    sr.system().initial_state(q0, v0);
    if (!initial.empty()) {
      if (initial.size() != static_cast<std::size_t>(q0.size() + v0.size()))
        throw InputError("the periodic search's initial state has " +
                         std::to_string(initial.size()) + " numbers; the scene's state has " +
                         std::to_string(q0.size() + v0.size()));
      q0 = Eigen::Map<const Vec>(initial.data(), q0.size());
      v0 = Eigen::Map<const Vec>(initial.data() + q0.size(), v0.size());
    }
    run::PeriodicOptions po;
    po.method = run::periodic_method(method);
    po.tol = tol;
    const run::PeriodicResult r =
        run::find_periodic(sr.system(), t0, T, q0, v0, settings, po, samples, &watch);
    d.stats = r.stats;
    d.wall = r.wall;
    if (!r.converged) {
      d.status = CaseStatus::failed;
      d.message = r.message;
    } else {
      // the rows of the converged cycle, from its sampled states
      OutputSet& out = sr.outputs();
      int crank = -1;
      for (int i = 0; i < out.size(); ++i)
        if (out.channels()[static_cast<std::size_t>(i)].name == "crank_angle") crank = i;
      std::vector<double> row(static_cast<std::size_t>(out.size()));
      const long nr = static_cast<long>(r.sample_t.size()), nc = static_cast<long>(channels.size());
      d.y.resize(nr, nc);
      for (long i = 0; i < nr; ++i) {
        const double t = r.sample_t[static_cast<std::size_t>(i)];
        out.values(t, r.sample_q[static_cast<std::size_t>(i)].data(),
                   r.sample_v[static_cast<std::size_t>(i)].data(), row.data());
        d.time.push_back(t);
        if (crank >= 0) d.crank.push_back(row[static_cast<std::size_t>(crank)]);
        for (long c = 0; c < nc; ++c) {
          const double y = row[static_cast<std::size_t>(channels[static_cast<std::size_t>(c)])];
          if (!std::isfinite(y))
            throw RunError(
                "channel '" +
                out.channels()[static_cast<std::size_t>(channels[static_cast<std::size_t>(c)])]
                    .name +
                "' is not finite at t = " + std::to_string(t) + " s");
          d.y(i, c) = y;
        }
      }
      d.state.assign(r.q.data(), r.q.data() + r.q.size());
      d.state.insert(d.state.end(), r.v.data(), r.v.data() + r.v.size());
      const long every = std::max(1L, nr / 36);
      for (long i = 0; i < nr; i += every) {
        const auto iu = static_cast<std::size_t>(i);
        d.cycle_t.push_back(r.sample_t[iu]);
        d.cycle_states.insert(d.cycle_states.end(), r.sample_q[iu].data(),
                              r.sample_q[iu].data() + r.sample_q[iu].size());
        d.cycle_states.insert(d.cycle_states.end(), r.sample_v[iu].data(),
                              r.sample_v[iu].data() + r.sample_v[iu].size());
      }
      d.status = CaseStatus::completed;
    }
  } catch (const std::exception& e) {
    d.status = CaseStatus::failed;
    d.message = e.what();
    d.state.clear();
    d.cycle_t.clear();
    d.cycle_states.clear();
  }
  if (d.y.rows() != d.rows()) d.y.resize(d.rows(), static_cast<long>(channels.size()));
  return d;
}

RunData run_case_repeated(const SceneSource& src, const IntegratorSettings& settings,
                          const std::vector<int>& channels, int repeats,
                          const std::function<bool()>& stop) {
  RunData best = run_case(src, settings, channels, nullptr, stop);
  for (int k = 1; k < repeats && best.status == CaseStatus::completed; ++k) {
    if (stop && stop()) break;
    RunData again = run_case(src, settings, channels, nullptr, stop);
    if (again.status != CaseStatus::completed) return again;
    again.wall = std::min(again.wall, best.wall);
    best = std::move(again);
  }
  return best;
}

}  // namespace evas::study
