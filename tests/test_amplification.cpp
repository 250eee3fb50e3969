// `evas study amplification` (study/amplification.h): the one-step
// amplification measured from the integrators against the closed forms.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <complex>
#include <fstream>
#include <sstream>

#include "amplification_matrix.h"
#include "integrators/newmark.h"
#include "integrators/settings.h"
#include "run_faults_support.h"
#include "study/amplification.h"

using namespace evas;
using namespace run_faults;
using amplification_matrix::spectral_radius;

namespace {

constexpr double kPi = 3.141592653589793;

// The generalized-alpha amplification matrix (Chung & Hulbert 1993, eq. 18
// with alpha_m, alpha_f, beta, gamma from rho_inf, eqs. 25-27) of the undamped
// oscillator at Omega = omega h, state (q, h v, h^2 a).
// The same matrix for any four parameters (HHT-alpha: alpha_m = 0; Newmark:
// alpha_m = alpha_f = 0).
Eigen::Matrix3d family_matrix(double W, double am, double af, double b, double g) {
  Eigen::Matrix3d L, R;
  L << 1, 0, -b, 0, 1, -g, W * W * (1 - af), 0, 1 - am;
  R << 1, 1, 0.5 - b, 0, 1, 1 - g, -W * W * af, 0, -am;
  return L.inverse() * R;
}

Eigen::Matrix3d ga_matrix(double W, double r) {
  const double am = (2 * r - 1) / (r + 1), af = r / (r + 1);
  return family_matrix(W, am, af, 0.25 * (1 - am + af) * (1 - am + af), 0.5 - am + af);
}

IntegratorSettings named(const std::string& name, double rho_inf = 0.8) {
  IntegratorSettings s;
  s.name = name;
  s.rho_inf = rho_inf;
  return s;
}

}  // namespace

// Linear acceleration (Newmark beta = 1/6, gamma = 1/2): no algorithmic
// damping, cos(Omega_bar) = 1 - Omega^2 / (2 (1 + Omega^2 / 6)) (Hughes, The
// Finite Element Method, 1987, section 9.3), stable up to h/T = sqrt(3)/pi
// (Omega = 2 sqrt 3), and rho -> 2 + sqrt 3 as h/T grows.
TEST(Amplification, LinearAccelerationAgainstItsClosedForm) {
  const std::vector<double> ht = {0.01, 0.1, 0.3, 0.55, 0.552, 100.0};
  const study::AmplificationCase c =
      study::measure_amplification(named("linear-acceleration"), ht, 0.0);
  ASSERT_TRUE(c.refused.empty()) << c.refused;
  ASSERT_EQ(c.points.size(), ht.size());
  for (std::size_t k = 0; k < 3; ++k) {
    const double W = 2 * kPi * ht[k];
    const double bar = std::acos(1 - W * W / (2 * (1 + W * W / 6)));
    EXPECT_NEAR(c.points[k].spectral_radius, 1.0, 1e-10) << ht[k];
    EXPECT_NEAR(c.points[k].damping_ratio, 0.0, 1e-9) << ht[k];
    EXPECT_NEAR(c.points[k].period_error, W / bar - 1, 1e-9) << ht[k];
    EXPECT_EQ(c.points[k].order, 2);
  }
  // the stability limit sqrt(3)/pi = 0.55133
  EXPECT_LE(c.points[3].spectral_radius, 1.0 + 1e-9);
  EXPECT_GT(c.points[4].spectral_radius, 1.0 + 1e-4);
  EXPECT_NEAR(c.points[5].spectral_radius, 2 + std::sqrt(3.0), 1e-4);
}

// Generalized-alpha at several rho_inf against its amplification matrix: the
// spectral radius (to round-off of the fit) at h/T from 0.01 to 10, the
// damping ratio and period error of the principal roots at h/T = 0.1; rho_inf
// = 1 is the trapezoidal rule: Omega_bar = 2 atan(Omega / 2).
TEST(Amplification, GeneralizedAlphaAgainstItsAmplificationMatrix) {
  const std::vector<double> ht = {0.01, 0.1, 1.0, 10.0};
  for (double r : {0.0, 0.5, 0.8, 1.0}) {
    SCOPED_TRACE(r);
    const study::AmplificationCase c =
        study::measure_amplification(named("generalized-alpha", r), ht, 0.0);
    ASSERT_EQ(c.points.size(), ht.size());
    for (std::size_t k = 0; k < ht.size(); ++k) {
      const double W = 2 * kPi * ht[k];
      EXPECT_NEAR(c.points[k].spectral_radius, spectral_radius(ga_matrix(W, r)), 1e-7) << ht[k];
    }
    const double W = 2 * kPi * 0.1;
    const auto root = amplification_matrix::principal_root_figures(ga_matrix(W, r), W);
    EXPECT_NEAR(c.points[1].damping_ratio, root.damping_ratio, 1e-8);
    EXPECT_NEAR(c.points[1].period_error, root.period_error, 1e-8);
    if (r == 1.0) {
      EXPECT_NEAR(c.points[1].period_error, W / (2 * std::atan(W / 2)) - 1, 1e-9);
    }
  }
}

