// Spectrum of the equivalent radiated power (ERP) of a surface output
// (model/surface.h, docs/theory.md section 8.3).
//
// A surface output writes ERP(t) = sum_k c_k(t)^2 with components c_k
// [W^0.5] linear in the body's velocities. The spectrum of each component
// over time (post/time_spectrum.h, the same window and segments for all)
// gives, per frequency bin f_j,
//   tonal power  P_j = sum_k A_kj^2 / 2     [W]   (A the peak amplitude: the
//                power of a harmonic at f_j, exact at a bin under any window)
//   density      D_j = sum_k G_kj           [W/Hz] (G the PSD)
// and per third-octave band (IEC 61260-1:2014) the power sum_k rms_k^2 [W]
// (sum of D_j df over the band's bins). Levels are 10 log10(P / 1e-12 W) [dB]
// (ISO 3744 reference sound power 1 pW); a power of 0 has no level (-inf is
// written as an empty field, never as a number).
#pragma once

#include <string>
#include <vector>

#include "model/types.h"
#include "post/time_spectrum.h"

namespace evas {

struct ErpSpectrum {
  std::vector<double> frequency;  ///< [Hz]
  std::vector<double> power;      ///< tonal power per bin [W]
  std::vector<double> density;    ///< power spectral density [W/Hz]
  double df = 0.0;
  int segments = 0;
  long samples = 0;
  double t0 = 0.0, t1 = 0.0;
  double mean = 0.0;  ///< mean of ERP(t) over [t0, t1] [W] (mean of sum c_k^2)
};

struct ErpBand {
  double centre = 0.0, lower = 0.0, upper = 0.0;  ///< [Hz]
  double power = 0.0;                             ///< [W]
  int bins = 0;
};

/// Spectrum of ERP from its components (each sampled at t). Throws
/// InputError for no component or a component of another length, and
/// whatever time_spectrum throws.
ErpSpectrum erp_spectrum(const std::vector<double>& t,
                         const std::vector<std::vector<double>>& components,
                         const TimeSpectrumOptions& o, std::vector<ErpBand>* bands = nullptr);

/// The components NAME.c0, NAME.c1, ... of surface output `name` among the
/// channels `names`, each a column of `values` (rows x channels); empty when
/// the channels hold none. `prefix` "e": the elastic part's NAME.e0, NAME.e1, ...
std::vector<std::vector<double>> erp_components(const std::vector<std::string>& names,
                                                const Mat& values, const std::string& name,
                                                const std::string& prefix = "c");

/// 10 log10(power / 1e-12 W) [dB re 1 pW]; power must be > 0.
double erp_level(double power);

}  // namespace evas
