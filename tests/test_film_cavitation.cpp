// Mass-conserving cavitation of the Reynolds film (journal-bearing `cavitation:
// mass-conserving`, Elrod-Adams' film fraction; elements/film_mass_conserving.cpp):
//   - against Raimondi & Boyd's full-bearing table (ASLE Transactions 1 (1958)
//     159-209, as tabulated in Shigley & Mischke's Mechanical Engineering
//     Design), fed by a narrow axial groove at the largest film: the film
//     reforms at the groove and the answer is the Reynolds condition's, within
//     the 5 % (measured: 2.7 %, and 0.1 % from the Swift-Stieber film
//     with the same groove);
//   - mass conservation: the flow out of the grooves equals the flow out of the
//     ends (the film's flow balance) to round-off, for axial grooves at ambient
//     and supply pressure, an oil hole and a circumferential groove;
//   - a pure squeeze film (no spin: nothing carried into the ruptured zone) is
//     the Swift-Stieber film exactly: the two complementarity problems coincide
//     (Elrod's film fraction theta = (A q)_k / (ed . u) in a ruptured cell,
//     theta <= 1 being Swift-Stieber's A q - g >= 0);
//   - the derivatives (differences at the final partition) against differences
//     of whole solves; bad settings refused; `evas bearing` reports the balance.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "elements/bearing_static.h"
#include "elements/journal_bearing.h"
#include "film_support.h"
#include "model/types.h"

using namespace evas;
using V2 = Eigen::Vector2d;
using film_test::json_number;
using film_test::raimondi_boyd;
using film_test::RBRow;
using film_test::RBTable;
using film_test::run_bearing;

namespace {

constexpr double kOmega = 300.0;  // rad/s

// A bearing of L/D on the Reynolds film with one axial groove (arc deg wide)
// at angle deg of the bearing frame, at the supply pressure.
JournalBearingParams fed(double l_over_d, const std::string& cavitation, double angle,
                         int grid_phi = 72, int grid_axial = 8) {
  JournalBearingParams p;
  p.radius = 0.04;
  p.width = l_over_d * 2.0 * p.radius;
  p.clearance = 4e-5;
  p.viscosity = 0.02;
  p.film = "reynolds";
  p.table = false;
  p.cavitation = cavitation;
  p.grid_phi = grid_phi;
  p.grid_axial = grid_axial;
  p.feed = "axial-grooves";
  p.feed_count = 1;
  p.feed_arc = 5.0;
  p.feed_angle = angle;
  return p;
}

JournalBearing bearing(const JournalBearingParams& p) { return JournalBearing("b", {0, 1}, p); }

}  // namespace

// Fed at the largest film (180 deg + the attitude angle from the load, where
// Raimondi & Boyd's full film begins), the mass-conserving film carries the
// load of their table within 5 % (their Reynolds condition), L/D = 1, 1/2, 1/4,
// eps 0.2 to 0.9, on 144 x 16 cells.
TEST(FilmCavitation, MassConservingMatchesRaimondiBoyd) {
  double worst = 0.0, worst_ss = 0.0;
  for (const RBTable& t : raimondi_boyd()) {
    for (const RBRow& r : t.rows) {
      JournalBearingParams p = fed(t.l_over_d, "swift-stieber", 0.0, 144, 16);
      p.feed = "none";
      const double psi = bearing_at_eccentricity(bearing(p), kOmega, r.eps).attitude_deg;
      p = fed(t.l_over_d, "mass-conserving", 180.0 + psi, 144, 16);
      const BearingOperatingPoint mc = bearing_at_eccentricity(bearing(p), kOmega, r.eps);
      p.cavitation = "swift-stieber";
      const BearingOperatingPoint ss = bearing_at_eccentricity(bearing(p), kOmega, r.eps);
      const double dev = std::abs(mc.sommerfeld / r.S - 1.0);
      const double dss = std::abs(mc.sommerfeld / ss.sommerfeld - 1.0);
      std::printf(
          "L/D %.2f eps %.1f: S %.5g (table %.4g, %+.2f %%; Swift-Stieber with the groove "
          "%+.3f %%), attitude %.2f (table %.2f), film fraction down to %.3f\n",
          t.l_over_d, r.eps, mc.sommerfeld, r.S, 100.0 * (mc.sommerfeld / r.S - 1.0),
          100.0 * (mc.sommerfeld / ss.sommerfeld - 1.0), mc.attitude_deg, r.phi,
          *mc.film_fraction_min);
      worst = std::max(worst, dev);
      worst_ss = std::max(worst_ss, dss);
      EXPECT_LT(dev, 0.05) << "L/D " << t.l_over_d << " eps " << r.eps;
      EXPECT_LT(*mc.film_fraction_min, 1.0);  // the film has ruptured
      EXPECT_NEAR(*mc.feed_flow, *mc.side_flow, 1e-9 * *mc.side_flow);
    }
  }
  std::printf("worst: %.2f %% from the table, %.3f %% from Swift-Stieber\n", 100.0 * worst,
              100.0 * worst_ss);
  EXPECT_LT(worst_ss, 0.01);
}

