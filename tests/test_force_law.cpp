// Force-deflection laws (elements/force_law.h).
// References: hand-evaluated polynomials; the monotone cubic Hermite scheme of
// F. N. Fritsch and R. E. Carlson, "Monotone piecewise cubic interpolation",
// SIAM J. Numer. Anal. 17 (1980) 238-246, with the interior slopes of
// Fritsch and Butland (as in MATLAB's pchip): exact for linear data, monotone
// for monotone data, no overshoot at a local extremum; derivatives against
// central finite differences.
#include <gtest/gtest.h>

#include <cmath>

#include "elements/force_law.h"

using namespace evas;

namespace {

double fd_slope(const ForceLaw& f, double d, double h) {
  return (f.value(d + h) - f.value(d - h)) / (2 * h);
}

double fd_slope(const ClearanceLaw& g, double d, double h) {
  double gp, gm, s;
  g.eval(d + h, gp, s);
  g.eval(d - h, gm, s);
  return (gp - gm) / (2 * h);
}

}  // namespace

TEST(force_law, PolynomialValueAndSlope) {
  const ForceLaw f = ForceLaw::polynomial({1e6, -2e8, 3e10});
  const double d = 2e-3;
  // Hand: 1e6*2e-3 - 2e8*4e-6 + 3e10*8e-9 = 2000 - 800 + 240 = 1440 N
  EXPECT_NEAR(f.value(d), 1440.0, 1e-9);
  // Slope: 1e6 - 2*2e8*2e-3 + 3*3e10*4e-6 = 1e6 - 8e5 + 3.6e5 = 5.6e5 N/m
  EXPECT_NEAR(f.slope(d), 5.6e5, 1e-6);
  EXPECT_EQ(f.value(0.0), 0.0);
  double worst = 0;
  for (double x = -5e-3; x <= 5e-3; x += 3.7e-4)
    worst = std::max(worst, std::abs(f.slope(x) - fd_slope(f, x, 1e-7)) / 1e6);
  std::cout << "polynomial slope vs FD, max rel. error " << worst << "\n";
  EXPECT_LT(worst, 1e-7);
  EXPECT_EQ(ForceLaw().value(1.0), 0.0);
}

TEST(force_law, LinearTable) {
  const ForceLaw f =
      ForceLaw::table({-1e-3, 0.0, 2e-3}, {-500.0, 0.0, 3000.0}, ForceLaw::Interp::Linear);
  EXPECT_NEAR(f.value(-1e-3), -500.0, 1e-9);
  EXPECT_NEAR(f.value(1e-3), 1500.0, 1e-9);
  EXPECT_NEAR(f.slope(1e-3), 1.5e6, 1e-6);
  // Linear extrapolation with the end segments' slopes.
  EXPECT_NEAR(f.value(3e-3), 3000.0 + 1.5e6 * 1e-3, 1e-9);
  EXPECT_NEAR(f.value(-2e-3), -500.0 - 5e5 * 1e-3, 1e-9);
  EXPECT_NEAR(f.slope(-2e-3), 5e5, 1e-6);
}

TEST(force_law, PchipIsExactOnLinesMonotoneAndSmooth) {
  // Data on a line: every secant equals the slope, so the interpolant is the line.
  const ForceLaw line =
      ForceLaw::table({-2e-3, -5e-4, 1e-3, 4e-3}, {-400, -100, 200, 800}, ForceLaw::Interp::Pchip);
  for (double x = -3e-3; x <= 5e-3; x += 1.3e-4) {
    EXPECT_NEAR(line.value(x), 2e5 * x, 1e-9);
    EXPECT_NEAR(line.slope(x), 2e5, 1e-6);
  }
  // A progressive rubber-like mount curve (stiffening at both ends).
  const std::vector<double> d = {-4e-3, -2e-3, -1e-3, 0.0, 1e-3, 2e-3, 4e-3};
  const std::vector<double> F = {-4000, -1200, -500, 0, 500, 1200, 4000};
  const ForceLaw f = ForceLaw::table(d, F, ForceLaw::Interp::Pchip);
  for (std::size_t i = 0; i < d.size(); ++i) EXPECT_NEAR(f.value(d[i]), F[i], 1e-9);
  double prev = -1e300, worst = 0, jump = 0;
  for (double x = -6e-3; x <= 6e-3; x += 1.1e-5) {
    const double v = f.value(x);
    EXPECT_GE(v, prev);  // monotone
    prev = v;
    worst = std::max(worst, std::abs(f.slope(x) - fd_slope(f, x, 1e-8)) / 1e6);
  }
  for (double xi : d) jump = std::max(jump, std::abs(f.slope(xi + 1e-12) - f.slope(xi - 1e-12)));
  std::cout << "pchip slope vs FD, max rel. error " << worst << "; slope jump at nodes " << jump
            << " N/m\n";
  EXPECT_LT(worst, 1e-5);
  EXPECT_LT(jump, 1e-2);  // C1 (differences of 1e-12 m times ~1e9 N/m^2 curvature)
  // Linear extrapolation with the end slopes = end secants.
  EXPECT_NEAR(f.slope(5e-3), (4000.0 - 1200.0) / 2e-3, 1e-6);
  EXPECT_NEAR(f.value(5e-3), 4000.0 + 1.4e6 * 1e-3, 1e-6);
  // Local extremum: no overshoot beyond the data.
  const ForceLaw bump =
      ForceLaw::table({0, 1, 2, 3}, {0, 1, 1, 0}, ForceLaw::Interp::Pchip, "bump");
  for (double x = 0; x <= 3; x += 0.01) {
    EXPECT_LE(bump.value(x), 1.0 + 1e-12);
    EXPECT_GE(bump.value(x), -1e-12);
  }
}

