// Cylinder-pressure table (elements/gas_pressure.h): periodic monotone cubic
// Hermite interpolation, the text format and its errors, and the synthetic
// diesel cycle of references.md section 3 (single zone, double Wiebe).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <random>

#include "elements/gas_pressure.h"
#include "elements/pressure_map.h"

using namespace evas;

namespace {

constexpr double kRad = M_PI / 180.0;

std::string temp_file(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + "evas_gas_" + name + ".txt";
  std::ofstream(path) << text;
  return path;
}

// Expects InputError whose message contains every fragment.
void expect_error(const std::string& text, const std::vector<std::string>& fragments,
                  const std::string& name) {
  const std::string path = temp_file(name, text);
  try {
    PressureTable::read(path);
    ADD_FAILURE() << name << ": no error";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    std::cout << "  " << name << ": " << msg << "\n";
    EXPECT_NE(msg.find(path), std::string::npos) << msg;
    for (const auto& f : fragments) EXPECT_NE(msg.find(f), std::string::npos) << f << " / " << msg;
  }
}

// Smooth periodic test function of the cycle angle a [deg] and its derivative per deg.
double smooth(double a, double* d = nullptr) {
  const double w = 2 * M_PI / 720.0;
  if (d)
    *d = w * (3e6 * std::cos(w * a) - 3 * 1e6 * std::sin(3 * w * a) +
              2 * 0.5e6 * std::cos(2 * w * a + 1));
  return 5e6 + 3e6 * std::sin(w * a) + 1e6 * std::cos(3 * w * a) + 0.5e6 * std::sin(2 * w * a + 1);
}

// Max errors of value and slope [Pa/deg] at many points for a table with spacing h.
void interpolation_error(double h, double& ev, double& ed) {
  std::vector<double> a, p;
  for (double x = 0.0; x < 720.0 - 1e-9; x += h) {
    a.push_back(x);
    p.push_back(smooth(x));
  }
  const PressureTable t(a, p, "smooth");
  ev = ed = 0.0;
  for (double x = -720.0; x < 1440.0; x += 0.173) {
    double d_ref, d;
    const double v = t(x * kRad, &d);
    ev = std::max(ev, std::abs(v - smooth(x, &d_ref)));
    ed = std::max(ed, std::abs(d * kRad - d_ref));
  }
}

}  // namespace

// A smooth function is reproduced. Monotone cubic Hermite interpolation
// (Fritsch & Carlson 1980, SIAM J. Numer. Anal. 17(2); harmonic-mean slopes of
// Fritsch & Butland 1984) is second-order accurate in the value, about first
// order in the slope near extrema, where the slope is set to zero.
TEST(GasPressure, InterpolatesSmoothFunction) {
  double ev1, ed1, ev2, ed2, ev4, ed4;
  interpolation_error(1.0, ev1, ed1);
  interpolation_error(2.0, ev2, ed2);
  interpolation_error(4.0, ev4, ed4);
  const double amp = 4.5e6, damp = 4.5e6 * 3 * 2 * M_PI / 720;
  std::cout << "relative value error h = 4, 2, 1 deg: " << ev4 / amp << " " << ev2 / amp << " "
            << ev1 / amp << "  (orders " << std::log2(ev4 / ev2) << ", " << std::log2(ev2 / ev1)
            << ")\n";
  std::cout << "relative slope error h = 4, 2, 1 deg: " << ed4 / damp << " " << ed2 / damp << " "
            << ed1 / damp << "  (orders " << std::log2(ed4 / ed2) << ", " << std::log2(ed2 / ed1)
            << ")\n";
  // Measured: value 1.5e-5, slope 2.3e-3 at 1 deg; mean orders 4 -> 1 deg about 2 and 1
  // (slopes are set to zero at discrete extrema, which limits the local accuracy there).
  EXPECT_LT(ev1 / amp, 2e-5);
  EXPECT_LT(ed1 / damp, 3e-3);
  EXPECT_GT(std::log2(ev4 / ev1) / 2, 1.8);
  EXPECT_GT(std::log2(ed4 / ed1) / 2, 0.9);
}