// Flow out of the feed = flow out of the ends, for each kind of feed.
TEST(FilmCavitation, FilmMassIsConserved) {
  std::vector<JournalBearingParams> feeds;
  feeds.push_back(fed(0.5, "mass-conserving", 180.0));  // one groove, ambient
  JournalBearingParams two = fed(0.5, "mass-conserving", 90.0);
  two.feed_count = 2, two.feed_arc = 20.0, two.supply_pressure = 2e5;
  feeds.push_back(two);
  JournalBearingParams circ = fed(0.5, "mass-conserving", 0.0);
  circ.feed = "circumferential-groove", circ.feed_width = 0.004, circ.supply_pressure = 3e5;
  feeds.push_back(circ);
  JournalBearingParams hole = fed(0.5, "mass-conserving", 160.0);
  hole.feed = "oil-holes", hole.feed_diameter = 0.006, hole.supply_pressure = 1e5;
  feeds.push_back(hole);
  for (const JournalBearingParams& p : feeds) {
    const JournalBearing b = bearing(p);
    for (double eps : {0.3, 0.7, 0.95}) {
      const V2 e = eps * p.clearance * V2(std::cos(0.4), std::sin(0.4));
      const ReynoldsSolution s =
          b.reynolds_film()->solve_mass_conserving(e, V2::Zero(), kOmega, false);
      std::printf(
          "%-22s p_s %.0f Pa, eps %.2f: feed %.6e, ends %.6e m^3/s, theta >= %.3f, %d sets\n",
          p.feed.c_str(), p.supply_pressure, eps, s.feed_flow, s.side_flow, s.theta_min,
          s.active_sets);
      EXPECT_GT(s.side_flow, 0.0);
      EXPECT_NEAR(s.feed_flow, s.side_flow, 1e-10 * s.side_flow) << p.feed << " eps " << eps;
      EXPECT_GE(s.theta_min, 0.0);
      EXPECT_LE(s.theta_min, 1.0);
    }
  }
}

// No spin: the mass-conserving film is Swift-Stieber's with W = ed.
TEST(FilmCavitation, PureSqueezeIsTheSwiftStieberFilm) {
  JournalBearingParams p = fed(0.5, "mass-conserving", 200.0);
  const JournalBearing mc = bearing(p);
  p.cavitation = "swift-stieber";
  const JournalBearing ss = bearing(p);
  for (const auto& st : {V2(0.3, 0.1), V2(-0.5, 0.6), V2(0.1, -0.9)}) {
    const V2 e = st * p.clearance, ed(0.004, -0.002);
    const ReynoldsSolution a = mc.reynolds_film()->solve_mass_conserving(e, ed, 0.0, false);
    const ReynoldsSolution b = ss.reynolds_film()->solve(e, ed, false);
    EXPECT_LT((a.f - b.f).norm(), 1e-10 * b.f.norm()) << st.transpose();
    EXPECT_GT(b.f.norm(), 0.0);
  }
}

