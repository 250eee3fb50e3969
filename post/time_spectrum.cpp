// Spectra over time (time_spectrum.h).
#include "post/time_spectrum.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <sstream>
#include <unsupported/Eigen/FFT>

#include "model/types.h"

namespace evas {

namespace {

std::string num(double x) {
  std::ostringstream os;
  os.precision(9);
  os << x;
  return os.str();
}

// The window's N samples (periodic form: the DFT's own period, Heinzel et al.).
std::vector<double> window_samples(const std::string& name, long N) {
  std::vector<double> w(static_cast<std::size_t>(N), 1.0);
  // sum_j (-1)^j a_j cos(2 pi j n / N)
  std::vector<double> a;
  if (name == "hann") a = {0.5, 0.5};
  if (name == "flattop") a = {0.21557895, 0.41663158, 0.277263158, 0.083578947, 0.006947368};
  if (a.empty()) return w;  // rectangular
  for (long n = 0; n < N; ++n) {
    double s = 0.0;
    for (std::size_t j = 0; j < a.size(); ++j)
      s += (j % 2 ? -1.0 : 1.0) * a[j] * std::cos(2.0 * M_PI * static_cast<double>(j * n) / N);
    w[static_cast<std::size_t>(n)] = s;
  }
  return w;
}

}  // namespace

const std::vector<std::string>& spectrum_windows() {
  static const std::vector<std::string> w = {"rectangular", "hann", "flattop"};
  return w;
}

TimeSpectrum time_spectrum(const std::vector<double>& t, const std::vector<double>& y,
                           const TimeSpectrumOptions& o) {
  const auto& names = spectrum_windows();
  if (std::find(names.begin(), names.end(), o.window) == names.end())
    throw InputError("time spectrum: unknown window '" + o.window +
                     "' (known: rectangular, hann, flattop)");
  if (t.size() != y.size()) throw InputError("time spectrum: time and signal lengths differ");
  if (!(o.overlap >= 0.0 && o.overlap < 1.0))
    throw InputError("time spectrum: the overlap " + num(o.overlap) + " is not in [0, 1)");
  if (!(o.t0 < o.t1)) throw InputError("time spectrum: the time window is empty");
  // the samples in [t0, t1]
  std::size_t first = 0, last = t.size();
  while (first < t.size() && t[first] < o.t0) ++first;
  while (last > first && t[last - 1] > o.t1) --last;
  const long n = static_cast<long>(last - first);
  if (n < 4)
    throw InputError("time spectrum: " + std::to_string(n) + " samples in [" + num(o.t0) + ", " +
                     num(o.t1) + "] s; 4 or more are needed");
  for (std::size_t i = first; i < last; ++i)
    if (!std::isfinite(t[i]) || !std::isfinite(y[i]))
      throw InputError("time spectrum: sample " + std::to_string(i) + " is not finite");
  const double dt = (t[last - 1] - t[first]) / static_cast<double>(n - 1);
  if (!(dt > 0.0)) throw InputError("time spectrum: the times must increase");
  for (std::size_t i = first + 1; i < last; ++i)
    if (std::abs(t[i] - t[i - 1] - dt) > 1e-6 * dt)
      throw InputError(
          "time spectrum: the time grid is not uniform at sample " + std::to_string(i) +
          " (t = " + num(t[i]) +
          " s): a spectrum over time needs the time output grid (a crank-angle grid is uniform "
          "in time only at constant speed)");
  const long N = o.segment > 0 ? o.segment : n;
  if (N < 4 || N > n)
    throw InputError("time spectrum: a segment of " + std::to_string(N) +
                     " samples does not fit the " + std::to_string(n) +
                     " samples of the time window (4 to " + std::to_string(n) + ")");
  const long hop =
      std::max(1L, static_cast<long>(std::floor(static_cast<double>(N) * (1.0 - o.overlap))));
  const std::vector<double> w = window_samples(o.window, N);
  double sw = 0.0, sw2 = 0.0;
  for (double x : w) {
    sw += x;
    sw2 += x * x;
  }
  const double fs = 1.0 / dt;
  TimeSpectrum s;
  s.df = fs / static_cast<double>(N);
  s.enbw = fs * sw2 / (sw * sw);
  s.samples = N;
  const long bins = N / 2 + 1;
  s.frequency.resize(static_cast<std::size_t>(bins));
  for (long k = 0; k < bins; ++k) s.frequency[static_cast<std::size_t>(k)] = k * s.df;
  std::vector<double> a2(static_cast<std::size_t>(bins), 0.0),
      g(static_cast<std::size_t>(bins), 0.0);
  Eigen::FFT<double> fft;
  std::vector<double> seg(static_cast<std::size_t>(N));
  std::vector<std::complex<double>> X;
  long segments = 0;
  // segments from the end of the window backwards, so that the latest samples
  // (after the start-up transient) are always in
  for (long end = n; end - N >= 0; end -= hop) {
    const std::size_t at = first + static_cast<std::size_t>(end - N);
    double mean = 0.0;
    if (o.remove_mean) {
      for (long i = 0; i < N; ++i) mean += y[at + static_cast<std::size_t>(i)];
      mean /= static_cast<double>(N);
    }
    for (long i = 0; i < N; ++i)
      seg[static_cast<std::size_t>(i)] =
          (y[at + static_cast<std::size_t>(i)] - mean) * w[static_cast<std::size_t>(i)];
    fft.fwd(X, seg);
    for (long k = 0; k < bins; ++k) {
      const double c = (k == 0 || (N % 2 == 0 && k == N / 2)) ? 1.0 : 2.0;
      const double m2 = std::norm(X[static_cast<std::size_t>(k)]);
      a2[static_cast<std::size_t>(k)] += (c * c) * m2 / (sw * sw);
      g[static_cast<std::size_t>(k)] += c * m2 / (fs * sw2);
    }
    if (segments == 0) s.t1 = t[at + static_cast<std::size_t>(N) - 1];
    s.t0 = t[at];
    ++segments;
  }
  s.segments = static_cast<int>(segments);
  s.amplitude.resize(static_cast<std::size_t>(bins));
  s.psd.resize(static_cast<std::size_t>(bins));
  for (std::size_t k = 0; k < a2.size(); ++k) {
    s.amplitude[k] = std::sqrt(a2[k] / static_cast<double>(segments));
    s.psd[k] = g[k] / static_cast<double>(segments);
  }
  return s;
}

std::vector<Band> third_octave_bands(const TimeSpectrum& s) {
  std::vector<Band> out;
  if (s.frequency.size() < 2) return out;
  const double nyquist = s.frequency.back();
  // x such that f_m = 1000 * 10^(x / 10): from 10 Hz (x = -20) up
  for (int x = -20; x <= 40; ++x) {
    Band b;
    b.centre = 1000.0 * std::pow(10.0, x / 10.0);
    b.lower = b.centre * std::pow(10.0, -1.0 / 20.0);
    b.upper = b.centre * std::pow(10.0, 1.0 / 20.0);
    if (b.lower > nyquist) break;
    if (b.upper <= s.df) continue;  // below the resolution
    double sum = 0.0;
    for (std::size_t k = 1; k < s.frequency.size(); ++k)
      if (s.frequency[k] >= b.lower && s.frequency[k] < b.upper) {
        sum += s.psd[k] * s.df;
        ++b.bins;
      }
    b.rms = std::sqrt(sum);
    out.push_back(b);
  }
  return out;
}

}  // namespace evas
