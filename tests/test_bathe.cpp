// The bathe integrator (integrators/bathe.cpp): the rho_inf-Bathe composite
// method (G. Noh, K.-J. Bathe, Computers & Structures 212 (2019) 299-310)
// against its amplification matrix, its spectral radius at infinity, the
// trapezoidal rule it becomes at rho_inf = 1, and on the paper's engine.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <complex>
#include <limits>

#include "amplification_matrix.h"
#include "engine_compare.h"
#include "integrators/settings.h"
#include "run_faults_support.h"
#include "study/amplification.h"

using namespace evas;
using namespace run_faults;
using amplification_matrix::spectral_radius;

namespace {

constexpr double kPi = 3.141592653589793;

// The method's amplification matrix on q'' + omega^2 q = 0, state (q, h v,
// h^2 a), W = omega h, written from its definition (Noh & Bathe 2019, eqs. for
// the trapezoidal first sub-step over gamma h and the second sub-step with q0,
// q1, q2): each column is one step from a unit state.
Eigen::Matrix3d bathe_matrix(double W, double rho) {
  const double g = rho >= 1.0 ? 0.5 : (2.0 - std::sqrt(2.0 + 2.0 * rho)) / (1.0 - rho);
  const double q1 = (rho + 1.0) / (2.0 * g * (rho - 1.0) + 4.0);
  const double q0 = (g - 1.0) * q1 + 0.5, q2 = -g * q1 + 0.5;
  const double w2 = W * W;
  Eigen::Matrix3d A;
  for (int j = 0; j < 3; ++j) {
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    x[j] = 1.0;
    const double u = x[0], v = x[1], a = x[2];
    const double um = (u + g * v + 0.25 * g * g * a) / (1.0 + 0.25 * w2 * g * g);
    const double am = -w2 * um, vm = v + 0.5 * g * (a + am);
    const double vb = v + q0 * a + q1 * am;
    const double u1 = (u + q0 * v + q1 * vm + q2 * vb) / (1.0 + q2 * q2 * w2);
    const double a1 = -w2 * u1;
    A.col(j) << u1, vb + q2 * a1, a1;
  }
  return A;
}

IntegratorSettings bathe(double rho) {
  IntegratorSettings s;
  s.name = "bathe";
  s.rho_inf = rho;
  return s;
}

}  // namespace

// The measured spectral radius against the matrix at h/T from 0.01 to 100,
// the damping ratio and period error of the principal roots at h/T = 0.1, and
// rho -> rho_inf as h/T grows (the property the method is named for).
TEST(Bathe, AmplificationAgainstItsMatrix) {
  const std::vector<double> ht = {0.01, 0.1, 1.0, 10.0, 100.0, 1e4};
  for (double r : {0.0, 0.3, 0.6, 1.0}) {
    SCOPED_TRACE(r);
    const study::AmplificationCase c = study::measure_amplification(bathe(r), ht, 0.0);
    ASSERT_TRUE(c.refused.empty()) << c.refused;
    ASSERT_EQ(c.points.size(), ht.size());
    for (std::size_t k = 0; k + 1 < ht.size(); ++k) {
      const double exact = spectral_radius(bathe_matrix(2 * kPi * ht[k], r));
      EXPECT_NEAR(c.points[k].spectral_radius, exact, 1e-7) << ht[k];
      EXPECT_LE(c.points[k].spectral_radius, 1.0 + 1e-9) << ht[k];  // unconditionally stable
    }
    // (the matrix's: 7.7e-5 above rho_inf = 0 at h/T = 1e4, falling like T/h;
    // a radius that small is measured to about 1e-5)
    EXPECT_NEAR(c.points.back().spectral_radius, r, 2e-4);
    const double W = 2 * kPi * 0.1;
    const auto root = amplification_matrix::principal_root_figures(bathe_matrix(W, r), W);
    EXPECT_NEAR(c.points[1].damping_ratio, root.damping_ratio, 1e-8);
    EXPECT_NEAR(c.points[1].period_error, root.period_error, 1e-8);
    if (r == 1.0) {
      // two trapezoidal steps of h/2: Omega_bar = 2 * 2 atan(Omega / 4), no damping
      EXPECT_NEAR(c.points[1].period_error, W / (4 * std::atan(W / 4)) - 1, 1e-9);
      EXPECT_NEAR(c.points[1].damping_ratio, 0.0, 1e-9);
    }
  }
}

TEST(Bathe, RefusesWhatItDoesNotOffer) {
  TempFolder tmp;
  const std::string scene =
      (fs::path(EVAS_SOURCE_DIR) / "validation" / "engine" / "engine.yaml").string();
  for (const std::string bad : {"step_control=adaptive", "iteration=fixed-point"}) {
    const fs::path out = tmp.path() / bad.substr(0, bad.find('='));
    const Outcome o = run_evas({"run", scene, "--param", "time.end=0.001", "--integrator", "bathe",
                                "--set", "step=5e-6", "--set", bad, "--out", out.string()},
                               out.string() + ".log");
    EXPECT_NE(o.code, 0) << bad;
    EXPECT_NE(o.log.find("bathe: " + bad.substr(0, bad.find('='))), std::string::npos) << o.log;
  }
}

// The paper's engine (validation/engine/engine.yaml, Case 1) to t = 0.01 s at
// h = 5 us, rho_inf 0 and 0.8: the main bearing loads within 1 % of their
// swing of IDA's at rtol 1e-7.
TEST(Bathe, RunsThePapersEngine) {
  TempFolder tmp;
  const auto ref = engine_compare::run_engine_reference(tmp.path() / "ida");
  ASSERT_EQ(ref.code, 0) << ref.log;
  for (const std::string rho : {"0", "0.8"}) {
    const auto b = engine_compare::run_engine_briefly(
        tmp.path() / ("bathe" + rho),
        {"--integrator", "bathe", "--set", "step=5e-6", "--set", "rho_inf=" + rho});
    ASSERT_EQ(b.code, 0) << b.log;
    engine_compare::expect_main_bearings_within(ref.columns, b.columns, 0.01, "rho_inf " + rho);
  }
}
