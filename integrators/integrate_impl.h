// Driver loop shared by every integrator: outputs and stops (see integrator.h).
#pragma once

#include <algorithm>

namespace evas {

template <class Sink>
void integrate(Integrator& integ, Problem& p, double t0, const std::vector<double>& outputs,
               Sink&& sink) {
  if (p.internal_count() > 0 && !integ.takes_internal_states())
    throw InputError("integrator '" + integ.name() +
                     "' does not integrate element internal states (" + p.internal_name(0) + ", " +
                     std::to_string(p.internal_count()) + " in all): use ida or cvode");
  require_quasi_static_support(integ, p);
  Vec q(p.size()), v(p.size());
  double t = t0;
  std::size_t k = 0;
  while (k < outputs.size()) {
    const double tout = outputs[k];
    const double stop = p.next_stop(t);
    const double eps = 1e-12 * std::max(1.0, std::abs(tout));
    if (stop < tout - eps) {
      integ.advance(stop, true, q, v);
      t = stop;
      if (p.at_stop(t, q.data(), v.data())) integ.restart(t, q, v);
      continue;
    }
    const bool land = std::abs(stop - tout) <= eps;
    integ.advance(tout, land, q, v);
    t = tout;
    sink(t, q, v);
    if (land && p.at_stop(t, q.data(), v.data())) integ.restart(t, q, v);
    ++k;
  }
}

}  // namespace evas