// The built-in members of the family against the same matrix: HHT-alpha
// (Hilber, Hughes & Taylor 1977: alpha_m = 0, alpha_f = -alpha, gamma = 1/2 -
// alpha, beta = (1 - alpha)^2 / 4; rho at infinity (1 + alpha) / (1 - alpha)),
// Newmark's beta, gamma (average acceleration; gamma = 0.6 with beta = 0.3025
// unconditionally stable, with beta = 1/4 stable to h omega = (gamma/2 -
// beta)^(-1/2), Hughes, The Finite Element Method, section 9.1.2) and the
// central difference (beta = 0: h/T <= 1/pi).
TEST(Amplification, HhtNewmarkAndCentralDifferenceAgainstTheirMatrices) {
  const std::vector<double> ht = {0.01, 0.1, 0.3, 1.0, 10.0};
  struct Member {
    std::string spec;
    double am, af, b, g;
  };
  const double third = 1.0 / 3.0;
  const std::vector<Member> members = {
      {"hht-alpha alpha=-0.3333333333333333", 0, third, (1 + third) * (1 + third) / 4, 0.5 + third},
      {"hht-alpha alpha=-0.1", 0, 0.1, 1.1 * 1.1 / 4, 0.6},
      {"newmark", 0, 0, 0.25, 0.5},
      {"newmark beta=0.3025 gamma=0.6", 0, 0, 0.3025, 0.6},
      {"newmark beta=0.25 gamma=0.6", 0, 0, 0.25, 0.6},
      {"central-difference", 0, 0, 0, 0.5}};
  for (const Member& m : members) {
    SCOPED_TRACE(m.spec);
    IntegratorSettings s;
    std::istringstream words(m.spec);
    words >> s.name;
    for (std::string kv; words >> kv;) apply_setting_assignment(s, kv);
    const study::AmplificationCase c = study::measure_amplification(s, ht, 0.0);
    ASSERT_TRUE(c.refused.empty()) << c.refused;
    ASSERT_EQ(c.points.size(), ht.size());
    for (std::size_t k = 0; k < ht.size(); ++k) {
      const double exact = spectral_radius(family_matrix(2 * kPi * ht[k], m.am, m.af, m.b, m.g));
      // past the limit the growth over the measured steps is fitted, not summed
      if (exact < 1.5) {
        EXPECT_NEAR(c.points[k].spectral_radius, exact, 1e-7 * std::max(1.0, exact)) << ht[k];
      }
    }
  }
  // the limits: central difference h/T = 1/pi, Newmark (1/4, 0.6) 1/(pi sqrt(0.2))
  IntegratorSettings cd;
  cd.name = "central-difference";
  const auto lim = study::measure_amplification(cd, {0.99 / kPi, 1.01 / kPi}, 0.0);
  EXPECT_LE(lim.points[0].spectral_radius, 1 + 1e-9);
  EXPECT_GT(lim.points[1].spectral_radius, 1 + 1e-3);
  EXPECT_DOUBLE_EQ(NewmarkIntegrator::stability_limit(0.25, 0.6), 1 / std::sqrt(0.05));
  EXPECT_DOUBLE_EQ(NewmarkIntegrator::stability_limit(1.0 / 6, 0.5), std::sqrt(12.0));
  EXPECT_TRUE(std::isinf(NewmarkIntegrator::stability_limit(0.25, 0.5)));
}

// Radau IIA (3 stages) on the damped oscillator: its amplification
// eigenvalues are R(h lambda) at the oscillator's eigenvalues lambda = omega
// (-zeta +- i sqrt(1 - zeta^2)), R(z) = (1 + 2z/5 + z^2/20) / (1 - 3z/5 +
// 3z^2/20 - z^3/60) (Hairer & Wanner, Solving ODEs II, section IV.5).
TEST(Amplification, RadauIIAAgainstItsStabilityFunction) {
  const double zeta = 0.1;
  const std::vector<double> ht = {0.05, 0.2, 1.0, 10.0};
  const study::AmplificationCase c = study::measure_amplification(named("radau"), ht, zeta);
  ASSERT_TRUE(c.refused.empty()) << c.refused;
  for (std::size_t k = 0; k < ht.size(); ++k) {
    const double W = 2 * kPi * ht[k];
    const std::complex<double> z = W * std::complex<double>(-zeta, std::sqrt(1 - zeta * zeta));
    const std::complex<double> R =
        (1.0 + 0.4 * z + z * z / 20.0) / (1.0 - 0.6 * z + 0.15 * z * z - z * z * z / 60.0);
    EXPECT_NEAR(c.points[k].spectral_radius, std::abs(R), 1e-8 * std::max(1.0, std::abs(R)))
        << ht[k];
  }
}

