// Belt element (elements/belt.h, paper Fig. 8).
// References: hand calculations in the belt plane:
//  - three pulleys of equal radius: spans along the centre lines, so
//    F_i = T_B (e_{i->next} + e_{i->prev}) with the unit vectors worked out by hand;
//  - two pulleys of radii r0 = 0.04 m and r1 = 0.09 m at distance d = sqrt(0.1) m:
//    the outer tangent is turned from the centre line (theta = atan(1/3) =
//    0.3217506 rad) by beta = asin((r1 - r0)/d) = asin(0.05/0.3162278) =
//    0.1587802 rad, so the span angles are theta - beta = 0.1629704 rad (0 -> 1)
//    and theta + pi + beta - 2 pi = -2.6610618 rad (1 -> 0), the span length is
//    d cos(beta) and the force on pulley 0 is 2 T_B cos(beta) along the centre line;
//  - tangency of every span to both circles, w.(c_j - c_i) = r_i - r_j, w = u x n;
//  - balance: sum of forces and of moments zero;
//  - analytic derivatives against Element::derivatives_fd.
#include <gtest/gtest.h>

#include <cmath>

#include "elements/belt.h"

using namespace evas;

TEST(belt, ThreeEqualPulleysHandCalculation) {
  const double T = 800.0, r = 0.05;
  Belt belt("belt", {0, 1, 2}, T, {r, r, r}, Vec3::UnitZ());
  MarkerMotion m[3];
  m[0].p = Vec3(0.0, 0.0, 0.0);
  m[1].p = Vec3(0.3, 0.0, 0.0);
  m[2].p = Vec3(0.1, 0.25, 0.0);
  MarkerLoad l[3];
  belt.evaluate(0.0, m, l);
  // Hand: e01 = (1, 0); e02 = (0.1, 0.25)/0.2692582 = (0.3713907, 0.9284767);
  // e12 = (-0.2, 0.25)/0.3201562 = (-0.6246950, 0.7808688).
  const Vec3 F0(1.3713907, 0.9284767, 0), F1(-1.6246950, 0.7808688, 0),
      F2(0.2533043, -1.7093455, 0);
  const double err =
      std::max({(l[0].F - T * F0).norm(), (l[1].F - T * F1).norm(), (l[2].F - T * F2).norm()}) / T;
  std::cout << "three equal pulleys: max |F - hand| / T_B = " << err << "\n";
  EXPECT_LT(err, 1e-6);
  for (auto& x : l) EXPECT_EQ(x.M.norm(), 0.0);
  // Channels: in-plane components in the automatic frame (x_ref = x for n = z).
  std::vector<double> out(belt.channels().size());
  belt.channel_values(0.0, m, out.data());
  EXPECT_NEAR(out[0], T * F0.x(), 1e-3);
  EXPECT_NEAR(out[3], T * F1.y(), 1e-3);
  EXPECT_NEAR(out[6], 0.0, 1e-12);                       // span 0 angle: along +x
  EXPECT_NEAR(out[7], 0.3, 1e-12);                       // span 0 length = centre distance
  EXPECT_NEAR(out[8], std::atan2(0.25, -0.2), 1e-12);    // span 1 angle
  EXPECT_NEAR(out[10], std::atan2(-0.25, -0.1), 1e-12);  // span 2 angle
}

TEST(belt, UnequalRadiiTangentGeometry) {
  const double T = 500.0, r0 = 0.04, r1 = 0.09;
  Belt belt("belt", {0, 1}, T, {r0, r1}, Vec3::UnitZ());
  MarkerMotion m[2];
  m[0].p = Vec3(0.0, 0.0, 0.0);
  m[1].p = Vec3(0.3, 0.1, 0.0);
  const double d = std::sqrt(0.1), theta = std::atan2(0.1, 0.3);
  const double beta = std::asin((r1 - r0) / d);  // hand: 0.1587802 rad
  EXPECT_NEAR(beta, 0.1587802, 1e-7);
  std::vector<double> out(belt.channels().size());
  belt.channel_values(0.0, m, out.data());
  const double a01 = out[4], a10 = out[6];
  const double hand01 = theta - beta, hand10 = std::remainder(theta + M_PI + beta, 2 * M_PI);
  std::cout << "unequal radii: span angle 0->1 " << a01 << " (hand " << hand01 << "), 1->0 " << a10
            << " (hand " << hand10 << ")\n";
  EXPECT_NEAR(a01, hand01, 1e-12);
  EXPECT_NEAR(a10, hand10, 1e-12);
  EXPECT_NEAR(a01, 0.1629704, 1e-7);
  EXPECT_NEAR(a10, -2.6610618, 1e-7);
  EXPECT_NEAR(out[5], d * std::cos(beta), 1e-12);
  MarkerLoad l[2];
  belt.evaluate(0.0, m, l);
  const Vec3 hand = 2 * T * std::cos(beta) * Vec3(std::cos(theta), std::sin(theta), 0);
  EXPECT_LT((l[0].F - hand).norm(), 1e-9 * T);
  EXPECT_LT((l[1].F + hand).norm(), 1e-9 * T);
}

