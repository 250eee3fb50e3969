// Spectra over time (post/time_spectrum.h), against signals whose spectra are
// known by hand: a sinusoid at a bin frequency reads its amplitude under every
// window (Heinzel, Ruediger & Schilling 2002: amplitude scaling by sum(w));
// between bins the flat-top window stays within 0.12 % and the Hann window
// loses the scalloping its formula predicts; the PSD integrates to the mean
// square (Parseval) and, for white noise of variance s^2, averages to
// 2 s^2 / fs; third-octave bands hold a sinusoid's RMS value a / sqrt(2) in the
// band of its frequency; and bad input is refused with what is wrong.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "model/types.h"
#include "post/time_spectrum.h"

using namespace evas;

namespace {

struct Signal {
  std::vector<double> t, y;
};

// n samples at fs of a cos(2 pi f t + phi) + offset.
Signal sine(long n, double fs, double a, double f, double phi = 0.3, double offset = 0.0) {
  Signal s;
  for (long i = 0; i < n; ++i) {
    const double t = 0.25 + i / fs;  // a start that is not zero
    s.t.push_back(t);
    s.y.push_back(offset + a * std::cos(2 * M_PI * f * t + phi));
  }
  return s;
}

std::size_t peak(const TimeSpectrum& s) {
  std::size_t k = 1;
  for (std::size_t i = 1; i < s.amplitude.size(); ++i)
    if (s.amplitude[i] > s.amplitude[k]) k = i;
  return k;
}

}  // namespace

TEST(TimeSpectrum, SinusoidAtABinReadsItsAmplitudeUnderEveryWindow) {
  const double fs = 10000.0, a = 2.5;
  const long n = 2000;                               // df = 5 Hz
  const Signal s = sine(n, fs, a, 350.0, 0.3, 7.0);  // bin 70; the offset is removed
  for (const std::string& w : spectrum_windows()) {
    SCOPED_TRACE(w);
    TimeSpectrumOptions o;
    o.window = w;
    const TimeSpectrum sp = time_spectrum(s.t, s.y, o);
    EXPECT_DOUBLE_EQ(sp.df, 5.0);
    ASSERT_EQ(sp.frequency.size(), static_cast<std::size_t>(n / 2 + 1));
    EXPECT_EQ(sp.segments, 1);
    const std::size_t k = peak(sp);
    EXPECT_DOUBLE_EQ(sp.frequency[k], 350.0);
    EXPECT_NEAR(sp.amplitude[k], a, 1e-9 * a);
    EXPECT_NEAR(sp.amplitude[0], 0.0, 1e-9);  // the mean is removed
  }
}

TEST(TimeSpectrum, BetweenBinsFlatTopHoldsTheAmplitudeAndHannLosesItsScalloping) {
  const double fs = 10000.0, a = 1.0;
  const Signal s = sine(2000, fs, a, 352.5);  // half-way between bins 70 and 71
  TimeSpectrumOptions o;
  o.window = "flattop";
  const TimeSpectrum ft = time_spectrum(s.t, s.y, o);
  EXPECT_NEAR(ft.amplitude[peak(ft)], a, 1.2e-3 * a);  // 0.9989: 0.01 dB
  // Hann at half a bin: |W(1/2)| / W(0) = sinc(1/2) / (1 - 1/4) = (2/pi) / (3/4)
  // = 0.8488 (the 1.42 dB scalloping loss)
  o.window = "hann";
  const TimeSpectrum h = time_spectrum(s.t, s.y, o);
  EXPECT_NEAR(h.amplitude[peak(h)], a * 8.0 / (3.0 * M_PI), 2e-3);
  // rectangular at half a bin: sinc(1/2) = 2/pi (3.92 dB)
  o.window = "rectangular";
  const TimeSpectrum r = time_spectrum(s.t, s.y, o);
  EXPECT_NEAR(r.amplitude[peak(r)], a * 2.0 / M_PI, 2e-3);
}