TEST(GasPressure, PeriodicAndContinuousAcrossTheWrap) {
  // Non-uniform spacing, table starting after 0 and ending before 720.
  std::vector<double> a, p;
  for (double x = 1.5; x < 719.0; x += 1.0 + 0.7 * std::sin(x)) {
    a.push_back(x);
    p.push_back(smooth(x));
  }
  const PressureTable t(a, p, "wrap");
  for (double x : {-3.0, 0.0, 0.7, 1.5, 100.2, 719.9}) {
    double d0, d1, d2;
    const double v0 = t(x * kRad, &d0), v1 = t((x + 720) * kRad, &d1),
                 v2 = t((x - 1440) * kRad, &d2);
    EXPECT_NEAR(v1, v0, 1e-6);
    EXPECT_NEAR(v2, v0, 1e-6);
    EXPECT_NEAR(d1, d0, 1e-3);
  }
  // Knots are reproduced; value and slope are continuous at the first knot
  // (the wrap-around interval joins it from the left).
  for (std::size_t k = 0; k < a.size(); k += 17) EXPECT_NEAR(t(a[k] * kRad), p[k], 1e-6);
  const double e = 1e-7, x0 = a.front();
  double dl, dr;
  EXPECT_NEAR(t((x0 - e) * kRad, &dl), t((x0 + e) * kRad, &dr), 1.0);
  EXPECT_NEAR(dl, dr, 1e-3 * std::abs(dr) + 1.0);
  // Slope is the derivative of the value.
  for (double x : {0.3, 10.0, 359.0, 719.7}) {
    double d;
    t(x * kRad, &d);
    const double h = 1e-4;
    const double fd = (t((x + h) * kRad) - t((x - h) * kRad)) / (2 * h * kRad);
    EXPECT_NEAR(d, fd, 1e-6 * std::abs(d) + 1e-2);
  }
}

