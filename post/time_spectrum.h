// Spectra over time of a channel (docs/theory.md s. 8.2), beside the order
// spectra over whole cycles (post/order_spectrum.h).
//
// The samples in a chosen time window [t0, t1] of a uniform time grid are cut
// into segments (Welch 1967: overlapping segments, each windowed, their
// spectra averaged); each segment's discrete Fourier transform X_k gives, with
// the window w_n (n = 0 .. N-1) and the sampling rate fs = 1/dt, the
// single-sided
//   amplitude  A_k   = c_k |X_k| / sum(w)                 (peak, the unit of y)
//   PSD        G_k   = c_k |X_k|^2 / (fs sum(w^2))       (unit^2/Hz)
// with c_k = 2 except at 0 Hz and at the Nyquist frequency (c_k = 1), after
// Heinzel, Ruediger & Schilling (2002), "Spectrum and spectral density
// estimation by the Discrete Fourier transform (DFT)", Max Planck Institute
// for Gravitational Physics (its sections on scaling and windows). A sinusoid of amplitude a at a
// bin frequency shows as A_k = a under every window; between bins the window's
// scalloping loss lowers it (up to 36 % rectangular, 15 % Hann, 0.11 % (0.01 dB)
// for the flat-top window, with the five cosine coefficients of MATLAB's
// flattopwin, Signal Processing Toolbox documentation). Sum(G_k) df is the mean square of the
// segment (Parseval) for the rectangular window. Averages over segments: G_k the mean, A_k the root
// mean square of the segments' amplitudes.
//
// Third-octave bands (IEC 61260-1:2014, base-10 mid-band frequencies
// f_m = 1000 * 10^(x/10) Hz, edges f_m * 10^(-+1/20)): the RMS value of each
// band, sqrt(sum of G_k df over the bins whose frequency lies in the band).
#pragma once

#include <limits>
#include <string>
#include <vector>

namespace evas {

struct TimeSpectrumOptions {
  double t0 = -std::numeric_limits<double>::infinity();  ///< window of the run [s]
  double t1 = std::numeric_limits<double>::infinity();
  std::string window = "hann";  ///< rectangular, hann or flattop
  /// Samples per segment; 0: the whole time window as one segment.
  long segment = 0;
  double overlap = 0.5;     ///< of a segment, in [0, 1)
  bool remove_mean = true;  ///< subtract each segment's mean before the window
};

struct TimeSpectrum {
  std::vector<double> frequency;  ///< [Hz], k df
  std::vector<double> amplitude;  ///< single-sided peak amplitude [unit of y]
  std::vector<double> psd;        ///< single-sided power spectral density [unit^2/Hz]
  double df = 0.0;                ///< bin width [Hz]
  double enbw = 0.0;              ///< effective noise bandwidth [Hz]: fs sum(w^2)/sum(w)^2
  int segments = 0;               ///< averaged
  long samples = 0;               ///< per segment
  double t0 = 0.0, t1 = 0.0;      ///< the samples used [s]
};

/// Names of the windows time_spectrum knows.
const std::vector<std::string>& spectrum_windows();

/// Spectrum of y(t) (t ascending with a uniform step) over o's time window.
/// Throws InputError for a non-uniform or non-finite grid, non-finite samples,
/// an unknown window, a time window with fewer than 4 samples, a segment longer
/// than the window or shorter than 4 samples, an overlap outside [0, 1).
TimeSpectrum time_spectrum(const std::vector<double>& t, const std::vector<double>& y,
                           const TimeSpectrumOptions& o = {});

struct Band {
  double centre = 0.0, lower = 0.0, upper = 0.0;  ///< [Hz]
  double rms = 0.0;                               ///< [unit of y]
  int bins = 0;  ///< spectrum bins in the band (0: narrower than the resolution)
};

/// Third-octave bands from 10 Hz (or the first band above the bin width) up to
/// the band that holds the Nyquist frequency, from the PSD of `s`.
std::vector<Band> third_octave_bands(const TimeSpectrum& s);

}  // namespace evas
