// One run for every front end (run.h).
#include "run/run.h"

#include <chrono>
#include <cmath>
#include <exception>
#include <memory>

#include "dae/consistent.h"
#include "run/stability_note.h"
#include "run/stop.h"
#include "solver/quasi_static.h"

namespace evas::run {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// A non-finite output ends the run naming the channel and the state it came from.
void check_finite(const OutputSet& outputs, const std::vector<double>& row, double t,
                  const System& sys, const Vec& q, const Vec& v) {
  for (std::size_t c = 0; c < row.size(); ++c)
    if (!std::isfinite(row[c]))
      throw RunError("channel '" + outputs.channels()[c].name + "' is " +
                     (std::isnan(row[c]) ? "NaN" : "infinite") + " at " +
                     sys.describe_state(t, q.data(), v.data()));
}

// The failure of a run as its outcome: the message, and the exit code (128 + N
// for a signal, 2 otherwise).
void record_failure(Outcome& out, std::exception_ptr error) {
  out.status = Status::failed;
  out.exit_code = 2;
  try {
    std::rethrow_exception(error);
  } catch (const Stopped& e) {
    out.message = e.what();
    out.exit_code = e.exit_code();
  } catch (const std::exception& e) {
    out.message = e.what();
  }
}

// The start of every run: the initial state, consistent with the constraints
// when `project` (dae/consistent.h), the element internal states, the
// integrator prepared; the multipliers of the start when it has them.
struct Start {
  Vec q, v, lambda;
  bool has_multipliers = false;
};

void start(Problem& p, Integrator& integ, const IntegratorSettings& s, double t0, bool project,
           Start& st) {
  p.initial_state(st.q, st.v);
  if (project && p.constraint_count() > 0) {
    const dae::ConsistentState cs = dae::consistent_state(p, t0, st.q, st.v);
    st.q = cs.q;
    st.v = cs.v;
    st.lambda = cs.lambda;
  }
  start_internal_states(p, t0, st.q, st.v);
  // the quasi-static modes at their static deflection (also done by the
  // integrators that take them; here so that the first output row has it)
  require_quasi_static_support(integ, p);
  settle_quasi_static(p, t0, st.q, st.v);
  integ.init(p, t0, st.q, st.v, s);
  if (Vec lam; p.constraint_count() > 0 && integ.multipliers(lam)) {
    st.lambda = lam;
    st.has_multipliers = true;
  }
}

}  // namespace

std::string Outcome::status_text() const {
  return status == Status::completed ? "completed" : "failed: " + message;
}

void MemorySink::begin(const std::vector<Channel>& channels, const Integrator&) {
  channels_.clear();
  if (columns_.empty()) {
    channels_ = channels;
    for (std::size_t c = 0; c < channels.size(); ++c) columns_.push_back(static_cast<int>(c));
  } else {
    for (int c : columns_) channels_.push_back(channels.at(static_cast<std::size_t>(c)));
  }
}

void MemorySink::row(double t, const double* values) {
  times_.push_back(t);
  for (int c : columns_) values_.push_back(values[c]);
}

SceneRun::SceneRun(const Scene& scene, double t_end)
    : t_start_(scene.t_start),
      t_end_(t_end),
      sys_(std::make_unique<System>(*scene.model)),
      out_(std::make_unique<OutputSet>(scene.output, *sys_, t_start_, t_end_)) {
  if (out_->times().empty())
    throw InputError(scene.path + ": output: the grid has no output time in [" +
                     std::to_string(t_start_) + ", " + std::to_string(t_end_) + "] s" +
                     (out_->has_crank_angle()
                          ? " (on the crank-angle grid: the crank turns from " +
                                format_number(out_->crank_angle(t_start_)) + " to " +
                                format_number(out_->crank_angle(t_end_)) + " deg in that time)"
                          : std::string()));
}

Outcome SceneRun::perform(const IntegratorSettings& settings, RowSink& sink) {
  const std::unique_ptr<Integrator> integ = make_integrator(settings.name);
  return perform(*integ, settings, sink);
}