TEST(TimeSpectrum, PsdIntegratesToTheMeanSquareAndWhiteNoiseIsFlat) {
  std::mt19937 gen(5);
  std::normal_distribution<double> N01(0.0, 1.0);
  const double fs = 2000.0, sigma = 0.7;
  Signal s;
  for (long i = 0; i < 40000; ++i) {
    s.t.push_back(i / fs);
    s.y.push_back(sigma * N01(gen));
  }
  // Parseval, one rectangular segment: sum G df = mean square of y - mean
  TimeSpectrumOptions o;
  o.window = "rectangular";
  const TimeSpectrum r = time_spectrum(s.t, s.y, o);
  double mean = 0.0, ms = 0.0, sum = 0.0;
  for (double y : s.y) mean += y;
  mean /= static_cast<double>(s.y.size());
  for (double y : s.y) ms += (y - mean) * (y - mean);
  ms /= static_cast<double>(s.y.size());
  for (double g : r.psd) sum += g * r.df;
  EXPECT_NEAR(sum, ms, 1e-12 * ms);
  // Welch, Hann, 1-s segments with half overlap: 39 segments; the mean PSD
  // over the band is 2 sigma^2 / fs within its scatter (1/sqrt(segments x bins))
  o.window = "hann";
  o.segment = 2000;
  const TimeSpectrum w = time_spectrum(s.t, s.y, o);
  EXPECT_EQ(w.segments, 39);
  EXPECT_NEAR(w.enbw, 1.5 * w.df, 1e-9);  // Hann: 1.5 bins
  double g = 0.0;
  for (std::size_t k = 1; k + 1 < w.psd.size(); ++k) g += w.psd[k];
  g /= static_cast<double>(w.psd.size() - 2);
  EXPECT_NEAR(g, 2.0 * sigma * sigma / fs, 0.02 * 2.0 * sigma * sigma / fs);
}

TEST(TimeSpectrum, ThirdOctaveBandHoldsTheSinusoidsRms) {
  const double fs = 20000.0, a = 3.0;
  const Signal s = sine(20000, fs, a, 1000.0);  // df = 1 Hz
  TimeSpectrumOptions o;
  o.window = "hann";
  const TimeSpectrum sp = time_spectrum(s.t, s.y, o);
  const std::vector<Band> bands = third_octave_bands(sp);
  ASSERT_FALSE(bands.empty());
  EXPECT_NEAR(bands.front().centre, 10.0, 1e-9);
  bool found = false;
  for (const Band& b : bands) {
    EXPECT_NEAR(b.upper / b.lower, std::pow(10.0, 0.1), 1e-12);
    if (std::abs(b.centre - 1000.0) < 1e-9) {
      found = true;
      EXPECT_NEAR(b.rms, a / std::sqrt(2.0), 1e-6 * a);
      EXPECT_EQ(b.bins, 231);  // 891.25 .. 1122.0 Hz at 1 Hz
    } else {
      EXPECT_LT(b.rms, 1e-6 * a) << b.centre;  // Hann leaks a few bins only
    }
  }
  EXPECT_TRUE(found);
  EXPECT_GE(bands.back().upper, 10000.0);  // up to the band of the Nyquist frequency
}

TEST(TimeSpectrum, TheTimeWindowSelectsSamplesAndSegmentsEndAtItsEnd) {
  const Signal s = sine(4000, 1000.0, 1.0, 50.0);  // t = 0.25 .. 4.249
  TimeSpectrumOptions o;
  o.t0 = 1.0;
  o.t1 = 3.0;
  o.segment = 500;
  o.overlap = 0.0;
  const TimeSpectrum sp = time_spectrum(s.t, s.y, o);
  EXPECT_EQ(sp.segments, 4);
  EXPECT_DOUBLE_EQ(sp.t1, 3.0);
  EXPECT_NEAR(sp.t0, 1.001, 1e-9);  // 2000 samples 1.001 .. 3.0 of the 2001 in [1, 3]
  EXPECT_NEAR(sp.amplitude[peak(sp)], 1.0, 1e-9);
}

TEST(TimeSpectrum, BadInputIsRefusedWithWhatIsWrong) {
  const Signal s = sine(100, 1000.0, 1.0, 50.0);
  auto says = [&](TimeSpectrumOptions o, const std::string& what, Signal x = {}) {
    if (x.t.empty()) x = s;
    try {
      time_spectrum(x.t, x.y, o);
      ADD_FAILURE() << "accepted: " << what;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  TimeSpectrumOptions o;
  o.window = "kaiser";
  says(o, "unknown window 'kaiser' (known: rectangular, hann, flattop)");
  o = {};
  o.overlap = 1.0;
  says(o, "overlap 1 is not in [0, 1)");
  o = {};
  o.t0 = 5.0;
  o.t1 = 6.0;
  says(o, "0 samples in [5, 6] s");
  o = {};
  o.segment = 101;
  says(o, "a segment of 101 samples does not fit the 100 samples");
  Signal bent = s;
  bent.t[40] += 2e-4;
  says({}, "not uniform at sample 40", bent);
  Signal nan = s;
  nan.y[7] = std::nan("");
  says({}, "sample 7 is not finite", nan);
}
