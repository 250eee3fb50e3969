// Test-only: runs an integrator on the oscillators of sdof_problem.h and
// measures the largest error against their closed form over the outputs.
#pragma once

#include <algorithm>
#include <vector>

#include "integrators/integrator.h"
#include "sdof_problem.h"

namespace evas {
namespace test {

struct Errors {
  double q = 0.0, v = 0.0;  // max over outputs of max-norm errors
};

inline Errors run_sdof(const IntegratorSettings& s, SdofProblem& p,
                       const std::vector<double>& outputs, IntegratorStats* stats = nullptr) {
  auto integ = make_integrator(s.name);
  Vec q0, v0;
  p.initial_state(q0, v0);
  integ->init(p, 0.0, q0, v0, s);
  Errors e;
  integrate(*integ, p, 0.0, outputs, [&](double t, const Vec& q, const Vec& v) {
    Vec qe, ve;
    p.exact(t, qe, ve);
    e.q = std::max(e.q, (q - qe).lpNorm<Eigen::Infinity>());
    e.v = std::max(e.v, (v - ve).lpNorm<Eigen::Infinity>());
  });
  if (stats) *stats = integ->stats();
  return e;
}

/// Outputs at t = 0.1, 0.2, ..., 1.
inline std::vector<double> tenth_outputs() {
  std::vector<double> outputs;
  for (int k = 1; k <= 10; ++k) outputs.push_back(0.1 * k);
  return outputs;
}

/// A kicked stop between outputs, a kicked stop on an output, a quiet stop.
inline std::vector<Stop> kicked_stops() {
  return {{0.3137, {0.7, -0.2, 0.1}}, {0.5, {-0.4, 0.3, 0.0}}, {0.6502, {}}};
}

}  // namespace test
}  // namespace evas