// The stability region of Radau IIA measured from its steps against |R(z)|
// of its stability function at every grid point (the real axis, where the
// test problem has a double root, to 1e-5).
TEST(Amplification, RadauIIARegionIsItsStabilityFunction) {
  const std::vector<study::RegionPoint> region = study::measure_region(named("radau"), 6.0, 12);
  ASSERT_EQ(region.size(), 13u * 7u);
  int unstable = 0;
  for (const auto& p : region) {
    const std::complex<double> z(p.re, p.im);
    const double R = std::abs((1.0 + 0.4 * z + z * z / 20.0) /
                              (1.0 - 0.6 * z + 0.15 * z * z - z * z * z / 60.0));
    // (at R's zeros, z = -4 +- 2i, the steps vanish and |R| is resolved to 1e-6)
    EXPECT_NEAR(p.abs_R, R, std::max(1e-6, (p.im == 0.0 ? 1e-5 : 1e-8) * std::max(1.0, R))) << z;
    if (p.re < 0.0) {
      EXPECT_LT(p.abs_R, 1.0) << z;  // A-stable
    }
    unstable += p.abs_R > 1.0;
  }
  EXPECT_GT(unstable, 0);  // its bounded instability region right of the axis
  EXPECT_TRUE(study::measure_region(named("ida"), 6.0, 12).empty());
}

// The command: one CSV per case with the columns, the figure, and ida
// refused with its reason (exit 1 when every case is refused).
TEST(Amplification, CommandWritesTheAtlas) {
  TempFolder tmp;
  const fs::path out = tmp.path() / "amp";
  const Outcome o = run_evas(
      {"study", "amplification", "--case", "generalized-alpha rho_inf=0.5", "--case", "ida",
       "--h-over-t", "1e-2..1e2/9", "--region", "4", "--region-points", "8", "--out", out.string()},
      tmp.path() / "amp.log");
  ASSERT_EQ(o.code, 0) << o.log;
  std::ifstream csv(out / "case0" / "amplification.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header.rfind("h_over_T,spectral_radius,damping_ratio,period_error", 0), 0u) << header;
  int rows = 0;
  for (std::string line; std::getline(csv, line);) ++rows;
  EXPECT_EQ(rows, 9);
  EXPECT_TRUE(fs::exists(out / "amplification.png"));
  EXPECT_TRUE(fs::exists(out / "case0" / "region.png"));
  std::ifstream region(out / "case0" / "region.csv");
  std::getline(region, header);
  EXPECT_EQ(header, "re_z,im_z,abs_R,status");
  EXPECT_NE(o.log.find("ida chooses its own step and order"), std::string::npos) << o.log;
  const Outcome only_ida = run_evas({"study", "amplification", "--case", "ida", "--no-plot",
                                     "--out", (tmp.path() / "ida").string()},
                                    tmp.path() / "ida.log");
  EXPECT_EQ(only_ida.code, 1) << only_ida.log;
  const Outcome bad = run_evas({"study", "amplification", "--case", "generalized-alpha",
                                "--h-over-t", "0,1", "--out", (tmp.path() / "bad").string()},
                               tmp.path() / "bad.log");
  EXPECT_EQ(bad.code, 1);
  EXPECT_NE(bad.log.find("--h-over-t"), std::string::npos) << bad.log;
}

// A gnuplot that fails after creating its output (as the real one does at `set
// output` before an error in the plot) leaves no PNG behind: the figure is
// removed and the failure said, the tables stay.
TEST(Amplification, FailedGnuplotLeavesNoFigure) {
  TempFolder tmp;
  const fs::path bin = tmp.path() / "bin";
  fs::create_directories(bin);
  {
    std::ofstream g(bin / "gnuplot");
    g << "#!/bin/sh\n"
         "for f in \"$@\"; do\n"
         "  out=$(/bin/sed -n \"s/^set output '\\(.*\\)'.*/\\1/p\" \"$f\")\n"
         "  [ -n \"$out\" ] && : > \"$out\"\n"
         "done\n"
         "exit 1\n";
  }
  fs::permissions(bin / "gnuplot", fs::perms::owner_all);
  const char* path = std::getenv("PATH");
  const fs::path out = tmp.path() / "amp";
  const Outcome o = run_evas(
      {"study", "amplification", "--case", "generalized-alpha rho_inf=0.5", "--h-over-t",
       "1e-2..1e2/5", "--region", "4", "--region-points", "6", "--out", out.string()},
      tmp.path() / "amp.log", {"PATH=" + bin.string() + ":" + std::string(path ? path : "")});
  ASSERT_EQ(o.code, 0) << o.log;
  EXPECT_TRUE(fs::exists(out / "case0" / "amplification.csv"));
  EXPECT_TRUE(fs::exists(out / "amplification.gp"));
  EXPECT_FALSE(fs::exists(out / "amplification.png"));
  EXPECT_FALSE(fs::exists(out / "case0" / "region.png"));
  EXPECT_NE(o.log.find("gnuplot failed on"), std::string::npos) << o.log;
  EXPECT_NE(o.log.find("amplification.png not written"), std::string::npos) << o.log;
}
