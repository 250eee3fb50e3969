// Radiation efficiency of a baffled piston and the A weighting
// (post/radiation.h).
#include <gtest/gtest.h>

#include <cmath>

#include "model/types.h"
#include "post/radiation.h"

using namespace evas;

namespace {
constexpr double kTwoPi = 6.283185307179586;
// f at which ka = x for a piston of radius a in air (c = 343 m/s)
double f_at(double ka, double a) { return ka * 343.0 / (kTwoPi * a); }
}  // namespace

// Kinsler, Frey, Coppens & Sanders, Fundamentals of Acoustics (4th ed. 2000),
// section 7.5: R_1(2ka) = 1 - J_1(2ka)/(ka). J_1(2) = 0.5767248078 and
// J_1(4) = -0.0660433280 (Abramowitz & Stegun, Table 9.1), so sigma(ka = 1) =
// 0.4232751922 and sigma(ka = 2) = 1.0330216640; the curve's maximum is 1.1325
// near ka = 2.57 (the overshoot of the published curve, Kinsler Fig. 7.5.2).
TEST(Radiation, BaffledPistonAgainstTheBesselFunctionTables) {
  const double a = 0.25;
  EXPECT_NEAR(piston_radiation_efficiency(f_at(1.0, a), a), 0.4232751922, 1e-9);
  EXPECT_NEAR(piston_radiation_efficiency(f_at(2.0, a), a), 1.0330216640, 1e-9);
  double top = 0.0, at = 0.0;
  for (double ka = 1.0; ka < 4.0; ka += 1e-3) {
    const double s = piston_radiation_efficiency(f_at(ka, a), a);
    if (s > top) top = s, at = ka;
  }
  EXPECT_NEAR(top, 1.1325, 5e-4);
  EXPECT_NEAR(at, 2.57, 0.02);
  // large ka: the plane-wave limit ERP assumes
  EXPECT_NEAR(piston_radiation_efficiency(f_at(200.0, a), a), 1.0, 2e-3);
  // small ka: a monopole, (ka)^2 / 2, and the series meets the Bessel form
  for (double ka : {1e-4, 1e-3, 1e-2})
    EXPECT_NEAR(piston_radiation_efficiency(f_at(ka, a), a) / (ka * ka / 2.0), 1.0, ka * ka);
  const double below = piston_radiation_efficiency(f_at(0.02499999, a), a);
  const double above = piston_radiation_efficiency(f_at(0.02500001, a), a);
  EXPECT_NEAR(below / above, std::pow(0.02499999 / 0.02500001, 2), 1e-9);
  EXPECT_EQ(piston_radiation_efficiency(0.0, a), 0.0);
}

// IEC 61672-1:2013, Table 3: the A weighting at the nominal frequencies (to
// 0.1 dB), which the standard computes at the exact base-10 frequencies
// 10^(n/10) Hz (31.5 nominal: 31.62 Hz; 16000 nominal: 15849 Hz).
TEST(Radiation, AWeightingAgainstIec61672) {
  const struct {
    int n;
    double db;
  } table[] = {{10, -70.4}, {15, -39.4}, {18, -26.2}, {20, -19.1}, {24, -8.6}, {27, -3.2},
               {30, 0.0},   {33, 1.2},   {36, 1.0},   {39, -1.1},  {42, -6.6}};
  for (const auto& r : table) {
    const double f = std::pow(10.0, r.n / 10.0);
    EXPECT_NEAR(a_weighting_db(f), r.db, 0.05 + 1e-9) << f << " Hz";
  }
  EXPECT_NEAR(a_weighting_db(1000.0), 0.0, 2e-3);  // normalised at 1 kHz
  EXPECT_TRUE(std::isinf(a_weighting_db(0.0)));
}

TEST(Radiation, ModelTextIsCheckedAndNamed) {
  EXPECT_DOUBLE_EQ(parse_radiation_model("piston:0.2", "--radiation").radius, 0.2);
  for (const char* bad : {"piston:", "piston:-1", "piston:0.2m", "plate:1", "piston:nan"}) {
    try {
      parse_radiation_model(bad, "--radiation");
      ADD_FAILURE() << bad << ": no error";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(std::string("--radiation '") + bad + "'"),
                std::string::npos)
          << e.what();
    }
  }
}
