// Element internal states (Problem::internal_count(); solver/system_internal.cpp,
// dae/formulation.cpp, solver/first_order.cpp) on a rigid body driven along x
// through its centre of mass by a standard linear solid: a spring k in parallel
// with a Maxwell branch (spring k2 in series with a dashpot c2), the other end
// on the ground. Zener's model (R. Lakes, Viscoelastic Materials, Cambridge
// University Press 2009, ch. 2) with the mass gives the linear system
//     m x'' = -k x - k2 (x - z),   c2 z' = k2 (x - z),
// whose solution X(t) = V exp(L t) V^-1 X(0), X = (x, x', z), is the reference.
// The same branch is coded twice:
//  - "maxwell": one differential state z (the dashpot's end);
//  - "node": the massless node between spring and dashpot as a differential
//    position y and an ALGEBRAIC speed u (its force balance 0 = k2 (x - y) - c2 u
//    replaces Newton's law for the massless node), an index-1 DAE.
// Checked: the System's blocks Fz, Hq, Hv, Hz and the iteration matrices of
// DaeForm and FirstOrderForm against differences; IDA (both codings, with and
// without a joint holding the body on the x axis) and CVODE (maxwell) against
// the closed form; the integrators that cannot take the states refuse them.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <complex>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "dae/formulation.h"
#include "integrators/integrator.h"
#include "model/model.h"
#include "random_body.h"
#include "solver/first_order.h"
#include "solver/system.h"

namespace evas {
namespace {

// Markers: 0 = ground, 1 = body. x = p1.x - p0.x.
class Branch final : public Element {
 public:
  // loaded: start with the dashpot end at 0 (the branch stretched) and, for the
  // node, u = 0 as well, which violates 0 = k2 (x - y) - c2 u: the integrator's
  // consistent start must solve u.
  Branch(std::vector<int> markers, double k, double k2, double c2, bool node, bool loaded)
      : Element("branch", std::move(markers)),
        k_(k),
        k2_(k2),
        c2_(c2),
        node_(node),
        loaded_(loaded) {}
  std::string type() const override { return "test-branch"; }
  int internal_count() const override { return node_ ? 2 : 1; }
  bool internal_algebraic(int i) const override { return node_ && i == 1; }
  std::string internal_name(int i) const override { return i == 0 ? "y" : "u"; }
  void internal_initial(double, const MarkerMotion* m, double* z) const override {
    z[0] = loaded_ ? 0.0 : x(m);  // unloaded: the branch carries no force
    if (node_) z[1] = 0.0;
  }
  void evaluate(double t, const MarkerMotion* m, MarkerLoad* loads) const override {
    const double z = x(m);
    evaluate_z(t, m, &z, loads);
  }
  void evaluate_z(double, const MarkerMotion* m, const double* z,
                  MarkerLoad* loads) const override {
    const double F = -(k_ * x(m) + k2_ * (x(m) - z[0]));
    loads[1].F = Vec3(F, 0, 0);
    loads[0].F = -loads[1].F;
    loads[0].M.setZero();
    loads[1].M.setZero();
  }
  void derivatives_z(double, const MarkerMotion*, const double*, Mat& D) const override {
    D.setZero();
    D(0, 0) = -(k_ + k2_);
    D(0, 12) = k_ + k2_;
    D(6, 0) = k_ + k2_;
    D(6, 12) = -(k_ + k2_);
  }
  void internal_rate(double, const MarkerMotion* m, const double* z, double* h) const override {
    if (node_) {
      h[0] = z[1];
      h[1] = k2_ * (x(m) - z[0]) - c2_ * z[1];
    } else {
      h[0] = k2_ / c2_ * (x(m) - z[0]);
    }
  }
  void internal_derivatives(double, const MarkerMotion*, const double*, Mat& Dz, Mat& Hm,
                            Mat& Hz) const override {
    Dz.setZero();
    Hm.setZero();
    Hz.setZero();
    Dz(6, 0) = k2_;   // marker 1, F_x
    Dz(0, 0) = -k2_;  // marker 0
    if (node_) {
      Hz(0, 1) = 1.0;
      Hm(1, 12) = k2_;
      Hm(1, 0) = -k2_;
      Hz(1, 0) = -k2_;
      Hz(1, 1) = -c2_;
    } else {
      Hm(0, 12) = k2_ / c2_;
      Hm(0, 0) = -k2_ / c2_;
      Hz(0, 0) = -k2_ / c2_;
    }
  }
  std::vector<Channel> channels() const override { return {{"x", "m"}}; }
  void channel_values(double, const MarkerMotion* m, double* out) const override { out[0] = x(m); }

