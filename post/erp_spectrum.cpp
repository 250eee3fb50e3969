#include "post/erp_spectrum.h"

#include <algorithm>
#include <cmath>

#include "model/types.h"

namespace evas {

std::vector<std::vector<double>> erp_components(const std::vector<std::string>& names,
                                                const Mat& values, const std::string& name,
                                                const std::string& prefix) {
  std::vector<std::vector<double>> out;
  for (int k = 0;; ++k) {
    const std::string want = name + "." + prefix + std::to_string(k);
    const auto it = std::find(names.begin(), names.end(), want);
    if (it == names.end()) return out;
    const Eigen::Index c = it - names.begin();
    out.emplace_back(values.col(c).data(), values.col(c).data() + values.rows());
  }
}

double erp_level(double power) { return 10.0 * std::log10(power / 1e-12); }

ErpSpectrum erp_spectrum(const std::vector<double>& t,
                         const std::vector<std::vector<double>>& components,
                         const TimeSpectrumOptions& o, std::vector<ErpBand>* bands) {
  if (components.empty()) throw InputError("ERP spectrum: no component");
  ErpSpectrum out;
  if (bands) bands->clear();
  for (std::size_t k = 0; k < components.size(); ++k) {
    const std::vector<double>& c = components[k];
    if (c.size() != t.size())
      throw InputError("ERP spectrum: component " + std::to_string(k) + " has " +
                       std::to_string(c.size()) + " samples, the time " + std::to_string(t.size()));
    const TimeSpectrum s = time_spectrum(t, c, o);
    if (k == 0) {
      out.frequency = s.frequency;
      out.power.assign(s.frequency.size(), 0.0);
      out.density.assign(s.frequency.size(), 0.0);
      out.df = s.df;
      out.segments = s.segments;
      out.samples = s.samples;
      out.t0 = s.t0;
      out.t1 = s.t1;
    }
    for (std::size_t j = 0; j < s.frequency.size(); ++j) {
      out.power[j] += 0.5 * s.amplitude[j] * s.amplitude[j];
      out.density[j] += s.psd[j];
    }
    // mean of c^2 over the samples used (the mean is not removed here)
    double sum = 0.0;
    long n = 0;
    for (std::size_t i = 0; i < t.size(); ++i)
      if (t[i] >= s.t0 && t[i] <= s.t1) {
        sum += c[i] * c[i];
        ++n;
      }
    out.mean += n ? sum / static_cast<double>(n) : 0.0;
    if (bands) {
      const std::vector<Band> b = third_octave_bands(s);
      if (k == 0)
        for (const Band& x : b) bands->push_back({x.centre, x.lower, x.upper, 0.0, x.bins});
      for (std::size_t j = 0; j < b.size() && j < bands->size(); ++j)
        (*bands)[j].power += b[j].rms * b[j].rms;
    }
  }
  return out;
}

}  // namespace evas
