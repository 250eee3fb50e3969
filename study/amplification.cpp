#include "study/amplification.h"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>

#include "integrators/settings.h"
#include "plot/gnuplot.h"
#include "study/case_grid.h"

namespace evas::study {

namespace fs = std::filesystem;

namespace {

constexpr double kTwoPi = 6.283185307179586;
constexpr double kNotComputed = std::numeric_limits<double>::quiet_NaN();
constexpr int kSteps = 10;  // steps from each unit state: 2 x (10 - m) equations

// q'' + c q' + k q = 0 (unit mass), the study's test problem (k = w^2, c =
// 2 zeta w; the region's k and c may be any reals).
class Oscillator : public Problem {
 public:
  Oscillator(double k, double c) : k_(k), c_(c) {
    std::vector<Eigen::Triplet<double>> t = {{0, 0, 1.0}};
    pattern_.resize(1, 1);
    pattern_.setFromTriplets(t.begin(), t.end());
  }
  int size() const override { return 1; }
  void initial_state(Vec& q, Vec& v) const override {
    q = Vec::Ones(1);
    v = Vec::Zero(1);
  }
  void force(double, const double* q, const double* v, double* f) override {
    f[0] = k_ * q[0] + c_ * v[0];
  }
  void force_jacobian(double, const double*, const double*, SpMat& K, SpMat& C) override {
    K.coeffRef(0, 0) = k_;
    C.coeffRef(0, 0) = c_;
  }
  const SpMat& jacobian_pattern() const override { return pattern_; }

