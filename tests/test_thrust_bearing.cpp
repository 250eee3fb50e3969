// Thrust bearing (elements/thrust_bearing.h).
// References: the clearance behaviour by hand (zero force in the gap,
// F = -k (|d| - gap) sign(d) beyond, for a linear contact law, in both
// directions; contact damping only in contact); the analytic derivatives
// against the element's central finite-difference fallback (Element::
// derivatives_fd) at generic states, inside the smoothing band at both gap
// edges and in the gap; force and moment balance (Newton's third law).
#include <gtest/gtest.h>

#include "elements/thrust_bearing.h"

using namespace evas;

namespace {

// Marker 0 (housing) rotated, marker 1 (shaft) placed at axial position d
// along the bearing axis plus a radial offset, with velocities.
void place(const ThrustBearing&, const Vec3& axis_local, double d, double dv, MarkerMotion* m) {
  m[0].p = Vec3(0.1, -0.2, 0.05);
  m[0].R = rotation_from_vector(Vec3(0.2, -0.4, 0.3));
  m[0].v = Vec3(0.3, -0.1, 0.2);
  m[0].psi = Vec3(0.01, 0.2, -0.1);
  m[0].w = Vec3(1, 2, 3);
  const Vec3 a = m[0].R * axis_local.normalized();
  Vec3 radial = a.cross(Vec3(0.3, 0.5, 0.8)).normalized();
  m[1].p = m[0].p + 0.002 * radial + d * a;
  m[1].v = m[0].v + 0.4 * radial + dv * a;
  m[1].psi = Vec3(0.3, 0.0, -0.2);
  m[1].w = Vec3(0.0, 150.0, 0.0);
  m[1].R = Mat3::Identity();
}

// Max |D - D_fd| relative to max(|D|, scale): near the gap edge the tangent
// stiffness is small, so the contact stiffness k1 is passed as the scale.
double deriv_error(const ThrustBearing& tb, const MarkerMotion* m, double scale = 1.0) {
  Mat D(12, 24), Dfd(12, 24);
  tb.derivatives(0.0, m, D);
  tb.derivatives_fd(0.0, m, Dfd);
  return (D - Dfd).cwiseAbs().maxCoeff() / std::max(scale, D.cwiseAbs().maxCoeff());
}

}  // namespace

TEST(thrust_bearing, ClearanceBehaviourBothDirections) {
  const double gap = 1.5e-4, k = 3e8, c = 2e3;
  const Vec3 axis(1, 0, 0);
  ThrustBearing tb("tb", {0, 1}, ClearanceLaw(ForceLaw::polynomial({k}), gap, 0.0), c, false, axis);
  MarkerMotion m[2];
  double out[3];
  for (double d : {0.0, 1e-4, -1e-4, 1.49e-4, -1.49e-4}) {
    place(tb, axis, d, 0.05, m);
    MarkerLoad l[2];
    tb.evaluate(0.0, m, l);
    EXPECT_LT(l[1].F.norm(), 1e-12) << "d = " << d;  // no force and no damping in the gap
    tb.channel_values(0.0, m, out);
    EXPECT_NEAR(out[1], d, 1e-15);
    EXPECT_NEAR(out[2], gap - std::abs(d), 1e-15);
  }
  double worst = 0;
  for (double d : {2e-4, -2e-4, 5e-4, -5e-4}) {
    place(tb, axis, d, 0.0, m);
    MarkerLoad l[2];
    tb.evaluate(0.0, m, l);
    const Vec3 a = m[0].R * axis;
    const double hand = -k * (std::abs(d) - gap) * (d > 0 ? 1 : -1);
    worst = std::max(worst, (l[1].F - hand * a).norm() / std::abs(hand));
    tb.channel_values(0.0, m, out);
    EXPECT_NEAR(out[0], hand, 1e-9 * std::abs(hand));
    // Contact damping adds -c dv in contact.
    place(tb, axis, d, 0.01, m);
    tb.evaluate(0.0, m, l);
    EXPECT_NEAR(l[1].F.dot(a), hand - c * 0.01, 1e-9 * std::abs(hand));
  }
  std::cout << "contact force vs hand -k(|d|-gap)sign(d): max rel. error " << worst << "\n";
  EXPECT_LT(worst, 1e-12);
  // Damping mode "always" damps in the gap too.
  ThrustBearing tba("tb", {0, 1}, ClearanceLaw(ForceLaw::polynomial({k}), gap, 0.0), c, true, axis);
  place(tba, axis, 0.0, 0.05, m);
  MarkerLoad l[2];
  tba.evaluate(0.0, m, l);
  EXPECT_NEAR(l[1].F.dot(m[0].R * axis), -c * 0.05, 1e-9);
}

