#include "post/order_spectrum.h"

#include <cmath>
#include <cstdio>
#include <string>

#include "model/types.h"

namespace evas {

OrderSpectrum order_spectrum(const std::vector<double>& theta, const std::vector<double>& y,
                             int cycles, double cycle_deg, double max_order) {
  return order_spectra(theta, {&y}, cycles, cycle_deg, max_order).front();
}

std::vector<OrderSpectrum> order_spectra(const std::vector<double>& theta,
                                         const std::vector<const std::vector<double>*>& ys,
                                         int cycles, double cycle_deg, double max_order) {
  const std::size_t n = theta.size();
  for (const auto* y : ys)
    if (y->size() != n) throw InputError("order spectrum: angle and signal lengths differ");
  if (n < 3) throw InputError("order spectrum: fewer than 3 samples");
  if (cycles < 0)
    throw InputError("order spectrum: cycles = " + std::to_string(cycles) +
                     " must be >= 1 (or 0 for every whole cycle)");
  if (!(cycle_deg > 0.0) || !std::isfinite(cycle_deg))
    throw InputError("order spectrum: the cycle length must be a positive number of degrees");
  if (!(max_order >= 0.0) || !std::isfinite(max_order))
    throw InputError("order spectrum: the highest order must be >= 0");
  for (std::size_t i = 0; i < n; ++i)
    if (!std::isfinite(theta[i]))
      throw InputError("order spectrum: crank angle " + std::to_string(i) + " is not finite");
  const double d = theta[1] - theta[0];
  if (!(d > 0.0)) throw InputError("order spectrum: crank angles must increase");
  for (std::size_t i = 1; i < n; ++i)
    if (std::abs(theta[i] - theta[i - 1] - d) > 1e-6 * d)
      throw InputError("order spectrum: crank-angle grid is not uniform at sample " +
                       std::to_string(i) + " (run the scene with output grid crank-angle)");
  const double per_cycle = cycle_deg / d;
  const long M = std::lround(per_cycle);
  if (M < 2 || std::abs(per_cycle - M) > 1e-6 * per_cycle)
    throw InputError("order spectrum: the step " + std::to_string(d) + " deg does not divide " +
                     std::to_string(cycle_deg) + " deg");
  const long available = static_cast<long>(n) / M;
  if (available < 1)
    throw InputError("order spectrum: the record covers less than one " +
                     std::to_string(cycle_deg) + "-deg cycle");
  const long C = cycles > 0 ? cycles : available;
  if (C > available)
    throw InputError("order spectrum: " + std::to_string(C) + " cycles asked, the record holds " +
                     std::to_string(available));
  const long N = C * M;
  const std::size_t first = n - static_cast<std::size_t>(N);
  for (const auto* y : ys)
    for (std::size_t i = first; i < n; ++i)
      if (!std::isfinite((*y)[i])) throw InputError("order spectrum: non-finite sample");

  const double order_step = 360.0 / cycle_deg;  // orders per cycle harmonic
  const long jmax_nyq = M / 2;
  const long jmax =
      max_order > 0.0 ? std::min(jmax_nyq, static_cast<long>(max_order / order_step)) : jmax_nyq;
  const double theta0 = theta[first] * M_PI / 180.0;
  std::vector<OrderSpectrum> out(ys.size());
  std::vector<double> c(static_cast<std::size_t>(N)), sn(static_cast<std::size_t>(N));
  for (long j = 0; j <= jmax; ++j) {
    // DFT bin k = j C: j periods per cycle; one table of cos and sin for all signals
    const double w = 2.0 * M_PI * static_cast<double>(j) / static_cast<double>(M);
    for (long i = 0; i < N; ++i) {
      c[static_cast<std::size_t>(i)] = std::cos(w * i);
      sn[static_cast<std::size_t>(i)] = std::sin(w * i);
    }
    const bool edge = j == 0 || (M % 2 == 0 && j == M / 2);
    const double scale = (edge ? 1.0 : 2.0) / static_cast<double>(N);
    const double order = j * order_step;
    for (std::size_t k = 0; k < ys.size(); ++k) {
      const std::vector<double>& y = *ys[k];
      double re = 0.0, im = 0.0;
      for (long i = 0; i < N; ++i) {
        re += y[first + i] * c[static_cast<std::size_t>(i)];
        im -= y[first + i] * sn[static_cast<std::size_t>(i)];
      }
      OrderSpectrum& s = out[k];
      s.cycles = static_cast<int>(C);
      s.available = static_cast<int>(available);
      s.first_angle = theta[first];
      s.last_angle = theta[n - 1];
      s.order.push_back(order);
      s.amplitude.push_back(scale * std::hypot(re, im));
      // y ~ A cos(order (theta - theta0) + phi0) = A cos(order theta + phase)
      s.phase.push_back(std::remainder(std::atan2(im, re) - order * theta0, 2.0 * M_PI));
    }
  }
  return out;
}

std::string cycles_used(const OrderSpectrum& s, double cycle_deg) {
  auto deg = [](double x) {
    char b[32];
    std::snprintf(b, sizeof b, "%.6g", x);
    return std::string(b);
  };
  const std::string whole = " whole " + deg(cycle_deg) + "-deg cycle";
  std::string t = s.cycles == s.available && s.cycles == 1
                      ? "the record's one" + whole
                      : "the last " + std::to_string(s.cycles) + " of " +
                            std::to_string(s.available) + whole + (s.available == 1 ? "" : "s");
  return t + " (crank angle " + deg(s.first_angle) + " to " + deg(s.last_angle) + " deg)";
}

}  // namespace evas
