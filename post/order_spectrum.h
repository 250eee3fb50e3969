// Order spectra of engine results (docs/theory.md s. 8).
//
// Engine results are read against crank angle and engine order. Given samples
// on a uniform crank-angle grid, the spectrum is taken over a whole number of
// cycles (720 deg for a four-stroke engine) at the end of the record, after the
// transient: the discrete Fourier transform of C cycles of M samples each
// resolves orders in steps of 360/cycle_deg (0.5 for 720 deg), and only those
// integer harmonics of the cycle are reported, so no leakage enters them.
#pragma once

#include <string>
#include <vector>

namespace evas {

struct OrderSpectrum {
  std::vector<double> order;      ///< engine order (harmonic of the crank rotation)
  std::vector<double> amplitude;  ///< single-sided amplitude (mean value at order 0)
  std::vector<double> phase;      ///< [rad] in (-pi, pi], of cos(order * theta + phase)
  int cycles = 0;                 ///< cycles used: the record's last ones
  int available = 0;              ///< whole cycles the record holds
  double first_angle = 0.0,
         last_angle = 0.0;  ///< crank angle of the first and last sample used [deg]
};

/// Which cycles a spectrum used, for the commands to print: "the last 1 of 6
/// whole 720-deg cycles (crank angle 3600 to 4319 deg)".
std::string cycles_used(const OrderSpectrum& s, double cycle_deg = 720.0);

/// theta_deg: crank angles, ascending with a uniform step that divides cycle_deg;
/// y: the signal at those angles. cycles = 0 uses as many whole cycles as the
/// record holds (from its end). Orders up to max_order (0 = Nyquist).
/// Throws InputError for a non-uniform grid, a step that does not divide the
/// cycle, a record shorter than one cycle, non-finite samples, cycles < 0, a
/// cycle length <= 0 or max_order < 0.
OrderSpectrum order_spectrum(const std::vector<double>& theta_deg, const std::vector<double>& y,
                             int cycles = 0, double cycle_deg = 720.0, double max_order = 0.0);

/// order_spectrum of several signals on the same crank angles (the checks and
/// the cosine and sine tables once for all): element k is order_spectrum(theta,
/// *ys[k], ...), digit for digit. A non-finite sample in any signal throws.
std::vector<OrderSpectrum> order_spectra(const std::vector<double>& theta,
                                         const std::vector<const std::vector<double>*>& ys,
                                         int cycles = 0, double cycle_deg = 720.0,
                                         double max_order = 0.0);

}  // namespace evas