 private:
  static double x(const MarkerMotion* m) { return m[1].p.x() - m[0].p.x(); }
  double k_, k2_, c2_;
  bool node_, loaded_;
};

std::string sci(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3e", x);
  return buf;
}

constexpr double kX0 = 0.01;   // initial displacement [m]
constexpr double kTau = 0.02;  // branch relaxation time c2 / k2 [s]

struct Rig {
  bool loaded = false;
  std::unique_ptr<Model> model;
  std::unique_ptr<System> sys;
  double m = 0, k = 0, k2 = 0, c2 = 0;
  int coord = -1;  // modal coordinate of the x translation
};

// A rigid body (no elastic modes) whose centre of mass sits at the origin; the
// branch acts through it, so the body only translates along x. `joint`: a
// prismatic joint along x to the ground in addition (constraints + states).
Rig make_rig(bool node, bool joint = false, bool loaded = false) {
  Rig r;
  r.loaded = loaded;
  r.model = std::make_unique<Model>();
  Model& model = *r.model;
  auto data = std::make_shared<ModalBody>(test_bodies::random_body(8, 0, 3));
  const int b = model.add_body("mass", data, Lof::fixed(Vec3::Zero(), Mat3::Identity()));
  const Body& B = model.bodies()[b];
  r.m = B.mp.mass;
  r.k = std::pow(2 * M_PI * 5.0, 2) * r.m;
  r.k2 = 2.0 * r.k;
  r.c2 = r.k2 * kTau;
  const Vec3 c = B.mp.com;
  Mat3 z_along_x;  // marker axes with z along G x: the prismatic joint's slide axis
  z_along_x.col(0) = Vec3::UnitY();
  z_along_x.col(1) = Vec3::UnitZ();
  z_along_x.col(2) = Vec3::UnitX();
  model.add_marker(make_ground_marker("g", c, z_along_x));
  Marker p = make_set_marker("p", b, *data, data->node_sets.at("all"), {}, &c);
  p.R_LM = z_along_x;
  model.add_marker(p);
  if (joint) {
    Joint j;
    j.name = "slide";
    j.type = JointType::prismatic;
    j.marker1 = 1;
    j.marker2 = 0;
    model.add_joint(j);
  }
  model.add_element(
      std::make_unique<Branch>(std::vector<int>{0, 1}, r.k, r.k2, r.c2, node, loaded));
  r.sys = std::make_unique<System>(model);
  r.coord = B.offset + B.rigid[0];
  return r;
}

// x(t) of the closed form.
double exact_x(const Rig& r, double t) {
  Eigen::Matrix3d A;
  A << 0, 1, 0, -(r.k + r.k2) / r.m, 0, r.k2 / r.m, r.k2 / r.c2, 0, -r.k2 / r.c2;
  Eigen::EigenSolver<Eigen::Matrix3d> es(A);
  const Eigen::Matrix3cd V = es.eigenvectors();
  const Eigen::Vector3cd c = V.inverse() * Eigen::Vector3cd(kX0, 0, r.loaded ? 0.0 : kX0);
  std::complex<double> x = 0;
  for (int i = 0; i < 3; ++i) x += V(0, i) * c[i] * std::exp(es.eigenvalues()[i] * t);
  return x.real();
}

// Start: the body displaced by kX0 along x (modal coordinate sqrt(m) x).
void start(const Rig& r, Vec& q, Vec& v) {
  r.sys->initial_state(q, v);
  q[r.coord] = std::sqrt(r.m) * kX0;
}

double marker_x(Rig& r, double t, const Vec& q, const Vec& v) {
  r.sys->observe(t, q.data(), v.data());
  return r.sys->motion(1).p.x() - r.sys->motion(0).p.x();
}

// Max |x - x_exact| / kX0 over 60 outputs to 0.3 s.
double run_error(Rig& r, IntegratorSettings s) {
  auto integ = make_integrator(s.name);
  Vec q, v;
  start(r, q, v);
  integ->init(*r.sys, 0.0, q, v, s);
  std::vector<double> out;
  for (int i = 1; i <= 60; ++i) out.push_back(0.005 * i);
  double worst = 0.0;
  integrate(*integ, *r.sys, 0.0, out, [&](double t, const Vec& qq, const Vec& vv) {
    worst = std::max(worst, std::abs(marker_x(r, t, qq, vv) - exact_x(r, t)) / kX0);
  });
  return worst;
}

TEST(InternalStates, SystemLayoutAndInitialStates) {
  Rig a = make_rig(false), b = make_rig(true);
  EXPECT_EQ(a.sys->internal_count(), 1);
  EXPECT_EQ(b.sys->internal_count(), 2);
  EXPECT_FALSE(b.sys->internal_algebraic(0));
  EXPECT_TRUE(b.sys->internal_algebraic(1));
  EXPECT_EQ(b.sys->internal_name(1), "element 'branch' state u (algebraic)");
  Vec q, v, z;
  start(b, q, v);
  b.sys->internal_initial(0.0, q, v, z);
  ASSERT_EQ(z.size(), 2);
  EXPECT_NEAR(z[0], kX0, 1e-15);  // the branch starts unloaded
}

// Fz, Hq, Hv, Hz of the System against central differences of f and h.
TEST(InternalStates, SystemBlocksMatchDifferences) {
  Rig r = make_rig(true);
  System& s = *r.sys;
  const int n = s.size(), nz = s.internal_count();
  Vec q = 1e-3 * Vec::Random(n), v = 1e-2 * Vec::Random(n), z(nz);
  z << 0.004, -0.03;
  SpMat Fz, Hq, Hv, Hz;
  s.internal_patterns(Fz, Hq, Hv, Hz);
  s.set_internal(z.data());
  s.internal_jacobian(0.1, q.data(), v.data(), Fz, Hq, Hv, Hz);
  auto f_of = [&](const Vec& qq, const Vec& vv, const Vec& zz) {
    Vec f(n);
    s.set_internal(zz.data());
    s.force(0.1, qq.data(), vv.data(), f.data());
    return f;
  };
  auto h_of = [&](const Vec& qq, const Vec& vv, const Vec& zz) {
    Vec h(nz);
    s.set_internal(zz.data());
    s.internal_rate(0.1, qq.data(), vv.data(), h.data());
    return h;
  };
  const double e = 1e-6;
  double err = 0.0, scale = 0.0;
  for (int j = 0; j < nz; ++j) {
    Vec zp = z, zm = z;
    zp[j] += e;
    zm[j] -= e;
    const Vec dF = (f_of(q, v, zp) - f_of(q, v, zm)) / (2 * e);
    const Vec dH = (h_of(q, v, zp) - h_of(q, v, zm)) / (2 * e);
    err = std::max(err, (dF - Mat(Fz).col(j)).cwiseAbs().maxCoeff());
    err = std::max(err, (dH - Mat(Hz).col(j)).cwiseAbs().maxCoeff());
    scale = std::max({scale, dF.cwiseAbs().maxCoeff(), dH.cwiseAbs().maxCoeff()});
  }
  for (int j = 0; j < n; ++j) {
    Vec qp = q, qm = q, vp = v, vm = v;
    qp[j] += e;
    qm[j] -= e;
    vp[j] += e;
    vm[j] -= e;
    const Vec dHq = (h_of(qp, v, z) - h_of(qm, v, z)) / (2 * e);
    const Vec dHv = (h_of(q, vp, z) - h_of(q, vm, z)) / (2 * e);
    err = std::max(err, (dHq - Mat(Hq).col(j)).cwiseAbs().maxCoeff());
    err = std::max(err, (dHv - Mat(Hv).col(j)).cwiseAbs().maxCoeff());
    scale = std::max(scale, dHq.cwiseAbs().maxCoeff());
  }
  EXPECT_GT(scale, 1.0);
  EXPECT_LT(err, 1e-7 * scale);
}

// The iteration matrices with internal states against differences of the residuals.
TEST(InternalStates, IterationMatricesMatchDifferences) {
  for (bool node : {false, true}) {
    SCOPED_TRACE(node ? "node" : "maxwell");
    Rig r = make_rig(node, node);  // the node rig also carries the joint
    dae::DaeForm form(*r.sys, dae::Formulation::ggl, 0, 0);
    const int N = form.size();
    Vec y = 1e-3 * Vec::Random(N), yd = 1e-2 * Vec::Random(N);
    const double cj = 250.0;
    SpMat J = form.residual_pattern();
    form.residual_jacobian(0.05, y.data(), yd.data(), cj, J);
    const Mat Jd(J);
    double err = 0.0, scale = 0.0;
    for (int j = 0; j < N; ++j) {
      const double e = 1e-7;
      Vec yp = y, ym = y, dp = yd, dm = yd;
      yp[j] += e;
      ym[j] -= e;
      dp[j] += e;
      dm[j] -= e;
      Vec Fp(N), Fm(N), Gp(N), Gm(N);
      form.residual(0.05, yp.data(), yd.data(), Fp.data());
      form.residual(0.05, ym.data(), yd.data(), Fm.data());
      form.residual(0.05, y.data(), dp.data(), Gp.data());
      form.residual(0.05, y.data(), dm.data(), Gm.data());
      const Vec col = (Fp - Fm) / (2 * e) + cj * (Gp - Gm) / (2 * e);
      err = std::max(err, (col - Jd.col(j)).cwiseAbs().maxCoeff());
      scale = std::max(scale, col.cwiseAbs().maxCoeff());
    }
    EXPECT_LT(err, 1e-6 * scale);
    if (node) continue;
    FirstOrderForm fo(*r.sys);
    ASSERT_EQ(fo.size(), 2 * r.sys->size() + 1);
    const int M = fo.size();
    Vec x = 1e-3 * Vec::Random(M);
    SpMat R = fo.rhs_pattern();
    fo.rhs_jacobian(0.05, x.data(), R);
    const Mat Rd(R);
    double rerr = 0.0, rscale = 0.0;
    for (int j = 0; j < M; ++j) {
      const double e = 1e-7;
      Vec xp = x, xm = x, gp(M), gm(M);
      xp[j] += e;
      xm[j] -= e;
      fo.rhs(0.05, xp.data(), gp.data());
      fo.rhs(0.05, xm.data(), gm.data());
      const Vec col = (gp - gm) / (2 * e);
      rerr = std::max(rerr, (col - Rd.col(j)).cwiseAbs().maxCoeff());
      rscale = std::max(rscale, col.cwiseAbs().maxCoeff());
    }
    EXPECT_LT(rerr, 1e-6 * rscale);
  }
}

TEST(InternalStates, IdaMatchesClosedFormInBothCodings) {
  IntegratorSettings s;
  s.name = "ida";
  s.rtol = 1e-9;
  s.atol = 1e-13;
  for (bool node : {false, true}) {
    SCOPED_TRACE(node ? "node (algebraic speed)" : "maxwell");
    Rig r = make_rig(node);
    const double e = run_error(r, s);
    RecordProperty(node ? "ida_node_error" : "ida_maxwell_error", sci(e));
    EXPECT_LT(e, 1e-6);
  }
}

// An inconsistent algebraic start (u = 0 while the branch pulls): solved by the
// Newton step of the consistent start and IDACalcIC, so the run follows the
// closed form of the loaded start z(0) = 0.
TEST(InternalStates, IdaSolvesAnInconsistentAlgebraicStart) {
  IntegratorSettings s;
  s.name = "ida";
  s.rtol = 1e-9;
  s.atol = 1e-13;
  Rig r = make_rig(true, false, true);
  const double e = run_error(r, s);
  RecordProperty("ida_inconsistent_start_error", sci(e));
  EXPECT_LT(e, 1e-6);
  // the two codings agree on the loaded start too
  Rig m = make_rig(false, false, true);
  EXPECT_LT(run_error(m, s), 1e-6);
}

// With a prismatic joint holding the body on x: the same motion, in every
// formulation IDA runs (the joint's reactions vanish, the states do not care).
TEST(InternalStates, IdaWithJointAndStatesInEveryFormulation) {
  for (const char* f : {"index-3", "index-2", "ggl", "index-1"}) {
    SCOPED_TRACE(f);
    IntegratorSettings s;
    s.name = "ida";
    s.formulation = f;
    s.rtol = 1e-9;
    s.atol = 1e-13;
    Rig r = make_rig(true, true);
    const double e = run_error(r, s);
    RecordProperty(std::string("ida_") + f + "_error", sci(e));
    EXPECT_LT(e, 1e-6);
  }
}

TEST(InternalStates, CvodeRunsDifferentialStatesAndRefusesAlgebraicOnes) {
  IntegratorSettings s;
  s.name = "cvode";
  s.rtol = 1e-9;
  s.atol = 1e-13;
  Rig r = make_rig(false);
  const double e = run_error(r, s);
  RecordProperty("cvode_maxwell_error", sci(e));
  EXPECT_LT(e, 1e-6);
  Rig a = make_rig(true);
  try {
    run_error(a, s);
    FAIL() << "cvode took an algebraic state";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "state u (algebraic): this integrator takes differential states only"),
              std::string::npos)
        << e.what();
  }
}

TEST(InternalStates, FixedStepMethodsRefuseStates) {
  for (const char* name : {"generalized-alpha", "linear-acceleration"}) {
    IntegratorSettings s;
    s.name = name;
    s.step = 1e-3;
    Rig r = make_rig(false);
    try {
      run_error(r, s);
      FAIL() << name << " ran with internal states";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("does not integrate element internal states"),
                std::string::npos)
          << e.what();
    }
  }
}

}  // namespace
}  // namespace evas
