// An outside program built against the installed evas package (docs/extending.md):
// loads a scene, runs it with a reference integrator and with another one
// (built in or from a plug-in), and prints the largest difference of every
// output channel relative to its peak.
//
//     evas_compare SCENE.yaml REFERENCE CANDIDATE [PLUGIN.so] [KEY=VALUE ...]
//
// KEY=VALUE settings (integrators/settings.h) apply to the candidate; the
// reference runs at rtol 1e-10, atol 1e-13. Exit 0 and "max relative
// difference D" on success, 1 on bad input, 2 when a run fails.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "integrators/integrator.h"
#include "integrators/plugin.h"
#include "integrators/settings.h"
#include "io/outputs.h"
#include "io/scene.h"
#include "solver/system.h"

namespace {

// Output rows (times x channels) of one run of the scene.
std::vector<std::vector<double>> run(const std::string& scene_path,
                                     const evas::IntegratorSettings& s) {
  evas::Scene scene = evas::read_scene(scene_path);
  evas::System sys(*scene.model);
  evas::OutputSet out(scene.output, sys, scene.t_start, scene.t_end);
  std::vector<std::vector<double>> rows;
  auto record = [&](double t, const double* q, const double* v) {
    rows.emplace_back(static_cast<std::size_t>(out.size()));
    out.values(t, q, v, rows.back().data());
  };
  evas::Vec q0, v0;
  sys.initial_state(q0, v0);
  std::vector<double> times = out.times();
  if (!times.empty() && times.front() <= scene.t_start) {
    record(scene.t_start, q0.data(), v0.data());
    times.erase(times.begin());
  }
  auto integ = evas::make_integrator(s.name);
  integ->init(sys, scene.t_start, q0, v0, s);
  evas::integrate(
      *integ, sys, scene.t_start, times,
      [&](double t, const evas::Vec& q, const evas::Vec& v) { record(t, q.data(), v.data()); });
  return rows;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: %s SCENE.yaml REFERENCE CANDIDATE [PLUGIN.so] [KEY=VALUE ...]\n",
                 argv[0]);
    return 1;
  }
  try {
    evas::IntegratorSettings ref, cand;
    ref.name = argv[2];
    ref.rtol = 1e-10;
    ref.atol = 1e-13;
    cand.name = argv[3];
    for (int i = 4; i < argc; ++i) {
      const std::string a = argv[i];
      if (a.find('=') == std::string::npos)
        evas::load_plugin(a);
      else
        evas::apply_setting_assignment(cand, a);
    }
    const auto a = run(argv[1], ref);
    const auto b = run(argv[1], cand);
    if (a.size() != b.size() || a.empty()) {
      std::fprintf(stderr, "the runs gave %zu and %zu rows\n", a.size(), b.size());
      return 2;
    }
    double worst = 0.0;
    for (std::size_t c = 0; c < a.front().size(); ++c) {
      double peak = 0.0, diff = 0.0;
      for (std::size_t r = 0; r < a.size(); ++r) {
        peak = std::max(peak, std::abs(a[r][c]));
        diff = std::max(diff, std::abs(a[r][c] - b[r][c]));
      }
      if (peak > 0.0) worst = std::max(worst, diff / peak);
    }
    std::printf("%s vs %s: %zu rows x %zu channels, max relative difference %.3e\n",
                cand.name.c_str(), ref.name.c_str(), a.size(), a.front().size(), worst);
    return 0;
  } catch (const evas::InputError& e) {
    std::fprintf(stderr, "evas_compare: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "evas_compare: %s\n", e.what());
    return 2;
  }
}