// Monotone data stay monotone: no overshoot at a step-like combustion rise.
TEST(GasPressure, NoOvershootAtSteepRise) {
  std::vector<double> a, p;
  for (int k = 0; k < 720; k += 5) {
    a.push_back(k);
    p.push_back(k >= 360 && k < 400 ? 150e5 : 2e5);
  }
  const PressureTable t(a, p, "step");
  double lo = 1e300, hi = -1e300;
  for (double x = 0; x < 720; x += 0.05) {
    const double v = t(x * kRad);
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  EXPECT_GE(lo, 2e5 - 1e-6);
  EXPECT_LE(hi, 150e5 + 1e-6);
}

TEST(GasPressure, ReadsUnitsAndFormats) {
  // separators: spaces, tabs, commas, semicolons, carriage returns; a line of
  // separators alone is blank
  const std::string body =
      "0 1.0\n180\t2.0\n , ;\t\r\n  360 ,  4.0\r\n540;3.0  # trailing comment\n";
  const double gap = 200.0;  // coarse test tables
  const PressureTable bar = PressureTable::read(temp_file("bar", "# unit: bar\n" + body), gap);
  const PressureTable mpa = PressureTable::read(temp_file("mpa", "# Unit: MPa\n" + body), gap);
  const PressureTable pa = PressureTable::read(temp_file("pa", "#unit:Pa\n\n" + body), gap);
  const PressureTable closed =
      PressureTable::read(temp_file("closed", "# unit: bar\n" + body + "720 1.0\n"), gap);
  EXPECT_DOUBLE_EQ(bar(2 * M_PI), 4e5);  // 360 deg
  EXPECT_DOUBLE_EQ(mpa(2 * M_PI), 4e6);
  EXPECT_DOUBLE_EQ(pa(2 * M_PI), 4.0);
  EXPECT_DOUBLE_EQ(bar(3 * M_PI), 3e5);  // 540 deg
  EXPECT_EQ(closed.angles_deg().size(), 4u);
  EXPECT_DOUBLE_EQ(closed(0.3), bar(0.3));
}

TEST(GasPressure, BadFilesNameFileAndLine) {
  const std::string h = "# unit: bar\n";
  std::string ok;
  for (int k = 0; k < 72; ++k) ok += std::to_string(10 * k) + " 1.0\n";
  EXPECT_NO_THROW(PressureTable::read(temp_file("ok", h + ok)));
  expect_error("0 1\n90 2\n", {":1:", "unit header"}, "nounit");
  expect_error("# unit: psi\n0 1\n", {":1:", "psi"}, "badunit");
  expect_error(h + "0 1\n10 2 3\n", {":3:", "two numbers"}, "threefields");
  expect_error(h + "0 1\n\t10 ,\n", {":3:", "got 1 fields: '10'"}, "onefield");
  expect_error(h + "0 1\n10 abc\n", {":3:", "abc"}, "notanumber");
  expect_error(h + "0 1\n10 nan\n", {":3:", "not finite"}, "nan");
  expect_error(h + "0 1\ninf 2\n", {":3:", "not finite"}, "inf");
  expect_error(h + "0 1\n10 2\n5 3\n20 2\n", {":4:", "increase"}, "unsorted");
  expect_error(h + "0 1\n10 2\n10 3\n20 2\n", {":4:", "increase"}, "duplicate");
  expect_error(h + "0 1\n5 2\n30 3\n35 2\n", {":4:", "gap of 25"}, "gap");
  expect_error(h + ok.substr(0, ok.find("600 ")), {"does not cover", "590"}, "short");
  expect_error(h + "-5 1\n0 1\n5 1\n", {":2:", "negative"}, "negative");
  expect_error(h + ok + "730 1.0\n", {":74:", "not below 720"}, "beyond");
  expect_error(h + ok + "720 5.0\n", {":74:", "periodic"}, "notperiodic");
  expect_error(h + "\n# only comments\n", {"no data"}, "empty");
  EXPECT_THROW(PressureTable::read("/nonexistent/p.txt"), InputError);
}

// references.md section 3: a 4.1 L in-line four diesel at 3000 rpm full load peaks
// near 14 MPa about 10 deg after TDC; single-zone compression is polytropic.
TEST(GasPressure, SyntheticDieselCycle) {
  DieselCycle c;
  double Q = 0;
  const PressureTable t = synthetic_diesel_cycle(c, &Q);
  double peak = 0, at = 0;
  for (double x = 0; x < 720; x += 0.01) {
    const double v = t(x * kRad);
    if (v > peak) peak = v, at = x;
  }
  std::cout << "peak " << peak / 1e6 << " MPa at " << at << " deg, heat " << Q << " J\n";
  EXPECT_NEAR(peak, 14e6, 0.01 * 14e6);
  EXPECT_NEAR(at, 10.0, 2.0);
  // Compression before the start of combustion: p V^n constant (n = n_compression).
  const double A = M_PI / 4 * c.bore * c.bore, R = c.stroke / 2, L = c.conrod;
  const double Vc = A * c.stroke / (c.compression_ratio - 1);
  auto V = [&](double deg) {
    const double th = deg * kRad;
    return Vc + A * (R + L - R * std::cos(th) - std::sqrt(L * L - std::pow(R * std::sin(th), 2)));
  };
  const double ref = c.p_intake * std::pow(V(c.ivc_deg), c.n_compression);
  for (double x : {-140.0, -100.0, -50.0, -10.0}) {
    const double pv = t(x * kRad) * std::pow(V(x), c.n_compression);
    EXPECT_NEAR(pv / ref, 1.0, 1e-6) << x;
  }
  // Late expansion (burn complete): p V^n_expansion constant.
  const double ref_e = t(90 * kRad) * std::pow(V(90), c.n_expansion);
  EXPECT_NEAR(t(125 * kRad) * std::pow(V(125), c.n_expansion) / ref_e, 1.0, 1e-4);
  // The committed table is this curve.
  const PressureTable file = PressureTable::read(std::string(EVAS_SOURCE_DIR) +
                                                 "/validation/data/cylinder_pressure_3000rpm.txt");
  double worst = 0;
  for (double x = 0; x < 720; x += 0.37)
    worst = std::max(worst, std::abs(file(x * kRad) - t(x * kRad)));
  EXPECT_LT(worst, 1.0);  // Pa (file written with 1e-6 bar resolution)
}

// The cycle moved over speed and load (diesel_cycle_at): at the calibration
// point it is the calibrated cycle itself; the Wiebe durations scale with
// (n / n_ref)^0.5 and the diffusion exponent with (n_ref / n)^0.3 (Woschni &
// Anisits, SAE 740086); boost follows (n / n_ref)^2 up to n_ref; half the fuel
// gives a lower peak over the same compression. The committed map
// (validation/data/pressure_map, evas_pressure --map) is these curves, and
// PressureMap reads it.
TEST(GasPressure, DieselCycleOverSpeedAndLoad) {
  const DieselCycle ref;
  double Q = 0;
  const PressureTable t = synthetic_diesel_cycle(ref, &Q);
  const PressureTable same = synthetic_diesel_cycle(diesel_cycle_at(ref, 3000, Q, 3000, 1.0));
  ASSERT_EQ(same.pressures().size(), t.pressures().size());
  for (std::size_t k = 0; k < t.pressures().size(); ++k)
    EXPECT_NEAR(same.pressures()[k], t.pressures()[k], 1e-9 * t.pressures()[k]);
  const DieselCycle slow = diesel_cycle_at(ref, 3000, Q, 1000, 1.0);
  EXPECT_NEAR(slow.diffusion_duration_deg, ref.diffusion_duration_deg * std::sqrt(1.0 / 3.0),
              1e-12);
  EXPECT_NEAR(slow.premixed_duration_deg, ref.premixed_duration_deg * std::sqrt(1.0 / 3.0), 1e-12);
  EXPECT_NEAR(slow.diffusion_m, ref.diffusion_m * std::pow(3.0, 0.3), 1e-12);
  EXPECT_NEAR(slow.p_intake, 1e5 + (ref.p_intake - 1e5) / 9.0, 1e-6);
  EXPECT_EQ(slow.heat_release, Q);
  EXPECT_EQ(diesel_cycle_at(ref, 3000, Q, 4000, 1.0).p_intake, ref.p_intake);  // wastegate
  const PressureTable half = synthetic_diesel_cycle(diesel_cycle_at(ref, 3000, Q, 3000, 0.5));
  EXPECT_LT(half.max_pressure(), 0.9 * t.max_pressure());
  EXPECT_NEAR(half(-60 * kRad), t(-60 * kRad), 1e-9 * t(-60 * kRad));  // same compression
  EXPECT_THROW(diesel_cycle_at(ref, 3000, Q, 0.0, 1.0), InputError);
  EXPECT_THROW(diesel_cycle_at(ref, 3000, Q, 3000, 0.0), InputError);
  // the committed map
  const std::string dir = std::string(EVAS_SOURCE_DIR) + "/validation/data/pressure_map";
  const PressureMap map = PressureMap::read(dir + "/map.txt");
  for (double rpm : {1000.0, 2500.0, 4000.0}) {
    const PressureTable want = synthetic_diesel_cycle(diesel_cycle_at(ref, 3000, Q, rpm, 1.0));
    const double w = rpm * M_PI / 30.0;
    double worst = 0;
    for (double x = 0; x < 720; x += 0.37)
      worst = std::max(worst, std::abs(map(x * kRad, w) - want(x * kRad)));
    EXPECT_LT(worst, 1.0) << rpm << " rpm";  // Pa (written with 1e-6 bar resolution)
  }
}

// A table of equal spacing is entered by division (gas_pressure.cpp, operator()),
// any other by bisection: both must pick the same interval. The twin table has
// one knot moved by 1e-7 deg (so it takes the bisection); away from that knot
// the knots, values and slopes of the two are the same, so the values must be
// bitwise equal, at the knots themselves (where rounding of the division could
// pick the neighbouring interval) and between them.
TEST(GasPressure, UniformTableEntersTheIntervalsOfTheBisection) {
  std::vector<double> a, p;
  for (int k = 0; k < 2400; ++k) {  // 0.3 deg: knots that a division by the step can miss
    a.push_back(0.3 * k);
    p.push_back(smooth(0.3 * k));
  }
  std::vector<double> a2 = a;
  a2[2334] += 1e-7;  // 700.2 deg
  const PressureTable uniform(a, p, "uniform"), twin(a2, p, "twin");
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.0, 690.0);
  std::vector<double> x;
  for (int k = 0; k < 2300; ++k) x.push_back(a[static_cast<std::size_t>(k)]);  // the knots
  for (int k = 0; k < 20000; ++k) x.push_back(u(rng));
  int compared = 0;
  for (double deg : x)
    for (double cycle : {0.0, 720.0, -1440.0}) {
      double d1, d2;
      const double v1 = uniform((deg + cycle) * kRad, &d1), v2 = twin((deg + cycle) * kRad, &d2);
      EXPECT_EQ(v1, v2) << "at " << deg + cycle << " deg";
      EXPECT_EQ(d1, d2) << "at " << deg + cycle << " deg";
      ++compared;
    }
  EXPECT_EQ(compared, 3 * (2300 + 20000));
}

