// Private helpers shared by all integrators in this folder (not a public header).
#pragma once

#include <chrono>
#include <cmath>
#include <iomanip>
#include <memory>
#include <sstream>
#include <string>

#include "integrators/integrator.h"

namespace evas {

// The built-in integrators behind make_integrator (registry.cpp), one entry
// (name, factory, description, capabilities) per integrator's source file.
IntegratorEntry ida_entry();
IntegratorEntry cvode_entry();
IntegratorEntry generalized_alpha_entry();
IntegratorEntry linear_acceleration_entry();
IntegratorEntry radau_entry();
IntegratorEntry hht_alpha_entry();
IntegratorEntry newmark_entry();
IntegratorEntry central_difference_entry();
IntegratorEntry arkode_entry();
IntegratorEntry bathe_entry();

/// A number in six significant digits, for messages (t, h).
inline std::string g6(double x) {
  std::ostringstream os;
  os << std::setprecision(6) << x;
  return os.str();
}

/// Track the smallest and largest accepted step.
inline void note_step(IntegratorStats& s, double h) {
  h = std::abs(h);
  if (h <= 0.0) return;
  if (s.min_step == 0.0 || h < s.min_step) s.min_step = h;
  if (h > s.max_step) s.max_step = h;
}

/// Adds the wall time of a scope to a running total (steady clock).
class WallTimer {
 public:
  explicit WallTimer(double& acc) : acc_(acc), start_(std::chrono::steady_clock::now()) {}
  ~WallTimer() {
    acc_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  WallTimer(const WallTimer&) = delete;
  WallTimer& operator=(const WallTimer&) = delete;

 private:
  double& acc_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace evas
