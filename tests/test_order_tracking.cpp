// Order tracking of a run-up (post/order_tracking.h) and `evas report` / `evas
// plot` on a run-up of the paper's engine.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "post/order_tracking.h"
#include "run_faults_support.h"

using namespace run_faults;

namespace {

constexpr double kPi = 3.141592653589793;

// A crank accelerating uniformly, w(t) = w0 + a t, sampled every degree: the
// time of angle theta [rad] solves theta = w0 t + a t^2 / 2.
struct Ramp {
  double w0 = 100.0, a = 500.0;
  double time(double theta) const { return (-w0 + std::sqrt(w0 * w0 + 2.0 * a * theta)) / a; }
};

}  // namespace

// y = 0.5 + 3 cos(2 theta) + 1.2 sin(4.5 theta): on the angle grid every
// cycle's orders are exact whatever the speed does; each cycle's mean speed is
// 2 revolutions over its duration, the change within it w(t_last) - w(t_first)
// over that mean (to the one-step differences' accuracy).
TEST(OrderTracking, ExactOrdersAndTheSpeedOfEachCycleOnARamp) {
  const Ramp r;
  std::vector<double> t, th, y;
  for (int k = 0; k < 5 * 720 + 100; ++k) {  // 5 whole cycles and a part
    const double theta = k * kPi / 180.0;
    th.push_back(k);
    t.push_back(r.time(theta));
    y.push_back(0.5 + 3.0 * std::cos(2.0 * theta) + 1.2 * std::sin(4.5 * theta));
  }
  const evas::OrderTrack tr = evas::order_tracking(t, th, y, {0.0, 2.0, 4.5, 1.0});
  ASSERT_EQ(tr.rpm.size(), 5u);
  for (std::size_t c = 0; c < 5; ++c) {
    EXPECT_NEAR(tr.amplitude[c][0], 0.5, 1e-12);
    EXPECT_NEAR(tr.amplitude[c][1], 3.0, 1e-12);
    EXPECT_NEAR(tr.amplitude[c][2], 1.2, 1e-12);
    EXPECT_NEAR(tr.amplitude[c][3], 0.0, 1e-12);
    const double t0 = r.time(4.0 * kPi * c), t1 = r.time(4.0 * kPi * (c + 1));
    EXPECT_NEAR(tr.rpm[c], 120.0 / (t1 - t0), 1e-4 * tr.rpm[c]);
    const double w_first = r.w0 + r.a * t0, w_last = r.w0 + r.a * t1;
    const double mean_w = tr.rpm[c] * 2.0 * kPi / 60.0;
    EXPECT_NEAR(tr.change[c], (w_last - w_first) / mean_w, 2e-3);
    if (c > 0) {
      EXPECT_GT(tr.rpm[c], tr.rpm[c - 1]);
    }
  }
  EXPECT_GT(evas::speed_spread(t, th), 0.02);
  // a constant speed has no spread
  std::vector<double> tc;
  for (double a : th) tc.push_back(a / 6000.0);
  EXPECT_NEAR(evas::speed_spread(tc, th), 0.0, 1e-12);
  EXPECT_THROW(evas::order_tracking(t, th, y, {0.75}), evas::InputError);  // not on the 0.5 grid
}

// The engine run up from 1000 to 2000 rpm in 0.4 s, the speed profile given on
// the command line: `evas report` writes its page with the orders tracked
// against speed and the ERP per cycle (a spectrum over time needs a constant
// speed); `evas plot order` over every cycle says that it pooled a run-up.
TEST(OrderTracking, ReportAndPlotsOfARunUp) {
  TempFolder tmp;
  const std::string engine = std::string(EVAS_SOURCE_DIR) + "/validation/engine/engine.yaml";
  const fs::path run = tmp.path() / "runup";
  const Outcome r =
      run_evas({"run", engine, "--param", "crank.lof.speed_profile=[[0, 104.72], [0.4, 209.44]]",
                "--param", "time.end=0.4", "--out", run.string(), "--quiet"},
               tmp.path() / "run.log");
  ASSERT_EQ(r.code, 0) << r.log;
  const std::string results = (run / "results.h5").string();
  const fs::path page = tmp.path() / "report";
  const Outcome rep =
      run_evas({"report", results, "--out", page.string()}, tmp.path() / "report.log");
  ASSERT_EQ(rep.code, 0) << rep.log;
  for (const char* f : {"index.html", "order_track_main3_fy.png", "erp_track_skin.png"})
    EXPECT_TRUE(fs::exists(page / f)) << f;
  EXPECT_FALSE(fs::exists(page / "erp_spectrum_skin.png"));
  std::ifstream in(page / "index.html");
  const std::string html((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(html.find("a run-up (or run-down)"), std::string::npos);
  // the tracked orders: one row per whole cycle, speeds rising from 1000 to 2000 rpm
  std::ifstream dat(page / "order_track_main3_fy.dat");
  std::vector<double> rpm;
  for (std::string line; std::getline(dat, line) && !line.empty();) rpm.push_back(std::stod(line));
  ASSERT_GE(rpm.size(), 4u);
  for (std::size_t k = 1; k < rpm.size(); ++k) EXPECT_GT(rpm[k], rpm[k - 1]);
  EXPECT_GT(rpm.front(), 1000.0);
  EXPECT_LT(rpm.back(), 2000.0);
  const Outcome ord = run_evas({"plot", "order", results, "--channel", "main3.fy", "--cycles", "0",
                                "--out", (tmp.path() / "o.png").string()},
                               tmp.path() / "order.log");
  ASSERT_EQ(ord.code, 0) << ord.log;
  EXPECT_NE(ord.log.find("the cycles pooled run from"), std::string::npos) << ord.log;
  // a spectrum over time of the run-up is refused, naming what to draw instead
  for (const char* kind : {"spectrum", "erp"}) {
    const Outcome sp = run_evas(
        {"plot", kind, results, "--channel", std::string(kind) == "erp" ? "skin" : "main3.fy",
         "--out", (tmp.path() / "s.png").string()},
        tmp.path() / "spectrum.log");
    EXPECT_EQ(sp.code, 1) << sp.log;
    EXPECT_NE(sp.log.find("a run-up (the speed runs from"), std::string::npos) << sp.log;
    EXPECT_NE(sp.log.find("evas plot order-track"), std::string::npos) << sp.log;
  }
  const Outcome ts = run_evas({"spectrum", results, "--erp", "skin"}, tmp.path() / "ts.log");
  EXPECT_EQ(ts.code, 1) << ts.log;
  EXPECT_NE(ts.log.find("a run-up (the speed runs from"), std::string::npos) << ts.log;
}
