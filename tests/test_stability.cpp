// Numerical stability at the extremes, on one undamped elastic mode
// (qdd + w^2 q = 0) run through the whole stack:
//  - linear acceleration (Newmark beta = 1/6, gamma = 1/2) is conditionally
//    stable: bounded for h w < 2 sqrt(3), growing beyond (references.md s. 6;
//    Newmark 1959; Hughes, The Finite Element Method, s. 9.1);
//  - generalised-alpha is unconditionally stable and its spectral radius at
//    h w -> infinity is the user's rho_inf (Chung & Hulbert 1993).
#include <gtest/gtest.h>

#include <cmath>

#include "integrators/integrator.h"
#include "random_body.h"
#include "solver/system.h"

using namespace evas;

namespace {

// Amplitude history |(q, v/w)| at every step of a fixed-step run.
std::vector<double> history(const std::string& name, double w, double h, int steps,
                            double rho = 0.8) {
  auto body = std::make_shared<ModalBody>(test_bodies::random_body(8, 1, 5, false));
  body->eigenvalues[0] = w * w;
  body->damping[0] = 0.0;
  Model model;
  model.add_body("b", body, Lof::fixed(Vec3::Zero(), Mat3::Identity()));
  model.bodies()[0].q0 = Vec::Constant(1, 1.0);
  System sys(model);
  IntegratorSettings s;
  s.name = name;
  s.step = h;
  s.rho_inf = rho;
  auto integ = make_integrator(name);
  Vec q, v;
  sys.initial_state(q, v);
  integ->init(sys, 0.0, q, v, s);
  std::vector<double> out;
  for (int k = 1; k <= steps; ++k) {
    integ->advance(k * h, true, q, v);
    out.push_back(std::hypot(q[0], v[0] / w));
    if (!std::isfinite(out.back()) || out.back() > 1e12) break;
  }
  return out;
}

}  // namespace

TEST(Stability, LinearAccelerationLimitIsTwoRootThree) {
  const double w = 2 * M_PI * 100.0, limit = 2 * std::sqrt(3.0);
  const auto below = history("linear-acceleration", w, 0.98 * limit / w, 400);
  const auto above = history("linear-acceleration", w, 1.02 * limit / w, 400);
  const double max_below = *std::max_element(below.begin(), below.end());
  std::cout << "h w = 0.98 * 2 sqrt 3: max amplitude " << max_below
            << "; h w = 1.02 * 2 sqrt 3: amplitude " << above.back() << " after " << above.size()
            << " steps\n";
  EXPECT_LT(max_below, 5.0);     // bounded (the Newmark amplitude is not exactly 1 in these units)
  EXPECT_GT(above.back(), 1e3);  // unbounded growth
}

TEST(Stability, GeneralizedAlphaSpectralRadiusAtInfinityIsRhoInf) {
  const double w = 2 * M_PI * 1000.0, h = 1e4 / w;  // h w = 1e4
  for (double rho : {0.0, 0.5, 0.8, 1.0}) {
    const auto a = history("generalized-alpha", w, h, 300, rho);
    ASSERT_EQ(a.size(), 300u);
    // Geometric mean decay per step over a late window (double root -> n rho^n; the
    // window is long enough to make the polynomial factor negligible).
    const double r = rho == 0.0 ? a[299] / a[0] : std::pow(a[299] / a[199], 1.0 / 100.0);
    std::cout << "rho_inf = " << rho << ": measured decay per step " << r << "\n";
    if (rho == 0.0)
      EXPECT_LT(r, 1e-6);
    else
      EXPECT_NEAR(r, rho, 0.02 * rho);
  }
}
