// The progress line of a run on stderr, redrawn at most twice a second.
#pragma once

#include <chrono>
#include <cmath>
#include <cstdio>

namespace evas::run {

class Progress {
 public:
  Progress(bool quiet, double t0, double t1) : quiet_(quiet), t0_(t0), t1_(t1) {}
  bool due() const {
    return !quiet_ &&
           std::chrono::duration<double>(std::chrono::steady_clock::now() - last_).count() >= 0.5;
  }
  /// h: the last step [s] (0: unknown); a collapsing step shows here first.
  void draw(double t, long steps, double h) {
    if (quiet_) return;
    last_ = std::chrono::steady_clock::now();
    const double pct = 100.0 * (t - t0_) / (t1_ - t0_);
    std::fprintf(stderr, "\r  t = %.6g s  %5.1f %%  %ld steps  step %.2g s   ", t, pct, steps,
                 std::abs(h));
    std::fflush(stderr);
    drawn_ = true;
  }
  void end() {
    if (drawn_) std::fputc('\n', stderr);
    drawn_ = false;
  }

 private:
  bool quiet_;
  double t0_, t1_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point last_{};
};

}  // namespace evas::run