Outcome SceneRun::perform(Integrator& integ, const IntegratorSettings& settings, RowSink& sink) {
  Outcome out;
  System& sys = *sys_;
  OutputSet& outputs = *out_;
  const auto t0 = Clock::now();
  bool started = false;
  // the last state the run reached (its start, then each output): a failure
  // of a conditionally stable method is judged there (run/stability_note.h)
  double t_last = t_start_;
  Vec q_last, v_last;
  try {
    // The start; a failure here ends the run below, after the sink has begun
    // (a results file is written as for any failure) and, when the initial
    // state was made, its row.
    Start st;
    std::exception_ptr start_error;
    try {
      start(sys, integ, settings, t_start_, true, st);
      if (st.has_multipliers) outputs.add_multiplier_channels();
    } catch (...) {
      start_error = std::current_exception();
    }
    sink.begin(outputs.channels(), integ);
    started = true;
    integ.set_step_monitor([&sink](double t, double h) { sink.between_steps(t, h); });
    if (start_error && st.q.size() != sys.size()) std::rethrow_exception(start_error);
    q_last = st.q;
    v_last = st.v;
    sink.between_steps(t_start_, 0.0);
    std::vector<double> row(static_cast<std::size_t>(outputs.size()));
    std::vector<double> times = outputs.times();
    const double eps = 1e-12 * std::max(1.0, std::abs(t_start_));
    if (times.front() <= t_start_ + eps) {
      outputs.values(t_start_, st.q.data(), st.v.data(), row.data(), st.lambda.data());
      check_finite(outputs, row, t_start_, sys, st.q, st.v);
      sink.row(t_start_, row.data());
      times.erase(times.begin());
    }
    if (start_error) std::rethrow_exception(start_error);
    integrate(integ, sys, t_start_, times, [&](double t, const Vec& q, const Vec& v) {
      sink.between_steps(t, integ.stats().last_step);
      Vec lam;
      const bool with_lam = outputs.has_multiplier_channels() && integ.multipliers(lam);
      try {
        outputs.values(t, q.data(), v.data(), row.data(), with_lam ? lam.data() : nullptr);
      } catch (const RangeError& e) {
        // the integrator took the steps, but the state at this output (a step's
        // or the interpolant between two) is outside an element's range
        throw RunError(std::string("the output channels at t = ") + format_number(t) +
                       " s cannot be evaluated: " + e.what() +
                       "; state: " + sys.describe_state(t, q.data(), v.data()) +
                       ". The steps around this time passed the integrator's own tests; with a "
                       "fixed step (generalized-alpha, linear-acceleration) a smaller 'step' or "
                       "step_control=adaptive follows the motion more closely");
      }
      check_finite(outputs, row, t, sys, q, v);
      sink.row(t, row.data());
      t_last = t;
      q_last = q;
      v_last = v;
    });
  } catch (const EndRun&) {
    // the sink ended the run early, as completed (e.g. --until-settled)
  } catch (...) {
    record_failure(out, std::current_exception());
    if (q_last.size() == sys.size() && out.exit_code == 2) {
      try {
        const std::string why = stability_limit_note(sys, settings, t_last, q_last, v_last);
        if (!why.empty()) out.message += ". Instability: " + why;
      } catch (...) {  // (the failure's own message stands)
      }
    }
  }
  integ.set_step_monitor(nullptr);
  out.stats = integ.stats();
  if (started) out.wall = seconds_since(t0);
  return out;
}

EndState run_to_end(Problem& p, const IntegratorSettings& settings, double t0, double t_end) {
  EndState end;
  const std::unique_ptr<Integrator> integ = make_integrator(settings.name);
  const auto clock0 = Clock::now();
  try {
    // The library's problems start from their published consistent values:
    // not projected, which would move them by round-off.
    Start st;
    start(p, *integ, settings, t0, false, st);
    end.q = st.q;
    end.v = st.v;
    integ->advance(t_end, true, end.q, end.v);
    if (!integ->multipliers(end.lambda)) end.lambda.resize(0);
  } catch (const InputError&) {
    throw;
  } catch (...) {
    record_failure(end.outcome, std::current_exception());
  }
  end.outcome.wall = seconds_since(clock0);
  end.outcome.stats = integ->stats();
  return end;
}

}  // namespace evas::run
