// Order spectrum over whole 720-deg cycles: a synthetic signal made of known
// engine orders (0.5, 1, 2, 4 and a mean) is recovered exactly (the orders are
// integer harmonics of the cycle, so there is no leakage), a start-up transient
// before the analysed cycles is ignored, and bad grids are rejected.
#include <gtest/gtest.h>

#include <cmath>

#include "model/types.h"
#include "post/order_spectrum.h"

using namespace evas;

namespace {
double component(const OrderSpectrum& s, double order, double* phase = nullptr) {
  for (std::size_t i = 0; i < s.order.size(); ++i)
    if (std::abs(s.order[i] - order) < 1e-12) {
      if (phase) *phase = s.phase[i];
      return s.amplitude[i];
    }
  ADD_FAILURE() << "order " << order << " missing";
  return 0.0;
}
}  // namespace

TEST(OrderSpectrum, RecoversKnownOrdersExactly) {
  std::vector<double> th, y;
  const double step = 2.0;             // deg
  for (int i = 0; i < 5 * 360; ++i) {  // 5 cycles of 720 deg
    const double t = 100.0 + i * step, r = t * M_PI / 180.0;
    double v = 3.0 + 5.0 * std::cos(0.5 * r + 0.3) + 2.0 * std::cos(1.0 * r - 1.0) +
               7.0 * std::cos(2.0 * r + 0.7) + 0.25 * std::cos(4.0 * r);
    if (i < 360) v += 50.0 * std::exp(-i / 40.0);  // transient in the first cycle only
    th.push_back(t);
    y.push_back(v);
  }
  const OrderSpectrum s = order_spectrum(th, y, 4, 720.0, 10.0);
  EXPECT_EQ(s.cycles, 4);
  EXPECT_NEAR(s.order[1], 0.5, 1e-15);
  double ph = 0;
  EXPECT_NEAR(component(s, 0.0), 3.0, 1e-12);
  EXPECT_NEAR(component(s, 0.5, &ph), 5.0, 1e-12);
  EXPECT_NEAR(std::remainder(ph - 0.3, 2 * M_PI), 0.0, 1e-12);
  EXPECT_NEAR(component(s, 1.0), 2.0, 1e-12);
  EXPECT_NEAR(component(s, 2.0, &ph), 7.0, 1e-12);
  EXPECT_NEAR(std::remainder(ph - 0.7, 2 * M_PI), 0.0, 1e-12);
  EXPECT_NEAR(component(s, 4.0), 0.25, 1e-12);
  EXPECT_NEAR(component(s, 1.5), 0.0, 1e-12);
  EXPECT_NEAR(component(s, 3.0), 0.0, 1e-12);
  EXPECT_NEAR(s.order.back(), 10.0, 1e-12);
  // All five cycles: the transient leaks into every order.
  const OrderSpectrum all = order_spectrum(th, y);
  EXPECT_EQ(all.cycles, 5);
  EXPECT_GT(std::abs(component(all, 1.5)), 1e-3);
  // Which cycles were used, as the commands print it: the last 4 of 5 start
  // one cycle (720 deg) after the record's first angle, 100 deg.
  EXPECT_EQ(s.available, 5);
  EXPECT_NEAR(s.first_angle, 820.0, 1e-12);
  EXPECT_NEAR(s.last_angle, 100.0 + (5 * 360 - 1) * step, 1e-12);
  EXPECT_EQ(cycles_used(s), "the last 4 of 5 whole 720-deg cycles (crank angle 820 to 3698 deg)");
  const OrderSpectrum last = order_spectrum(th, y, 1);
  EXPECT_EQ(cycles_used(last),
            "the last 1 of 5 whole 720-deg cycles (crank angle 2980 to 3698 deg)");
  // one cycle (evas periodic's record): the record's one cycle
  const std::vector<double> th1(th.end() - 360, th.end()), y1(y.end() - 360, y.end());
  EXPECT_EQ(cycles_used(order_spectrum(th1, y1)),
            "the record's one whole 720-deg cycle (crank angle 2980 to 3698 deg)");
}

TEST(OrderSpectrum, RejectsBadGrids) {
  std::vector<double> th = {0, 1, 2.5, 3}, y = {0, 0, 0, 0};
  EXPECT_THROW(order_spectrum(th, y), InputError);  // not uniform
  th.clear();
  y.clear();
  for (int i = 0; i < 1000; ++i) {
    th.push_back(i * 0.7);  // 0.7 deg does not divide 720
    y.push_back(0);
  }
  EXPECT_THROW(order_spectrum(th, y), InputError);
  th.resize(100);
  y.resize(100);
  for (int i = 0; i < 100; ++i) th[i] = i * 1.0;  // less than one cycle
  EXPECT_THROW(order_spectrum(th, y), InputError);
}
