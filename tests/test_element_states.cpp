// Element internal states of the engine mount (Maxwell branch) and the motor
// (massless clutch disk), element by element:
//  - analytic d(loads)/d(motion) at fixed states, d(loads)/dz, dh/d(motion) and
//    dh/dz against central differences (Element::internal_derivatives_fd);
//  - the Maxwell branch: unloaded at z = d (the mount of the paper), force
//    -k2 (d - z), rate (k2/c2)(d - z) (standard linear solid, R. Lakes,
//    Viscoelastic Materials, Cambridge 2009, ch. 2), and the dynamic stiffness
//    k + k2 i w tau / (1 + i w tau), tau = c2 / k2, of a harmonic deflection;
//  - the clutch disk: a consistent start (h = 0), and the limit of a rigid
//    clutch (K_c -> infinity) is the paper's motor, Eq. 5;
//  - the parameters each refuses, with their messages.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <random>
#include <string>
#include <vector>

#include "elements/registry.h"

namespace evas {
namespace {

std::unique_ptr<Element> make(const std::string& type, ParamValues v) {
  const ElementType& t = element_type(type);
  complete_params(t, v, "test");
  return t.make("e", {0, 1}, v);
}

ParamValues mount_params(bool branch) {
  ParamValues v;
  v.numbers["k_x"] = {2e5, 3e6};  // nonlinear law on x
  v.numbers["k_y"] = {1.5e5};
  v.numbers["k_z"] = {3e5};
  v.numbers["damping"] = {900, 1000, 1100};
  v.numbers["preload"] = {0, 0, 250};
  v.numbers["rot_stiffness"] = {100, 200, 300};
  v.numbers["orientation"] = {0.1, -0.2, 0.3};
  v.numbers["offset"] = {0.001, 0, -0.002};
  if (branch) {
    v.numbers["maxwell_stiffness"] = {1.5e5, 0, 3e5};  // branches on x and z
    v.numbers["maxwell_damping"] = {2400, 0, 4800};
  }
  return v;
}

ParamValues motor_params(double Kc, double Cc) {
  ParamValues v;
  v.numbers["axis"] = {1, 0.2, -0.1};
  v.numbers["speed"] = {314.159};
  v.numbers["initial_angle"] = {10};
  v.numbers["stiffness"] = {5e4};
  v.numbers["damping"] = {20};
  v.numbers["clutch_stiffness"] = {Kc};
  v.numbers["clutch_damping"] = {Cc};
  return v;
}

std::vector<MarkerMotion> random_motion(unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  std::vector<MarkerMotion> m(2);
  for (auto& mm : m) {
    mm.p = 0.003 * Vec3(U(gen), U(gen), U(gen));
    mm.v = 0.2 * Vec3(U(gen), U(gen), U(gen));
    mm.psi = 0.01 * Vec3(U(gen), U(gen), U(gen));
    mm.w = 3.0 * Vec3(U(gen), U(gen), U(gen));
  }
  m[0].R = rotation_from_vector(Vec3(0.2, 0.1, -0.3));
  return m;
}

// Central differences of evaluate_z over the motion at fixed z.
Mat loads_fd(const Element& e, double t, std::vector<MarkerMotion> m, const double* z) {
  Mat D = Mat::Zero(12, 24);
  MarkerLoad lp[2], lm[2];
  for (int j = 0; j < 2; ++j)
    for (int c = 0; c < 12; ++c) {
      Vec3* parts[4] = {&m[j].p, &m[j].v, &m[j].psi, &m[j].w};
      double& x = (*parts[c / 3])[c % 3];
      const double x0 = x, h = 1e-6 * std::max(1.0, std::abs(x0));
      x = x0 + h;
      e.evaluate_z(t, m.data(), z, lp);
      x = x0 - h;
      e.evaluate_z(t, m.data(), z, lm);
      x = x0;
      for (int i = 0; i < 2; ++i) {
        D.block<3, 1>(6 * i, 12 * j + c) = (lp[i].F - lm[i].F) / (2 * h);
        D.block<3, 1>(6 * i + 3, 12 * j + c) = (lp[i].M - lm[i].M) / (2 * h);
      }
    }
  return D;
}

double rel(const Mat& a, const Mat& b) {
  const double s = std::max(1.0, b.cwiseAbs().maxCoeff());
  return (a - b).cwiseAbs().maxCoeff() / s;
}

void check_derivatives(const Element& e, double t, unsigned seed) {
  const auto m = random_motion(seed);
  const int nz = e.internal_count();
  std::vector<double> z(static_cast<std::size_t>(nz));
  e.internal_initial(t, m.data(), z.data());
  for (int i = 0; i < nz; ++i) z[static_cast<std::size_t>(i)] += 1e-3 * (i + 1);  // off rest
  Mat D(12, 24), Dz(12, nz), Hm(nz, 24), Hz(nz, nz), Dz0, Hm0, Hz0;
  e.derivatives_z(t, m.data(), z.data(), D);
  EXPECT_LT(rel(D, loads_fd(e, t, m, z.data())), 1e-7) << "d(loads)/d(motion)";
  e.internal_derivatives(t, m.data(), z.data(), Dz, Hm, Hz);
  e.internal_derivatives_fd(t, m.data(), z.data(), Dz0, Hm0, Hz0);
  EXPECT_LT(rel(Dz, Dz0), 1e-7) << "d(loads)/dz";
  EXPECT_LT(rel(Hm, Hm0), 1e-7) << "dh/d(motion)";
  EXPECT_LT(rel(Hz, Hz0), 1e-7) << "dh/dz";
  EXPECT_GT(Dz.cwiseAbs().maxCoeff(), 0.0);
  EXPECT_GT(Hm.cwiseAbs().maxCoeff(), 0.0);
  // the z-free derivatives match the z-free loads (branch unloaded / disk quasi-static)
  Mat Df(12, 24), Dref(12, 24);
  e.derivatives(t, m.data(), Df);
  e.derivatives_fd(t, m.data(), Dref);
  EXPECT_LT(rel(Df, Dref), 1e-6) << "z-free derivatives";
}

TEST(ElementStates, MaxwellMountDerivativesMatchDifferences) {
  auto e = make("engine-mount", mount_params(true));
  ASSERT_EQ(e->internal_count(), 2);
  EXPECT_EQ(e->internal_name(0), "z_x");
  EXPECT_EQ(e->internal_name(1), "z_z");
  EXPECT_FALSE(e->internal_algebraic(0));
  for (unsigned seed : {1u, 2u, 3u}) check_derivatives(*e, 0.01, seed);
}

TEST(ElementStates, ClutchDiskDerivativesMatchDifferences) {
  auto e = make("motor", motor_params(3e4, 8));
  ASSERT_EQ(e->internal_count(), 2);
  EXPECT_FALSE(e->internal_algebraic(0));
  EXPECT_TRUE(e->internal_algebraic(1));
  for (unsigned seed : {4u, 5u, 6u}) check_derivatives(*e, 0.02, seed);
}

TEST(ElementStates, MaxwellBranchForceAndRate) {
  auto plain = make("engine-mount", mount_params(false));
  auto e = make("engine-mount", mount_params(true));
  EXPECT_EQ(plain->internal_count(), 0);
  const auto m = random_motion(7);
  double z[2];
  e->internal_initial(0, m.data(), z);  // unloaded: z = d
  MarkerLoad a[2], b[2];
  plain->evaluate(0, m.data(), a);
  e->evaluate_z(0, m.data(), z, b);
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(a[i].F, b[i].F);
    EXPECT_EQ(a[i].M, b[i].M);
  }
  double h[2];
  e->internal_rate(0, m.data(), z, h);
  EXPECT_EQ(h[0], 0.0);
  EXPECT_EQ(h[1], 0.0);
  // stretched branch: channels report -k2 (d - z) and the rate (k2/c2)(d - z)
  const double zx = z[0] - 1e-3, zz = z[1] + 2e-3;
  const double zs[2] = {zx, zz};
  std::vector<double> out(e->channels().size());
  e->channel_values_z(0, m.data(), zs, out.data());
  ASSERT_EQ(e->channels()[9].name, "maxwell_fx");
  ASSERT_EQ(e->channels()[12].name, "z_z");
  EXPECT_NEAR(out[9], -1.5e5 * 1e-3, 1e-9);
  EXPECT_NEAR(out[10], 3e5 * 2e-3, 1e-9);
  e->internal_rate(0, m.data(), zs, h);
  EXPECT_NEAR(h[0], 1.5e5 / 2400 * 1e-3, 1e-12);
  EXPECT_NEAR(h[1], -3e5 / 4800 * 2e-3, 1e-12);
}

// Harmonic deflection d = D sin(w t) along the mount's x axis; the branch
// state integrated with RK4 (step T/2000) from rest over 12 periods; the
// force's first Fourier coefficient over the last period against the dynamic
// stiffness of the standard linear solid (Lakes 2009, ch. 2).
TEST(ElementStates, MaxwellBranchHasTheZenerDynamicStiffness) {
  ParamValues v;
  v.numbers["k_x"] = {1e5};
  v.numbers["maxwell_stiffness"] = {2e5, 0, 0};
  v.numbers["maxwell_damping"] = {2e5 * 0.01, 0, 0};  // tau = 10 ms
  auto e = make("engine-mount", v);
  const double D = 1e-3, tau = 0.01;
  for (double f : {5.0, 16.0, 60.0}) {
    const double w = 2 * M_PI * f, T = 1 / w * 2 * M_PI;
    const int N = 2000;
    const double dt = T / N;
    auto motion = [&](double t) {
      std::vector<MarkerMotion> m(2);
      m[1].p.x() = D * std::sin(w * t);
      m[1].v.x() = D * w * std::cos(w * t);
      return m;
    };
    auto rate = [&](double t, double z) {
      double h;
      e->internal_rate(t, motion(t).data(), &z, &h);
      return h;
    };
    double z = 0.0, t = 0.0;
    std::complex<double> c = 0;
    for (int k = 0; k < 12 * N; ++k) {
      if (k >= 11 * N) {
        std::vector<double> out(e->channels().size());
        e->channel_values_z(t, motion(t).data(), &z, out.data());
        c += out[0] * std::exp(std::complex<double>(0, -w * t)) * dt;  // fx (spring + branch)
      }
      const double k1 = rate(t, z), k2 = rate(t + dt / 2, z + dt / 2 * k1);
      const double k3 = rate(t + dt / 2, z + dt / 2 * k2), k4 = rate(t + dt, z + dt * k3);
      z += dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
      t += dt;
    }
    // F = -K* d with d = D sin = D Im(e^{iwt}): the coefficient 2c/T = -K* D / i
    const std::complex<double> K = -2.0 * c / T * std::complex<double>(0, 1) / D;
    const std::complex<double> iwt(0, w * tau);
    const std::complex<double> Kzener = 1e5 + 2e5 * iwt / (1.0 + iwt);
    EXPECT_LT(std::abs(K - Kzener) / std::abs(Kzener), 1e-5) << f << " Hz";
  }
}

TEST(ElementStates, ClutchDiskStartsConsistentAndStiffClutchIsThePaperMotor) {
  auto plain = make("motor", motor_params(0, 0));
  EXPECT_EQ(plain->internal_count(), 0);
  for (unsigned seed : {8u, 9u}) {
    const auto m = random_motion(seed);
    for (double Kc : {1e6, 1e8, 1e10}) {
      auto e = make("motor", motor_params(Kc, 0));
      double z[2], h[2];
      e->internal_initial(0.03, m.data(), z);
      e->internal_rate(0.03, m.data(), z, h);
      EXPECT_LT(std::abs(h[1]), 1e-9 * (5e4 + Kc) * 1e-2);  // torque balance holds
      MarkerLoad a[2], b[2];
      plain->evaluate(0.03, m.data(), a);
      e->evaluate_z(0.03, m.data(), z, b);
      // series springs: T differs from Eq. 5 by a relative O(K_r / K_c)
      const double d = (a[0].M - b[0].M).norm() / a[0].M.norm();
      EXPECT_LT(d, 20 * 5e4 / Kc) << Kc;
    }
  }
}

TEST(ElementStates, BadParametersAreRefused) {
  auto expect_refused = [](const std::string& type, ParamValues v, const std::string& part) {
    try {
      make(type, std::move(v));
      FAIL() << "accepted: " << part;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
  };
  ParamValues v = mount_params(false);
  v.numbers["maxwell_stiffness"] = {1e5, 0, 0};
  expect_refused("engine-mount", v, "axis x: a Maxwell branch (maxwell_stiffness > 0) needs");
  v = mount_params(false);
  v.numbers["maxwell_damping"] = {0, 10, 0};
  expect_refused("engine-mount", v, "axis y: maxwell_damping is given without maxwell_stiffness");
  ParamValues m = motor_params(1e4, 0);
  m.numbers["damping"] = {0};
  expect_refused("motor", m, "a massless clutch disk needs damping on one side");
  expect_refused("motor", motor_params(0, 5), "clutch_damping is given without clutch_stiffness");
}

}  // namespace
}  // namespace evas
