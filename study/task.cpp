// A study's unit of work (task.h): running it and its exact byte forms.
#include "study/task.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <type_traits>

#include "integrators/settings.h"
#include "study/case_grid.h"
#include "study/report.h"

namespace evas::study {

namespace {

// Appends values to a byte string; Reader takes them back in the same order.
class Writer {
 public:
  template <class T>
  void raw(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    out_.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  void text(const std::string& s) {
    raw<std::uint64_t>(s.size());
    out_ += s;
  }
  void reals(const double* p, std::size_t n) {
    raw<std::uint64_t>(n);
    out_.append(reinterpret_cast<const char*>(p), n * sizeof(double));
  }
  std::string take() { return std::move(out_); }

 private:
  std::string out_;
};

class Reader {
 public:
  explicit Reader(const std::string& in) : in_(in) {}
  template <class T>
  T raw() {
    T v;
    need(sizeof v);
    std::memcpy(&v, in_.data() + pos_, sizeof v);
    pos_ += sizeof v;
    return v;
  }
  std::string text() {
    const auto n = static_cast<std::size_t>(raw<std::uint64_t>());
    need(n);
    std::string s = in_.substr(pos_, n);
    pos_ += n;
    return s;
  }
  std::vector<double> reals() {
    const auto n = static_cast<std::size_t>(raw<std::uint64_t>());
    if (n > (in_.size() - pos_) / sizeof(double)) fail();
    std::vector<double> v(n);
    if (n) std::memcpy(v.data(), in_.data() + pos_, n * sizeof(double));
    pos_ += n * sizeof(double);
    return v;
  }
  void finish() const {
    if (pos_ != in_.size()) fail();
  }
  bool at_end() const { return pos_ == in_.size(); }