// df_de, df_ded and df_dom (differences at the final partition, steps 1e-6)
// against central differences of whole solves (steps 1e-7).
TEST(FilmCavitation, DerivativesMatchDifferences) {
  const JournalBearingParams p = fed(0.5, "mass-conserving", 150.0);
  const JournalBearing b = bearing(p);
  const ReynoldsFilm& film = *b.reynolds_film();
  // steps of 1e-7 (c, m/s, 1e3 rad/s): at 1e-5 m/s the whole solves at the second
  // state cross a change of the partition (df/ded 2.2e-2 off, the derivative one-sided)
  const double c = p.clearance, h = 1e-7;
  for (const auto& st : {V2(0.5, 0.2), V2(-0.3, 0.6), V2(0.1, -0.85)}) {
    const V2 e = st * c, ed(0.002, -0.001);
    const ReynoldsSolution a = film.solve_mass_conserving(e, ed, kOmega, true);
    auto f = [&](const V2& ee, const V2& edd, double w) {
      return film.solve_mass_conserving(ee, edd, w, false).f;
    };
    Eigen::Matrix2d ne, ned;
    for (int j = 0; j < 2; ++j) {
      const V2 d = V2::Unit(j);
      ne.col(j) = (f(e + h * c * d, ed, kOmega) - f(e - h * c * d, ed, kOmega)) / (2 * h * c);
      ned.col(j) = (f(e, ed + h * d, kOmega) - f(e, ed - h * d, kOmega)) / (2 * h);
    }
    const V2 nom = (f(e, ed, kOmega + 1e3 * h) - f(e, ed, kOmega - 1e3 * h)) / (2e3 * h);
    const double re = (a.df_de - ne).norm() / ne.norm(), rd = (a.df_dW - ned).norm() / ned.norm(),
                 ro = (a.df_dom - nom).norm() / nom.norm();
    std::printf("eps (%.2f, %.2f): relative errors df/de %.1e, df/ded %.1e, df/dom %.1e\n", st.x(),
                st.y(), re, rd, ro);
    EXPECT_LT(re, 1e-5);
    EXPECT_LT(rd, 1e-5);
    EXPECT_LT(ro, 1e-5);
  }
}

TEST(FilmCavitation, BadSettingsAreRefused) {
  JournalBearingParams p = fed(0.5, "mass-conserving", 0.0);
  p.feed = "none";  // nothing refills the ruptured film
  try {
    bearing(p);
    ADD_FAILURE() << "a mass-conserving film without a feed was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("needs a feed"), std::string::npos) << e.what();
  }
  p.feed = "circumferential-groove", p.feed_width = 0.004, p.supply_pressure = 0.0;
  EXPECT_THROW(bearing(p), InputError);  // a groove at ambient pressure feeds nothing
  p = fed(0.5, "mass-conserving", 0.0);
  p.table = true;
  EXPECT_THROW(bearing(p), InputError);
  // the W form (Swift-Stieber's) is not this film's
  EXPECT_THROW(bearing(fed(0.5, "mass-conserving", 0.0))
                   .reynolds_film()
                   ->solve(V2(1e-5, 0.0), V2(0.0, 0.01), false),
               InputError);
}

// evas bearing: the flow balance and the film fraction in the JSON.
TEST(FilmCavitation, BearingCommand) {
  int code = -1;
  const std::string js = run_bearing(
      "--radius 0.04 --width 0.04 --clearance 4e-5 --viscosity 0.02 --speed 3000 --load 5000 "
      "--film reynolds --cavitation mass-conserving --feed axial-grooves --feed-count 1 "
      "--feed-angle 200 --json",
      code);
  ASSERT_EQ(code, 0) << js;
  const double side = json_number(js, "side_flow"), feed = json_number(js, "feed_flow");
  EXPECT_NEAR(feed, side, 1e-8 * side) << js;
  EXPECT_GT(json_number(js, "film_fraction_min"), 0.0);
  EXPECT_LT(json_number(js, "film_fraction_min"), 1.0);
  EXPECT_NEAR(json_number(js, "load"), 5000.0, 1e-6 * 5000.0) << js;
}