namespace {

// Crank (large), alternator, back-side idler (negative radius), water pump, with
// small out-of-plane offsets and a rotated frame marker.
void layout(MarkerMotion* m) {
  m[0].p = Vec3(0.0, 0.0, 0.001);
  m[1].p = Vec3(0.25, 0.28, -0.002);
  m[2].p = Vec3(0.05, 0.22, 0.0);
  m[3].p = Vec3(-0.12, 0.3, 0.003);
  for (int i = 0; i < 4; ++i) {
    m[i].v = Vec3(0.1 * i, -0.2, 0.3);
    m[i].psi = Vec3(0.01, 0.02 * i, 0.5);
    m[i].w = Vec3(0, 0, 100.0 * i);
  }
  m[1].R = rotation_from_vector(Vec3(0.0, 0.0, 0.7));  // rotation about the plane normal
}

}  // namespace

TEST(belt, TangencyBalanceAndDerivatives) {
  const double T = 1200.0;
  const std::vector<double> radii = {0.09, 0.035, -0.03, 0.05};
  Belt belt("belt", {0, 1, 2, 3}, T, radii, Vec3::UnitZ(), {0, 1, 2, 3}, 1);
  MarkerMotion m[4];
  layout(m);
  MarkerLoad l[4];
  belt.evaluate(0.0, m, l);
  Vec3 Fs = Vec3::Zero(), Ms = Vec3::Zero();
  for (int i = 0; i < 4; ++i) {
    Fs += l[i].F;
    // in-plane moment balance (about z)
    Ms += Vec3(m[i].p.x(), m[i].p.y(), 0).cross(l[i].F) + l[i].M;
  }
  EXPECT_LT(Fs.norm(), 1e-9 * T);
  EXPECT_LT(std::abs(Ms.z()), 1e-9 * T);
  double tang = 0;
  for (int s = 0; s < 4; ++s) {
    const int i = s, j = (s + 1) % 4;
    Vec3 u;
    double L;
    belt.span(Vec3::UnitZ(), m[i].p, m[j].p, radii[i], radii[j], u, L, nullptr);
    const Vec3 w = u.cross(Vec3::UnitZ());
    const Vec3 dc = m[j].p - m[i].p;
    tang = std::max(tang, std::abs(w.dot(dc) - (radii[i] - radii[j])));
    EXPECT_GT(u.dot(dc), 0.0);
    EXPECT_NEAR(u.norm(), 1.0, 1e-14);
    EXPECT_NEAR(u.z(), 0.0, 1e-14);
  }
  std::cout << "tangency residual max |w.(cj-ci) - (ri-rj)| = " << tang << " m\n";
  EXPECT_LT(tang, 1e-14);
  Mat D(24, 48), Dfd(24, 48);
  belt.derivatives(0.0, m, D);
  belt.derivatives_fd(0.0, m, Dfd);
  const double err = (D - Dfd).cwiseAbs().maxCoeff() / D.cwiseAbs().maxCoeff();
  std::cout << "belt D vs derivatives_fd: max rel. error " << err << "\n";
  EXPECT_LT(err, 1e-6);
  // A tilted plane, reverse order and a reference axis.
  Belt tilted("belt", {0, 1, 2, 3}, T, {-0.09, -0.035, 0.03, -0.05}, Vec3(0.1, -0.05, 1.0),
              {3, 2, 1, 0}, -1, Vec3(1, 0, 0));
  tilted.derivatives(0.0, m, D);
  tilted.derivatives_fd(0.0, m, Dfd);
  const double err2 = (D - Dfd).cwiseAbs().maxCoeff() / D.cwiseAbs().maxCoeff();
  std::cout << "belt D vs derivatives_fd (tilted plane): max rel. error " << err2 << "\n";
  EXPECT_LT(err2, 1e-6);
}

TEST(belt, DeclarationAndErrors) {
  const ElementType t = belt_element_type();
  EXPECT_EQ(t.num_markers, 0);
  ParamValues v;
  v.numbers["tension"] = {300};
  v.numbers["radii"] = {0.05, 0.05, 0.05};
  v.numbers["normal"] = {0, 0, 1};
  complete_params(t, v, "test");
  auto el = t.make("b", {4, 5, 6}, v);
  EXPECT_EQ(el->channels().size(), 12u);
  ParamValues bad = v;
  bad.numbers["radii"] = {0.05, 0.05};
  EXPECT_THROW(t.make("b", {4, 5, 6}, bad), InputError);
  bad = v;
  bad.numbers["order"] = {0, 0, 1};
  EXPECT_THROW(t.make("b", {4, 5, 6}, bad), InputError);
  ParamValues missing;
  EXPECT_THROW(complete_params(t, missing, "test"), InputError);
  // Overlapping pulleys: no tangent, a RunError naming the element.
  Belt belt("bad-belt", {0, 1}, 100, {0.01, 0.2}, Vec3::UnitZ());
  MarkerMotion m[2];
  m[1].p = Vec3(0.1, 0, 0);
  MarkerLoad l[2];
  try {
    belt.evaluate(0.0, m, l);
    FAIL();
  } catch (const RunError& e) {
    EXPECT_NE(std::string(e.what()).find("bad-belt"), std::string::npos);
  }
}
