// evas_work_precision SCENE OUT_DIR [T_END]
// Work-precision diagram of one scene: every integrator over a tolerance (or
// step) sweep, error against a reference run of IDA at rtol 1e-11, against
// wall time and residual evaluations. Writes OUT_DIR/work_precision_table.md (table),
// OUT_DIR/work_precision.dat and, when gnuplot is present, OUT_DIR/work_precision.png.
//
// Error: max over output times and channels of |y - y_ref| / A_c, with A_c the
// largest |y_ref - mean(y_ref)| of channel c over the run (an L-infinity error
// relative to each channel's own amplitude). Time: minimum of two runs.
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "integrators/integrator.h"
#include "io/outputs.h"
#include "io/scene.h"

using namespace evas;
using Clock = std::chrono::steady_clock;

namespace {

struct Result {
  std::vector<std::vector<double>> y;  // per output time, per channel
  IntegratorStats stats;
  double wall = 0;
};

Result run(const std::string& path, const IntegratorSettings& s, double t_end) {
  Scene scene = read_scene(path);
  if (t_end > 0) scene.t_end = t_end;
  System sys(*scene.model);
  OutputSet out(scene.output, sys, scene.t_start, scene.t_end);
  auto integ = make_integrator(s.name);
  Vec q, v;
  sys.initial_state(q, v);
  Result r;
  const auto t0 = Clock::now();
  integ->init(sys, scene.t_start, q, v, s);
  std::vector<double> row(out.size());
  std::vector<double> times = out.times();
  if (!times.empty() && times.front() <= scene.t_start) {  // the initial state is an output
    out.values(scene.t_start, q.data(), v.data(), row.data());
    r.y.push_back(row);
    times.erase(times.begin());
  }
  integrate(*integ, sys, scene.t_start, times, [&](double t, const Vec& qq, const Vec& vv) {
    out.values(t, qq.data(), vv.data(), row.data());
    r.y.push_back(row);
  });
  r.wall = std::chrono::duration<double>(Clock::now() - t0).count();
  r.stats = integ->stats();
  return r;
}

double error(const Result& r, const Result& ref) {
  const std::size_t nc = ref.y.front().size();
  double e = 0;
  for (std::size_t c = 0; c < nc; ++c) {
    double mean = 0, amp = 0;
    for (const auto& row : ref.y) mean += row[c] / ref.y.size();
    for (const auto& row : ref.y) amp = std::max(amp, std::abs(row[c] - mean));
    if (amp == 0) continue;
    for (std::size_t k = 0; k < ref.y.size(); ++k)
      e = std::max(e, std::abs(r.y[k][c] - ref.y[k][c]) / amp);
  }
  return e;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::cerr << "usage: evas_work_precision SCENE OUT_DIR [T_END]\n";
    return 1;
  }
  const std::string scene = argv[1], dir = argv[2];
  const double t_end = argc > 3 ? std::atof(argv[3]) : 0.0;
  try {
    IntegratorSettings ref_s;
    ref_s.name = "ida";
    ref_s.rtol = 1e-11;
    ref_s.atol = 1e-15;
    const Result ref = run(scene, ref_s, t_end);
    std::cerr << "reference: " << ref.stats.steps << " steps, " << ref.wall << " s\n";

    struct Config {
      std::string label;
      IntegratorSettings s;
    };
    std::vector<Config> configs;
    for (std::string name : {"ida", "cvode-bdf", "cvode-adams"}) {
      for (double rtol : {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8}) {
        IntegratorSettings s;
        s.name = name == "ida" ? "ida" : "cvode";
        s.method = name == "cvode-adams" ? "adams" : "bdf";
        s.rtol = rtol;
        s.atol = rtol * 1e-4;
        configs.push_back({name, s});
      }
    }
    for (std::string name : {"generalized-alpha", "linear-acceleration"}) {
      for (double h : {4e-5, 2e-5, 1e-5, 5e-6}) {
        IntegratorSettings s;
        s.name = name;
        s.step = h;
        s.rtol = 1e-10;
        s.atol = 1e-14;
        s.balance_tol = 1e-3;  // the paper's 0.1 %
        configs.push_back({name, s});
      }
    }
    std::ofstream dat(dir + "/work_precision.dat");
    std::ostringstream md;
    md << "| integrator | rtol / step | error | wall [s] | steps | residuals | Jacobians | "
          "factorizations | nonlinear iterations "
          "|\n|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    std::string last;
    std::vector<std::string> labels;
    for (const auto& c : configs) {
      Result r = run(scene, c.s, t_end);
      const Result r2 = run(scene, c.s, t_end);
      r.wall = std::min(r.wall, r2.wall);
      const double e = error(r, ref);
      if (c.label != last) {
        if (!last.empty()) dat << "\n\n";
        dat << "# " << c.label << "\n";
        labels.push_back(c.label);
      }
      last = c.label;
      const double knob =
          c.s.step > 0 && (c.label == "generalized-alpha" || c.label == "linear-acceleration")
              ? c.s.step
              : c.s.rtol;
      dat << std::setprecision(6) << e << " " << r.wall << " " << r.stats.residual_evals << " "
          << knob << "\n";
      md << "| " << c.label << " | " << std::defaultfloat << knob << " | " << std::scientific
         << std::setprecision(2) << e << " | " << std::fixed << std::setprecision(4) << r.wall
         << " | " << r.stats.steps << " | " << r.stats.residual_evals << " | "
         << r.stats.jacobian_evals << " | " << r.stats.linear_setups << " | "
         << r.stats.nonlinear_iterations << " |\n";
      std::cerr << c.label << " " << knob << ": error " << e << ", " << r.wall << " s\n";
    }
    dat.close();
    std::ofstream(dir + "/work_precision_table.md") << md.str();
    std::cout << md.str();
    // Figure: one curve per integrator, error against wall time (log-log).
    std::ofstream gp(dir + "/work_precision.gp");
    gp << "set terminal pngcairo size 900,600\nset output '" << dir << "/work_precision.png'\n"
       << "set logscale xy\nset format x '1e%L'\nset format y '1e%L'\nset xlabel 'error (relative "
          "to channel amplitude)'\n"
       << "set ylabel 'wall time [s]'\nset key outside right\nset grid\n"
       << "set title 'work-precision: " << scene << "'\n"
       << "plot ";
    for (std::size_t i = 0; i < labels.size(); ++i)
      gp << (i ? ", " : "") << "'" << dir << "/work_precision.dat' index " << i
         << " using 1:2 with linespoints title '" << labels[i] << "'";
    gp << "\n";
    gp.close();
    if (std::system("command -v gnuplot >/dev/null 2>&1") == 0)
      std::system(("gnuplot " + dir + "/work_precision.gp 2>/dev/null").c_str());
  } catch (const std::exception& e) {
    std::cerr << "evas_work_precision: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