 private:
  double k_, c_;
  SpMat pattern_;
};

// The settings of a measured step h: fixed, Newton, and the iteration
// converged to round-off unless the case says otherwise (a tolerance-limited
// step is not a linear map). W = |h lambda|, the step's stiffness scale.
IntegratorSettings step_settings(const IntegratorSettings& s0, double h, double W) {
  IntegratorSettings s = s0;
  s.step = h;
  s.min_step = std::min(s.min_step, 0.5 * h);
  s.step_control = StepControl::fixed;
  if (s.iteration == Iteration::method_default) s.iteration = Iteration::newton;
  const IntegratorSettings defaults;
  // (the balance error's round-off floor grows with W^2)
  if (s.balance_tol == defaults.balance_tol) s.balance_tol = 1e-12 * std::max(1.0, W * W);
  if (s.rtol == defaults.rtol) s.rtol = 1e-13;
  if (s.atol == defaults.atol) s.atol = 1e-14;
  return s;
}

// The displacements q_0 .. q_kSteps from (q0, v0).
std::vector<double> displacements(const IntegratorSettings& s, double k, double c, double q0,
                                  double v0) {
  Oscillator p(k, c);
  const std::unique_ptr<Integrator> integ = make_integrator(s.name);
  Vec q = Vec::Constant(1, q0), v = Vec::Constant(1, v0);
  integ->init(p, 0.0, q, v, s);
  std::vector<double> out = {q0};
  for (int n = 1; n <= kSteps; ++n) {
    integ->advance(n * s.step, true, q, v);
    out.push_back(q[0]);
  }
  return out;
}

// The monic recurrence of smallest order m (1..4) that both sequences obey to
// round-off: its roots. Empty when none fits.
std::vector<std::complex<double>> recurrence_roots(const std::vector<std::vector<double>>& seqs,
                                                   double tol, int& order) {
  for (int m = 1; m <= 4; ++m) {
    std::vector<Vec> rows;
    std::vector<double> rhs;
    for (const auto& q : seqs)
      for (int n = 0; n + m < static_cast<int>(q.size()); ++n) {
        Vec r(m);
        double scale = std::abs(q[static_cast<std::size_t>(n + m)]);
        for (int j = 0; j < m; ++j) {
          r[j] = q[static_cast<std::size_t>(n + j)];
          scale = std::max(scale, std::abs(r[j]));
        }
        if (!(scale > 0.0) || !std::isfinite(scale)) continue;
        rows.push_back(r / scale);
        rhs.push_back(-q[static_cast<std::size_t>(n + m)] / scale);
      }
    if (static_cast<int>(rows.size()) < m + 2) continue;
    Mat A(static_cast<Eigen::Index>(rows.size()), m);
    Vec b(static_cast<Eigen::Index>(rows.size()));
    for (std::size_t i = 0; i < rows.size(); ++i) {
      A.row(static_cast<Eigen::Index>(i)) = rows[i].transpose();
      b[static_cast<Eigen::Index>(i)] = rhs[i];
    }
    const Vec c = A.colPivHouseholderQr().solve(b);
    if (!c.allFinite()) continue;
    const double residual = (A * c - b).norm() / std::max(1.0, b.norm());
    if (residual > tol) continue;
    Mat companion = Mat::Zero(m, m);
    for (int j = 0; j < m; ++j) companion(0, j) = -c[m - 1 - j];
    for (int j = 1; j < m; ++j) companion(j, j - 1) = 1.0;
    Eigen::EigenSolver<Mat> eig(companion, false);
    std::vector<std::complex<double>> roots;
    for (Eigen::Index j = 0; j < m; ++j) roots.push_back(eig.eigenvalues()[j]);
    order = m;
    return roots;
  }
  order = 0;
  return {};
}

std::string field(double x) {
  if (!std::isfinite(x)) return "";
  std::ostringstream os;
  os << std::setprecision(12) << x;
  return os.str();
}

// Draws `script` (run from its folder) into `png`; a failure is said on stderr
// and leaves no figure (draw_figure).
void draw(const fs::path& script, const fs::path& png) {
  if (draw_figure(script, png)) return;
  std::cerr << "evas study amplification: warning: gnuplot failed on " << script.string() << ": "
            << png.filename().string() << " not written\n";
}

// case<k>/region.csv (a blank line after each Im z row: gnuplot's grid) and
// its figure: |R| coloured blue (< 1, stable) to red (> 1), mirrored below the
// real axis.
void write_region(const fs::path& sub, const AmplificationCase& c, bool plot) {
  std::ofstream f(sub / "region.csv");
  f << "re_z,im_z,abs_R,status\n";
  // the figure's data: |R| clipped at 2, a failed point 2.2 (grey); no field
  // is empty, which would drop the point from gnuplot's grid
  std::ofstream fig(sub / "region_figure.csv");
  bool failed = false;
  double im = c.region.front().im;
  for (const RegionPoint& p : c.region) {
    if (p.im != im) {
      f << "\n";
      fig << "\n";
    }
    im = p.im;
    // a point whose fixed step failed (e.g. an implicit stage's Newton
    // iteration right of the axis): no value, its status says so
    const bool ok = std::isfinite(p.abs_R);
    failed = failed || !ok;
    f << field(p.re) << "," << field(p.im) << "," << (ok ? field(p.abs_R) : "")
      << (ok ? ",ok\n" : ",failed\n");
    fig << field(p.re) << "," << field(p.im) << "," << (ok ? field(std::min(p.abs_R, 2.0)) : "2.2")
        << "\n";
  }
  fig.close();
  if (!fig) throw InputError((sub / "region_figure.csv").string() + ": cannot write");
  if (!f) throw InputError((sub / "region.csv").string() + ": cannot write");
  std::ostringstream gp;
  gp << gp_terminal(sub / "region.png", 800, 700) << "set datafile separator ','\n"
     << "set title " << gp_quote("stability region of " + c.label + ": stable where |R(z)| <= 1")
     << "\nset xlabel 'Re z = Re(h lambda)'\nset ylabel 'Im z = Im(h lambda)'\n"
     << "set view map\nset size ratio -1\nset pm3d map corners2color c1\n"
     << "set palette defined (0 '#2166ac', 0.95 '#d1e5f0', 1 'white', 1.05 '#fddbc7', 2 "
        "'#b2182b', 2.001 '#999999', 2.2 '#999999')\n"
     << "set cbrange [0:2.2]\nset cbtics 0, 0.5, 2\nset cblabel "
     << gp_quote(std::string("|R(z)| (clipped at 2") +
                 (failed ? "; grey: the fixed step failed)" : ")"))
     << "\nunset key\n"
     << "splot 'region_figure.csv' using 1:2:3 with pm3d, "
     << "'region_figure.csv' using 1:(-$2):3 with pm3d\n";
  std::ofstream g(sub / "region.gp");
  g << gp.str();
  g.close();
  if (plot && have_gnuplot()) draw(sub / "region.gp", sub / "region.png");
}

}  // namespace

std::vector<double> parse_h_over_t(const std::string& text) {
  std::vector<double> out;
  std::vector<std::string> values;
  for (const std::string& item : split_list(text, ',')) {
    if (item.find("..") != std::string::npos) {
      for (const std::string& v : log_range("--h-over-t", item, "number")) values.push_back(v);
    } else {
      values.push_back(item);
    }
  }
  for (const std::string& v : values) {
    char* end = nullptr;
    const double x = std::strtod(v.c_str(), &end);
    if (v.empty() || *end || !(x > 0.0) || !std::isfinite(x))
      throw InputError("--h-over-t '" + text + "': '" + v + "' is not a number > 0");
    out.push_back(x);
  }
  if (out.empty()) throw InputError("--h-over-t '" + text + "': no value");
  return out;
}

AmplificationCase measure_amplification(const IntegratorSettings& s0,
                                        const std::vector<double>& h_over_T, double zeta) {
  AmplificationCase c;
  {  // the label of fixed steps without the step, which the study sweeps
    IntegratorSettings fixed = s0;
    fixed.step_control = StepControl::fixed;
    std::istringstream words(settings_label(fixed));
    for (std::string w; words >> w;)
      if (w.rfind("step=", 0) != 0 && w != "step_control=fixed")
        c.label += (c.label.empty() ? "" : " ") + w;
  }
  const IntegratorCapabilities caps = integrator_capabilities(s0.name);
  if (caps.declared && !caps.fixed_step) {
    c.refused = s0.name +
                " chooses its own step and order (variable-step, variable-order BDF): it has no "
                "one-step amplification of a given h to measure";
    return c;
  }
  constexpr double T = 1.0, w = kTwoPi / T;
  for (double ht : h_over_T) {
    const IntegratorSettings s = step_settings(s0, ht * T, w * ht * T);
    AmplificationPoint pt;
    pt.h_over_T = ht;
    std::vector<std::vector<double>> seqs;
    try {
      seqs.push_back(displacements(s, w * w, 2.0 * zeta * w, 1.0, 0.0));
      seqs.push_back(displacements(s, w * w, 2.0 * zeta * w, 0.0, 1.0));
    } catch (const std::exception& e) {
      pt.spectral_radius = pt.damping_ratio = pt.period_error = kNotComputed;
      pt.note = std::string("the run failed: ") + e.what();
      c.points.push_back(pt);
      continue;
    }
    // the steps' round-off grows with (omega h)^2 (the stiffness term of the
    // step's equation): the fit's tolerance with it, at most 1e-5
    const double fit_tol = std::min(1e-5, 1e-10 * std::max(1.0, std::pow(w * s.step, 2)));
    const std::vector<std::complex<double>> roots = recurrence_roots(seqs, fit_tol, pt.order);
    if (roots.empty()) {
      pt.spectral_radius = pt.damping_ratio = pt.period_error = kNotComputed;
      pt.note = "no linear recurrence of order <= 4 fits the steps: not a linear one-step map";
      c.points.push_back(pt);
      continue;
    }
    double rho = 0.0;
    const std::complex<double>* principal = nullptr;
    for (const auto& r : roots) {
      rho = std::max(rho, std::abs(r));
      if (r.imag() > 0.0 && (!principal || std::abs(r) > std::abs(*principal))) principal = &r;
    }
    pt.spectral_radius = rho;
    if (w * s.step >= 0.5 * kTwoPi) {
      pt.damping_ratio = pt.period_error = kNotComputed;
      pt.note =
          "h/T >= 1/2: a step of half a period or more, whose phase aliases: no damping "
          "ratio or period error";
    } else if (principal) {
      const double phase = std::atan2(principal->imag(), principal->real());
      pt.damping_ratio = -std::log(std::norm(*principal)) / (2.0 * phase);
      pt.period_error = w * s.step / phase - 1.0;
    } else {
      pt.damping_ratio = pt.period_error = kNotComputed;
      pt.note = "real principal roots: the step does not oscillate";
    }
    c.points.push_back(pt);
  }
  return c;
}

std::vector<RegionPoint> measure_region(const IntegratorSettings& s0, double extent, int n) {
  std::vector<RegionPoint> out;
  const IntegratorCapabilities caps = integrator_capabilities(s0.name);
  if (caps.declared && !caps.fixed_step) return out;
  for (int j = 0; j <= n / 2; ++j)
    for (int i = 0; i <= n; ++i) {
      RegionPoint p;
      p.re = -extent + 2.0 * extent * i / n;
      p.im = extent * j / (n / 2);
      // q'' + c q' + k q = 0 has the eigenvalues z, conj(z) (a double root
      // on the real axis): h = 1
      const double k = p.re * p.re + p.im * p.im, c = -2.0 * p.re;
      const IntegratorSettings s = step_settings(s0, 1.0, std::sqrt(k));
      try {
        const std::vector<std::vector<double>> seqs = {displacements(s, k, c, 1.0, 0.0),
                                                       displacements(s, k, c, 0.0, 1.0)};
        int order = 0;
        const double tol = std::min(1e-5, 1e-10 * std::max(1.0, k));
        double rho = kNotComputed;
        for (const auto& r : recurrence_roots(seqs, tol, order))
          rho = std::isfinite(rho) ? std::max(rho, std::abs(r)) : std::abs(r);
        p.abs_R = rho;
      } catch (const std::exception&) {
        p.abs_R = kNotComputed;
      }
      out.push_back(p);
    }
  return out;
}

std::vector<AmplificationCase> amplification_study(const std::vector<std::string>& specs,
                                                   const AmplificationOptions& o) {
  if (specs.empty()) throw InputError("missing --case SPEC (an integrator and its settings)");
  if (o.h_over_T.empty()) throw InputError("--h-over-t: no value");
  if (!(o.damping_ratio >= 0.0 && o.damping_ratio < 1.0))
    throw InputError("--damping must be in [0, 1) (the oscillator's damping ratio)");
  std::vector<AmplificationCase> cases;
  for (const std::string& spec : specs)
    for (const Case& k : expand_case(spec, IntegratorSettings{})) {
      AmplificationCase c = measure_amplification(k.settings, o.h_over_T, o.damping_ratio);
      c.spec = spec;
      if (o.region > 0.0 && c.refused.empty())
        c.region = measure_region(k.settings, o.region, o.region_points);
      cases.push_back(std::move(c));
    }
  const fs::path dir =
      o.out_dir.empty() ? fs::path("out/study-amplification") : fs::path(o.out_dir);
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw InputError("--out " + dir.string() + ": cannot create the folder: " + ec.message());
  std::ostringstream md;
  md << "# Amplification of the integrators (evas study amplification)\n\n"
     << "Oscillator q'' + 2 zeta omega q' + omega^2 q = 0, T = 2 pi / omega = 1 s, zeta = "
     << o.damping_ratio
     << "; fixed steps h; spectral radius, algorithmic damping ratio and relative period "
        "error from the recurrence the displacements obey (docs/study.md).\n\n"
     << "| case | settings | stable to h/T | rho at the largest h/T | file "
        "|\n|---|---|---|---|---|\n";
  std::ostringstream gp[3];
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const AmplificationCase& c = cases[k];
    const fs::path sub = dir / ("case" + std::to_string(k));
    if (!c.refused.empty()) {
      md << "| " << k << " | " << c.label << " | not measured: " << c.refused << " | | |\n";
      continue;
    }
    fs::create_directories(sub, ec);
    std::ofstream f(sub / "amplification.csv");
    f << "h_over_T,spectral_radius,damping_ratio,period_error,order,note\n";
    double stable_to = kNotComputed;
    bool unstable = false;
    for (const AmplificationPoint& p : c.points) {
      f << field(p.h_over_T) << "," << field(p.spectral_radius) << "," << field(p.damping_ratio)
        << "," << field(p.period_error) << "," << p.order << ","
        << (p.note.find(',') != std::string::npos ? "\"" + p.note + "\"" : p.note) << "\n";
      if (!unstable && std::isfinite(p.spectral_radius) && p.spectral_radius <= 1.0 + 1e-9)
        stable_to = p.h_over_T;
      else
        unstable = true;
    }
    if (!f) throw InputError((sub / "amplification.csv").string() + ": cannot write");
    if (!c.region.empty()) write_region(sub, c, o.plot);
    md << "| " << k << " | " << c.label << " | "
       << (unstable ? field(stable_to) : "all (" + field(c.points.back().h_over_T) + ")") << " | "
       << field(c.points.back().spectral_radius) << " | case" << k << "/amplification.csv |\n";
    // gnuplot's eight colours repeat from the ninth case on: a dash and a
    // point type of their own tell those cases apart
    const int round = static_cast<int>(k / 8);
    const int point_type[] = {7, 5, 9, 11, 13};
    for (int panel = 0; panel < 3; ++panel)
      gp[panel] << (gp[panel].tellp() > 0 ? ", " : "plot ")
                << gp_quote("case" + std::to_string(k) + "/amplification.csv")
                << " using 1:" << panel + 2 << " with linespoints lw 2 dt " << round % 5 + 1
                << " pt " << point_type[round % 5] << " ps " << (round > 0 ? 0.8 : 0.5) << " title "
                << gp_quote(c.label);
  }
  {
    std::ofstream f(dir / "amplification.md");
    f << md.str();
  }
  if (o.plot && gp[0].tellp() > 0) {
    std::ostringstream s;
    s << gp_terminal(dir / "amplification.png", 1000, 1100)
      << "set datafile separator ','\nset key autotitle columnhead\n"
      << "set multiplot layout 3,1 title "
      << gp_quote("one-step amplification of the linear oscillator (zeta = " +
                  field(o.damping_ratio) + ")")
      << "\nset logscale x\nset grid\nset xlabel 'h/T'\nset key outside right top\n"
      << "set lmargin at screen 0.08\nset rmargin at screen 0.6\n"
      << "set ylabel 'spectral radius rho (clipped at 2.5)'\nset yrange [0:*<2.5]\n"
      << gp[0].str() << "\n"
      << "unset key\nset autoscale y\n"
      << "set xrange [*:0.5]\nset ylabel 'algorithmic damping ratio'\n"
      << gp[1].str() << "\n"
      << "set ylabel 'period error (T_bar - T)/T'\n"
      << gp[2].str() << "\nunset multiplot\n";
    std::ofstream f(dir / "amplification.gp");
    f << s.str();
    f.close();
    if (have_gnuplot()) draw(dir / "amplification.gp", dir / "amplification.png");
  }
  return cases;
}

}  // namespace evas::study
