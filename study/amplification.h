// `evas study amplification`: the one-step amplification of time integrators,
// measured from the integrator itself as a black box (Hilber, Hughes & Taylor
// 1977; Chung & Hulbert 1993).
//
// The test problem is the linear oscillator q'' + 2 zeta omega q' + omega^2 q
// = 0 with omega = 2 pi / T, T = 1 s. A one-step method of state dimension m
// (2 for the Newmark family's displacement and velocity, 3 for
// generalized-alpha, which carries the acceleration too) advances it by a
// constant amplification matrix A (m x m): x_{n+1} = A x_n. By the Cayley-
// Hamilton theorem the displacements then obey the recurrence
//     q_{n+m} + c_{m-1} q_{n+m-1} + ... + c_0 q_n = 0,
// whose characteristic roots are A's eigenvalues. The study runs the
// integrator with a fixed step h from the two unit states (q, v) = (1, 0) and
// (0, 1) for a few steps, fits the recurrence of the smallest order m (1 to
// 4) that holds to round-off (least squares over both sequences), and takes
// its roots lambda_i:
//   spectral radius      rho = max |lambda_i|
//   principal roots      the complex pair of largest modulus, lambda = A +- iB:
//                        Omega_bar = atan2(B, A) (the step's numerical phase),
//   damping ratio        xi_bar = -ln(A^2 + B^2) / (2 Omega_bar),
//   period error         (T_bar - T) / T = Omega / Omega_bar - 1, Omega = omega h
// (Chung & Hulbert 1993, eqs. 22-24). Where the principal roots are real
// (the method over-damps the step: no oscillation) or h/T >= 1/2 (a step of
// half a period or more, whose phase aliases) the damping ratio and the
// period error are not defined and are left empty.
//
// The integrator runs as its settings say, with step = h and step_control =
// fixed; the Newmark family's iteration is Newton (exact in one iteration on
// a linear problem) and balance_tol, rtol and atol are 1e-12 max(1, (omega h)^2),
// 1e-13 and 1e-14
// unless the case sets them (values other than the defaults), so that the
// measured map is the method's and not its iteration's tolerance. Integrators that choose
// their own step and order (ida, cvode: variable-step BDF) have no one-step
// amplification to measure and are refused with that reason.
#pragma once

#include <string>
#include <vector>

#include "integrators/integrator.h"

namespace evas::study {

struct AmplificationOptions {
  std::vector<double> h_over_T;  ///< steps as fractions of the period
  double damping_ratio = 0.0;    ///< zeta of the oscillator
  double region = 0.0;           ///< > 0: also the stability region over |Re z|, Im z <= region
  int region_points = 60;        ///< Re z values - 1 (Im z: half as many)
  std::string out_dir;
  bool plot = true;
};

struct AmplificationPoint {
  double h_over_T = 0.0;
  double spectral_radius = 0.0;
  double damping_ratio = 0.0;  ///< NaN where the principal roots are real
  double period_error = 0.0;   ///< NaN likewise
  int order = 0;               ///< m, the recurrence's order (the state dimension seen)
  std::string note;            ///< why a value is missing (empty when all are there)
};

/// One point of a stability region: z = h lambda and the spectral radius of
/// the step's amplification of q'' + c q' + k q = 0 whose eigenvalues are z
/// and conj(z) (k = |z|^2, c = -2 Re z, h = 1). For a method applied to the
/// first-order form [q' = v, v' = -c v - k q] (a Runge-Kutta method such as
/// radau) the amplification's eigenvalues are R(z) and R(conj z), so this is
/// |R(z)|, the stability function's modulus (Hairer & Wanner, Solving ODEs II,
/// section IV.2); for a second-order method (the Newmark family) it is its
/// spectral radius at that damping and frequency. NaN where no measurement.
struct RegionPoint {
  double re = 0.0, im = 0.0, abs_R = 0.0;
};
struct AmplificationCase {
  std::string spec, label;
  std::vector<AmplificationPoint> points;
  std::vector<RegionPoint> region;  ///< with AmplificationOptions::region > 0
  std::string refused;              ///< not measurable: why (no points)
};

/// Measures one integrator setting at every h/T (see above). Throws
/// InputError for an unknown integrator or setting.
AmplificationCase measure_amplification(const IntegratorSettings& s,
                                        const std::vector<double>& h_over_T, double zeta);

/// The region over Re z in [-extent, extent] (n + 1 values) and Im z in [0,
/// extent] (n/2 + 1 values; symmetric about the real axis). Empty for an
/// integrator without fixed steps.
std::vector<RegionPoint> measure_region(const IntegratorSettings& s, double extent, int n);

/// The amplification study: every case spec's settings measured, written to
/// out_dir as case<k>/amplification.csv (h_over_T, spectral_radius,
/// damping_ratio, period_error, order), amplification.md and the three-panel
/// figure amplification.png; with o.region > 0 also case<k>/region.csv (re_z,
/// im_z, abs_R) and its contour figure case<k>/region.png. Returns the cases.
std::vector<AmplificationCase> amplification_study(const std::vector<std::string>& specs,
                                                   const AmplificationOptions& o);

/// "A,B,C" or a log range "A..B/N" of h/T values (> 0). Throws InputError.
std::vector<double> parse_h_over_t(const std::string& text);

}  // namespace evas::study