TEST(force_law, TableErrorsNameTheProblem) {
  try {
    ForceLaw::table({0.0, 1e-3, 1e-3}, {0, 1, 2}, ForceLaw::Interp::Linear, "mount 'm1'");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("mount 'm1'"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("increase strictly"), std::string::npos);
  }
  EXPECT_THROW(ForceLaw::table_pairs({0, 0, 1e-3}, ForceLaw::Interp::Linear), InputError);
  EXPECT_THROW(ForceLaw::table({0.0}, {0.0}, ForceLaw::Interp::Linear), InputError);
  EXPECT_THROW(make_force_law("table", {}, {}, "pchip", "x"), InputError);
  EXPECT_THROW(make_force_law("spline", {1}, {}, "pchip", "x"), InputError);
  EXPECT_THROW(make_force_law("polynomial", {1}, {0, 0, 1, 1}, "pchip", "x"), InputError);
  EXPECT_THROW(ClearanceLaw(ForceLaw(), -1e-3, 0.0), InputError);
}

TEST(force_law_clearance, DeadBandSharpAndSmooth) {
  const double gap = 1e-4, k = 2e8;
  const ClearanceLaw sharp(ForceLaw::polynomial({k}), gap, 0.0);
  double g, dg;
  for (double d : {0.0, 5e-5, -5e-5, 0.99e-4, -0.99e-4}) {
    sharp.eval(d, g, dg);
    EXPECT_EQ(g, 0.0);
    EXPECT_EQ(dg, 0.0);
  }
  sharp.eval(1.5e-4, g, dg);
  EXPECT_NEAR(g, k * 0.5e-4, 1e-6);
  EXPECT_EQ(dg, k);
  sharp.eval(-1.5e-4, g, dg);
  EXPECT_NEAR(g, -k * 0.5e-4, 1e-6);
  EXPECT_EQ(dg, k);

  const double w = 2e-5;
  const ClearanceLaw smooth(ForceLaw::polynomial({k, 0.0, 1e16}), gap, w);
  // rho: C1 at both ends of the band, rho <= e.
  double r, dr;
  smooth.smooth(0.0, r, dr);
  EXPECT_EQ(r, 0.0);
  EXPECT_EQ(dr, 0.0);
  smooth.smooth(w * (1 - 1e-12), r, dr);
  EXPECT_NEAR(r, w, 1e-15);
  EXPECT_NEAR(dr, 1.0, 1e-9);
  for (double e = 0; e < w; e += w / 50) {
    smooth.smooth(e, r, dr);
    EXPECT_LE(r, e + 1e-20);
    EXPECT_GE(dr, 0.0);
  }
  // Beyond the band the law is exact; odd symmetry; slope vs FD everywhere incl. the edges.
  const ForceLaw& f = smooth.law();
  smooth.eval(gap + 3 * w, g, dg);
  EXPECT_NEAR(g, f.value(3 * w), 1e-9);
  double worst = 0, chi_worst = 0;
  for (double d = -2.5e-4; d <= 2.5e-4; d += 1.7e-7) {
    double gm, dgm;
    smooth.eval(d, g, dg);
    smooth.eval(-d, gm, dgm);
    EXPECT_NEAR(g, -gm, 1e-9);
    worst = std::max(worst, std::abs(dg - fd_slope(smooth, d, 1e-10)) / k);
    double c, dc, cp, cm, s;
    smooth.contact(d, c, dc);
    smooth.contact(d + 1e-10, cp, s);
    smooth.contact(d - 1e-10, cm, s);
    chi_worst = std::max(chi_worst, std::abs(dc - (cp - cm) / 2e-10) * w);
    EXPECT_GE(c, 0.0);
    EXPECT_LE(c, 1.0);
  }
  std::cout << "clearance slope vs FD (smooth), max rel. error " << worst
            << "; contact fraction slope error (x w) " << chi_worst << "\n";
  EXPECT_LT(worst, 1e-4);
  EXPECT_LT(chi_worst, 1e-4);
}