TEST(thrust_bearing, DerivativesMatchFiniteDifferences) {
  // derivatives_fd steps positions by 1e-6 m, so the smoothing band here is wide
  // (2e-4 m) to keep its truncation error small; thin bands are checked below
  // with a finer step on the axial law itself.
  const double gap = 1e-4, w = 2e-4;
  const Vec3 axis(0.2, 0.1, 1.0);
  for (int mode = 0; mode < 2; ++mode) {
    ThrustBearing tb("tb", {0, 1}, ClearanceLaw(ForceLaw::polynomial({2e8, 1e11, 1e15}), gap, w),
                     5e3, mode == 1, axis, 1e-5);
    double worst = 0;
    // Generic contact states, near both edges of the smoothing band, and in the gap.
    for (double d : {5e-4, -5e-4, gap + 0.3 * w, -(gap + 0.7 * w), gap + 0.02 * w, gap + 0.98 * w,
                     -(gap + 0.02 * w), 0.5 * gap, -0.2 * gap}) {
      MarkerMotion m[2];
      place(tb, axis, d + 1e-5, 0.07, m);
      const double e = deriv_error(tb, m, 2e8);
      worst = std::max(worst, e);
      EXPECT_LT(e, 1e-4) << "d = " << d << " mode " << mode;
    }
    std::cout << "thrust bearing D vs derivatives_fd (smoothing band, damping "
              << (mode ? "always" : "contact") << "): max rel. error " << worst << "\n";
  }
  // Sharp edge: derivatives exact away from the kink (more than one FD step).
  {
    ThrustBearing tb("tb", {0, 1}, ClearanceLaw(ForceLaw::polynomial({2e8}), gap, 0.0), 5e3, false,
                     axis);
    double worst = 0;
    for (double d : {1.05 * gap, -1.05 * gap, 0.95 * gap, 4e-4}) {
      MarkerMotion m[2];
      place(tb, axis, d, -0.03, m);
      worst = std::max(worst, deriv_error(tb, m));
    }
    std::cout << "thrust bearing D vs derivatives_fd (sharp edge, off the kink): max rel. error "
              << worst << "\n";
    EXPECT_LT(worst, 1e-6);
  }
  // Thin band (2e-6 m): dF/dd and dF/ddv of the axial law against central
  // differences with a 1e-10 m step, across both edges of the band.
  {
    const double wt = 2e-6, k = 2e8;
    ThrustBearing tb("tb", {0, 1}, ClearanceLaw(ForceLaw::polynomial({k}), gap, wt), 5e3, false,
                     axis);
    double worst = 0;
    for (double s : {1.0, -1.0})
      for (double frac : {-0.5, 0.001, 0.1, 0.5, 0.9, 0.999, 1.5}) {
        const double d = s * (gap + frac * wt), dv = 0.2, h = 1e-10;
        double F, Fd, Fv, Fp, Fm, x, y;
        tb.axial(d, dv, F, Fd, Fv);
        tb.axial(d + h, dv, Fp, x, y);
        tb.axial(d - h, dv, Fm, x, y);
        worst = std::max(worst, std::abs(Fd - (Fp - Fm) / (2 * h)) / k);
        tb.axial(d, dv + 1e-3, Fp, x, y);
        tb.axial(d, dv - 1e-3, Fm, x, y);
        worst = std::max(worst, std::abs(Fv - (Fp - Fm) / 2e-3) / k);
      }
    std::cout << "thin-band axial law dF/dd vs FD (h = 1e-10 m): max rel. error " << worst << "\n";
    EXPECT_LT(worst, 1e-3);
  }
}

TEST(thrust_bearing, BalanceAndDeclaration) {
  const ElementType t = thrust_bearing_element_type();
  ParamValues v;
  v.numbers["gap"] = {1e-4};
  v.numbers["stiffness"] = {1e8};
  v.numbers["axis"] = {1, 0, 0};
  v.numbers["smoothing"] = {1e-5};
  v.numbers["damping"] = {100};
  complete_params(t, v, "test");
  auto el = t.make("tb", {0, 1}, v);
  MarkerMotion m[2];
  place(static_cast<const ThrustBearing&>(*el), Vec3::UnitX(), 3e-4, 0.1, m);
  MarkerLoad l[2];
  el->evaluate(0.0, m, l);
  EXPECT_GT(l[1].F.norm(), 1e3);
  EXPECT_LT((l[0].F + l[1].F).norm(), 1e-9);
  const Vec3 Mo = l[0].M + l[1].M + m[0].p.cross(l[0].F) + m[1].p.cross(l[1].F);
  EXPECT_LT(Mo.norm(), 1e-12 * l[1].F.norm());
  EXPECT_EQ(el->channels().size(), 3u);
  // A table law must start at zero force.
  ParamValues bad;
  bad.texts["law"] = "table";
  bad.numbers["table"] = {0.0, 10.0, 1e-4, 1e4};
  complete_params(t, bad, "test");
  EXPECT_THROW(t.make("tb", {0, 1}, bad), InputError);
  for (const auto& p : t.params)
    if (p.kind != ParamSpec::Kind::Text && !p.default_value.empty())
      check_param(p, p.default_value, "defaults");
}