 private:
  void need(std::size_t n) const {
    if (n > in_.size() - pos_) fail();
  }
  [[noreturn]] static void fail() { throw std::runtime_error("malformed task bytes"); }
  const std::string& in_;
  std::size_t pos_ = 0;
};

constexpr std::uint32_t kTaskTag = 0x7461736b;  // "task"
constexpr std::uint32_t kRunTag = 0x72756e64;   // "rund"

}  // namespace

RunData run_task(const TaskSpec& task, const std::function<bool()>& stop) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  bool timed_out = false;
  auto ask = [&] {
    if (stop && stop()) return true;
    if (task.max_wall > 0.0 &&
        std::chrono::duration<double>(Clock::now() - start).count() > task.max_wall)
      timed_out = true;
    return timed_out;
  };
  RunData d;
  if (!task.periodic.empty()) {
    d = run_periodic_case(task.src, task.settings, task.channels, task.periodic, task.periodic_tol,
                          ask, task.initial);
  } else if (task.limit.empty()) {
    d = run_case_repeated(task.src, task.settings, task.channels, task.repeats, ask);
  } else {
    // A fixed step longer than two output intervals: the outputs between the
    // step points are interpolated, and an interpolant over a long step of a
    // stiff mode swings far beyond the solution at the step points (a bounded,
    // decaying solution can show ten times its amplitude there). Stability is
    // then judged at the step points: only the output row nearest each step
    // point (within half an output interval) is held to the bound; the largest
    // excursion elsewhere is reported beside the verdict.
    const double h = takes_fixed_steps(task.settings) ? task.settings.step : 0.0;
    int row = 0;
    double t0 = 0.0, dt = 0.0, excursion = 0.0;
    std::string excursion_at;
    const RowCheck check = [&](double t, const double* y) {
      const int r = row++;
      if (r == 0) t0 = t;
      if (r == 1) dt = t - t0;
      if (r == 0 && t <= task.limit_after) return;
      bool at_step = true;
      if (h > 2.0 * dt && dt > 0.0) {
        const double k = std::round((t - t0) / h);
        at_step = std::abs(t - t0 - k * h) <= 0.5 * dt * (1.0 + 1e-9);
      }
      for (std::size_t c = 0; c < task.limit.size(); ++c) {
        const double b = task.limit[c];
        if (!(b > 0)) continue;
        if (!std::isfinite(y[c]) || (at_step && std::abs(y[c]) > b))
          throw RunError("|" + task.limit_names.at(c) + "| = " + sci(std::abs(y[c]), 3) + " > " +
                         gnum(task.growth, 4) + " x reference max " + sci(b / task.growth, 3) +
                         " at t = " + gnum(t, 6) + " s" + (h > 2.0 * dt ? " (a step point)" : ""));
        const double ratio = std::abs(y[c]) * task.growth / b;  // x the reference max
        if (!at_step && ratio > excursion) {
          excursion = ratio;
          excursion_at = task.limit_names.at(c) + " at t = " + gnum(t, 6) + " s";
        }
      }
    };
    d = run_case(task.src, task.settings, task.channels, check, ask);
    if (d.status == CaseStatus::completed && excursion > task.growth)
      d.message = "between step points the interpolated outputs reach " + gnum(excursion, 3) +
                  " x the reference max (" + excursion_at + "); judged at the step points";
  }
  if (timed_out && d.status == CaseStatus::failed)
    d.message = "timed out: wall time above --max-wall " + gnum(task.max_wall, 6) + " s (" +
                d.message + ")";
  return d;
}

std::string pack_task(const TaskSpec& t) {
  Writer w;
  w.raw(kTaskTag);
  w.text(t.src.path);
  w.text(t.src.text);
  w.raw<std::uint8_t>(t.src.edited);
  const auto& keys = integrator_settings();
  // a plug-in's own settings follow the built-in ones (none: the bytes as before)
  w.raw<std::uint64_t>(keys.size() + t.settings.own.size());
  for (const auto& k : keys) {
    w.text(k.key);
    w.text(get_integrator_setting(t.settings, k.key));
  }
  for (const auto& [key, value] : t.settings.own) {
    w.text(key);
    w.text(number_text(value));
  }
  w.raw<std::uint64_t>(t.channels.size());
  for (int c : t.channels) w.raw<std::int32_t>(c);
  w.raw<std::int32_t>(t.repeats);
  w.raw(t.max_wall);
  w.reals(t.limit.data(), t.limit.size());
  w.raw<std::uint64_t>(t.limit_names.size());
  for (const auto& n : t.limit_names) w.text(n);
  w.raw(t.limit_after);
  w.raw(t.growth);
  // a periodic task only: a transient task's bytes (and fingerprint) are
  // those it had before periodic tasks existed
  if (!t.periodic.empty()) {
    w.text(t.periodic);
    w.raw(t.periodic_tol);
    w.reals(t.initial.data(), t.initial.size());
  }
  return w.take();
}

TaskSpec unpack_task(const std::string& bytes) {
  Reader r(bytes);
  if (r.raw<std::uint32_t>() != kTaskTag) throw std::runtime_error("not a task");
  TaskSpec t;
  t.src.path = r.text();
  t.src.text = r.text();
  t.src.edited = r.raw<std::uint8_t>() != 0;
  const auto nkeys = r.raw<std::uint64_t>();
  for (std::uint64_t i = 0; i < nkeys; ++i) {
    const std::string key = r.text();
    set_integrator_setting(t.settings, key, r.text());
  }
  const auto nch = r.raw<std::uint64_t>();
  for (std::uint64_t i = 0; i < nch; ++i) t.channels.push_back(r.raw<std::int32_t>());
  t.repeats = r.raw<std::int32_t>();
  t.max_wall = r.raw<double>();
  t.limit = r.reals();
  const auto nnames = r.raw<std::uint64_t>();
  for (std::uint64_t i = 0; i < nnames; ++i) t.limit_names.push_back(r.text());
  if (t.limit_names.size() != t.limit.size()) throw std::runtime_error("malformed task limits");
  t.limit_after = r.raw<double>();
  t.growth = r.raw<double>();
  if (!r.at_end()) {
    t.periodic = r.text();
    t.periodic_tol = r.raw<double>();
    t.initial = r.reals();
  }
  r.finish();
  return t;
}

std::string pack_run(const RunData& d) {
  Writer w;
  w.raw(kRunTag);
  w.raw<std::int32_t>(static_cast<std::int32_t>(d.status));
  w.text(d.message);
  w.reals(d.time.data(), d.time.size());
  w.reals(d.crank.data(), d.crank.size());
  w.raw<std::int64_t>(d.y.rows());
  w.raw<std::int64_t>(d.y.cols());
  w.reals(d.y.data(), static_cast<std::size_t>(d.y.size()));
  w.text(stats_to_bytes(d.stats));
  w.raw(d.wall);
  // a periodic cycle's start state only: a transient run's bytes are those
  // it had before
  if (!d.state.empty()) {
    w.reals(d.state.data(), d.state.size());
    w.reals(d.cycle_t.data(), d.cycle_t.size());
    w.reals(d.cycle_states.data(), d.cycle_states.size());
  }
  return w.take();
}

RunData unpack_run(const std::string& bytes) {
  Reader r(bytes);
  if (r.raw<std::uint32_t>() != kRunTag) throw std::runtime_error("not a run result");
  RunData d;
  const auto status = r.raw<std::int32_t>();
  if (status < 0 || status > 2) throw std::runtime_error("malformed run status");
  d.status = static_cast<CaseStatus>(status);
  d.message = r.text();
  d.time = r.reals();
  d.crank = r.reals();
  const auto rows = r.raw<std::int64_t>(), cols = r.raw<std::int64_t>();
  const std::vector<double> y = r.reals();
  if (rows < 0 || cols < 0 || static_cast<std::size_t>(rows * cols) != y.size())
    throw std::runtime_error("malformed run values");
  d.y = Eigen::Map<const Mat>(y.data(), rows, cols);
  d.stats = stats_from_bytes(r.text());
  d.wall = r.raw<double>();
  if (!r.at_end()) {
    d.state = r.reals();
    d.cycle_t = r.reals();
    d.cycle_states = r.reals();
    if (d.cycle_t.empty() ? !d.cycle_states.empty() : d.cycle_states.size() % d.cycle_t.size() != 0)
      throw std::runtime_error("malformed cycle states");
  }
  r.finish();
  return d;
}

std::string task_fingerprint(const TaskSpec& t) {
  TaskSpec u = t;
  u.max_wall = 0.0;
  u.initial.clear();
  std::uint64_t h = 1469598103934665603ull;  // FNV-1a, 64 bits
  for (unsigned char c : pack_task(u)) {
    h ^= c;
    h *= 1099511628211ull;
  }
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  return hex;
}

}  // namespace evas::study