// read_cached: one parse per file state, shared; a rewritten file is read
// again; another gap is another table; an error is thrown each time.
TEST(GasPressure, CachedTablesFollowTheirFile) {
  const double gap = 200.0;
  const std::string body = "# unit: bar\n0 1.0\n180 2.0\n360 4.0\n540 3.0\n";
  const std::string path = temp_file("cached", body);
  const auto a = PressureTable::read_cached(path, gap), b = PressureTable::read_cached(path, gap);
  EXPECT_EQ(a.get(), b.get());
  EXPECT_DOUBLE_EQ((*a)(2 * M_PI), 4e5);
  EXPECT_NE(PressureTable::read_cached(path, 250.0).get(), a.get());
  // a new file under the same name (another size here): read again
  std::remove(path.c_str());
  std::ofstream(path) << "# unit: bar\n0 1.0\n180 2.0\n360 40.0\n540 3.0\n";
  const auto c = PressureTable::read_cached(path, gap);
  EXPECT_NE(c.get(), a.get());
  EXPECT_DOUBLE_EQ((*c)(2 * M_PI), 40e5);
  EXPECT_DOUBLE_EQ((*a)(2 * M_PI), 4e5);  // the first stays what it was
  const std::string bad = temp_file("cached_bad", "# unit: bar\n0 1.0\n");
  for (int pass = 0; pass < 2; ++pass)
    EXPECT_THROW(PressureTable::read_cached(bad, gap), InputError);
  EXPECT_THROW(PressureTable::read_cached(path + ".missing", gap), InputError);
}
