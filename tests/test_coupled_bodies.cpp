// Through the whole stack (bodies, markers, spring-dampers, System, integrators):
//  - a single-degree-of-freedom oscillator (translation modes of a body on a
//    ground spring) against its closed-form solution, every integrator;
//  - two flexible bodies coupled by spring-dampers, one spinning: all four
//    integrators agree within their tolerances;
//  - the same run with a tracking LOF instead of the spin LOF agrees.
#include <gtest/gtest.h>

#include <cmath>

#include "bodies/body_builder.h"
#include "elements/spring_damper.h"
#include "integrators/integrator.h"
#include "random_body.h"
#include "solver/system.h"

using namespace evas;

namespace {

struct RunResult {
  std::vector<double> t;
  std::vector<Vec> p;  // positions of the watched markers, stacked
  IntegratorStats stats;
};

RunResult simulate(Model& model, const std::vector<int>& watch, IntegratorSettings s, double t_end,
                   int n_out) {
  System sys(model);
  auto integ = make_integrator(s.name);
  Vec q, v;
  sys.initial_state(q, v);
  integ->init(sys, 0.0, q, v, s);
  std::vector<double> outs;
  for (int k = 1; k <= n_out; ++k) outs.push_back(t_end * k / n_out);
  RunResult r;
  integrate(*integ, sys, 0.0, outs, [&](double t, const Vec& qq, const Vec& vv) {
    sys.update_markers(t, qq.data(), vv.data());
    Vec p(3 * watch.size());
    for (std::size_t i = 0; i < watch.size(); ++i) p.segment<3>(3 * i) = sys.motion(watch[i]).p;
    r.t.push_back(t);
    r.p.push_back(p);
  });
  r.stats = integ->stats();
  return r;
}

double max_diff(const RunResult& a, const RunResult& b) {
  double d = 0;
  for (std::size_t k = 0; k < a.p.size(); ++k)
    d = std::max(d, (a.p[k] - b.p[k]).cwiseAbs().maxCoeff());
  return d;
}

// Adaptive methods: tolerance rtol. Fixed-step methods: step h, with their
// iterations converged far below the discretisation error.
IntegratorSettings settings(const std::string& name, double rtol, double step) {
  IntegratorSettings s;
  s.name = name;
  s.rtol = step > 0 ? 1e-10 : rtol;
  s.atol = step > 0 ? 1e-14 : rtol * 1e-3;
  s.step = step;
  s.balance_tol = 1e-9;
  s.max_iterations = 100;
  return s;
}

// Body with the three translation modes only, hung on a vertical spring.
std::unique_ptr<Model> sdof_model(double k, double c, double z0, double& m) {
  auto model = std::make_unique<Model>();
  auto full = test_bodies::random_body(12, 0, 31);
  auto body = std::make_shared<ModalBody>(full.select_modes({0, 1, 2}));
  const MassProperties mp = mass_properties(body->s, body->mass);
  m = mp.mass;
  model->add_body("mass", body, Lof::fixed(Vec3::Zero(), Mat3::Identity()));
  const int mk = model->add_marker(make_set_marker("com", 0, *body, body->node_sets.at("all"), {}));
  const int g =
      model->add_marker(make_ground_marker("g", model->markers()[mk].c, Mat3::Identity()));
  model->add_element(std::make_unique<SpringDamper>("spring", std::vector<int>{g, mk},
                                                    Vec3(k, k, k), Vec3(c, c, c), Vec3::Zero(),
                                                    Vec3::Zero(), Vec3::Zero(), Vec3::Zero()));
  model->bodies()[0].q0 = Vec3(0, 0, z0 * std::sqrt(m));  // translation mode z: q = sqrt(m) dz
  return model;
}

}  // namespace

TEST(CoupledBodies, SdofThroughTheFullStackAllIntegrators) {
  // Reference: damped free vibration z(t) = e^{-zeta w t} z0 (cos wd t + zeta w / wd sin wd t).
  double m;
  const double k = 4e4, z0 = 1e-3;
  auto probe = sdof_model(k, 0, z0, m);
  const double w = std::sqrt(k / m), zeta = 0.02, c = 2 * zeta * w * m;
  const double wd = w * std::sqrt(1 - zeta * zeta);
  auto exact = [&](double t) {
    return std::exp(-zeta * w * t) * z0 * (std::cos(wd * t) + zeta * w / wd * std::sin(wd * t));
  };
  const double T = 2 * M_PI / w;
  for (const auto& s :
       {settings("ida", 1e-9, 0), settings("cvode", 1e-9, 0),
        settings("generalized-alpha", 0, T / 2000), settings("linear-acceleration", 0, T / 2000)}) {
    auto model = sdof_model(k, c, z0, m);
    const int watch = model->find_marker("com");
    const double z_ref0 = model->markers()[watch].c.z();
    RunResult r = simulate(*model, {watch}, s, 3 * T, 60);
    double err = 0;
    for (std::size_t i = 0; i < r.t.size(); ++i)
      err = std::max(err, std::abs(r.p[i].z() - z_ref0 - exact(r.t[i])));
    std::cout << s.name << ": max |z - z_exact| / z0 = " << err / z0 << " (" << r.stats.steps
              << " steps)\n";
    EXPECT_LT(err / z0, 1e-4) << s.name;
  }
}

namespace {

// Two flexible bodies: a balanced shaft (truss beam spinning about its own axis
// through its centre of mass, as a crankshaft LOF is attached to its axis)
// coupled at both ends to a block hung on ground springs.
std::unique_ptr<Model> two_bodies(const Lof& shaft_lof) {
  auto model = std::make_unique<Model>();
  TrussBeamSpec spec;
  spec.segments = 6;
  spec.length = 0.6;
  spec.width = 0.04;
  BuildOptions opt;
  opt.num_elastic = 4;
  opt.damping_ratio = 0.01;
  auto shaft = std::make_shared<ModalBody>(build_modal_body("shaft", make_truss_beam(spec), opt));
  auto block = std::make_shared<ModalBody>(test_bodies::random_body(30, 4, 42));
  model->add_body("shaft", shaft, shaft_lof);
  model->add_body("block", block, Lof::fixed(Vec3(0, 0, 0), Mat3::Identity()));
  const int s1 =
      model->add_marker(make_set_marker("s1", 0, *shaft, shaft->node_sets.at("end0"), {}));
  const int s2 =
      model->add_marker(make_set_marker("s2", 0, *shaft, shaft->node_sets.at("section3"), {}));
  const int s3 =
      model->add_marker(make_set_marker("s3", 0, *shaft, shaft->node_sets.at("end1"), {}));
  // Block markers at the shaft markers' places at t = 0, carried by block node 0.
  auto at = [&](const std::string& n, int shaft_marker) {
    Marker mk = make_node_marker(n, 1, *block, block->node_ids[0]);
    const LofState L0 = shaft_lof.at(0.0);
    mk.c = L0.p_GL + L0.R_GL * model->markers()[shaft_marker].c;
    return model->add_marker(mk);
  };
  const int b1 = at("b1", s1), b2 = at("b2", s2), b3 = at("b3", s3);
  const Vec3 c(20, 20, 20);
  auto sd = [&](const std::string& n, int a, int b, const Vec3& kk, const Vec3& kr) {
    model->add_element(std::make_unique<SpringDamper>(n, std::vector<int>{a, b}, kk, c, kr,
                                                      Vec3::Zero(), Vec3::Zero(), Vec3::Zero()));
  };
  sd("c1", b1, s1, Vec3(2e5, 2e5, 2e5), Vec3::Zero());
  sd("c2", b2, s2, Vec3(0, 2e5, 2e5), Vec3::Zero());
  sd("c3", b3, s3, Vec3(2e5, 2e5, 2e5), Vec3::Zero());
  for (int i : {3, 9, 17, 25}) {
    const int bn = model->add_marker(
        make_node_marker("bn" + std::to_string(i), 1, *block, block->node_ids[i]));
    const int g = model->add_marker(
        make_ground_marker("g" + std::to_string(i), block->s.row(i).transpose(), Mat3::Identity()));
    sd("m" + std::to_string(i), g, bn, Vec3(5e5, 5e5, 5e5), Vec3::Zero());
  }
  // Initial elastic and rigid velocities (the rigid spin about the axis stays free).
  model->bodies()[0].v0 = Vec::LinSpaced(shaft->num_modes(), 0.02, -0.03);
  model->bodies()[1].q0 = Vec::LinSpaced(block->num_modes(), 1e-5, -2e-5);
  return model;
}

Lof shaft_spin() {
  return Lof::spin(Vec3::Zero(), Mat3::Identity(), Vec3::UnitX(), 0.0, {0.0}, {300.0});
}

}  // namespace

TEST(CoupledBodies, FourIntegratorsAgreeOnSpinningFlexibleBodies) {
  const double t_end = 0.04;
  auto ref_model = two_bodies(shaft_spin());
  std::vector<int> watch = {ref_model->find_marker("s1"), ref_model->find_marker("s3"),
                            ref_model->find_marker("bn9")};
  RunResult ref = simulate(*ref_model, watch, settings("ida", 1e-10, 0), t_end, 40);
  double scale = 0;
  for (std::size_t k = 0; k < ref.p.size(); ++k)
    scale = std::max(scale, (ref.p[k] - ref.p.front()).cwiseAbs().maxCoeff());
  ASSERT_GT(scale, 1e-6) << "the bodies must move";
  struct Expect {
    IntegratorSettings s;
    double tol;
  };
  for (const auto& e :
       {Expect{settings("ida", 1e-7, 0), 1e-3}, Expect{settings("cvode", 1e-7, 0), 1e-3},
        Expect{settings("generalized-alpha", 0, 2e-6), 2e-3},
        Expect{settings("linear-acceleration", 0, 2e-6), 2e-3}}) {
    auto model = two_bodies(shaft_spin());
    RunResult r = simulate(*model, watch, e.s, t_end, 40);
    const double d = max_diff(r, ref) / scale;
    std::cout << e.s.name << ": max marker deviation / motion amplitude = " << d << " ("
              << r.stats.steps << " steps, " << r.stats.residual_evals << " residuals)\n";
    EXPECT_LT(d, e.tol) << e.s.name;
  }
}

TEST(CoupledBodies, TrackingAndSpinFramesAgree) {
  const double t_end = 0.04;
  const Lof spin = shaft_spin();
  const LofState L0 = spin.at(0.0);
  auto a = two_bodies(spin);
  auto b = two_bodies(Lof::tracking(L0.p_GL, L0.R_GL, Vec3::Zero(), L0.w_GL_G, 1e-3));
  std::vector<int> watch = {a->find_marker("s1"), a->find_marker("s3"), a->find_marker("bn9")};
  RunResult ra = simulate(*a, watch, settings("ida", 1e-10, 0), t_end, 40);
  RunResult rb = simulate(*b, watch, settings("ida", 1e-10, 0), t_end, 40);
  double scale = 0;
  for (std::size_t k = 0; k < ra.p.size(); ++k)
    scale = std::max(scale, (ra.p[k] - ra.p.front()).cwiseAbs().maxCoeff());
  const double d = max_diff(ra, rb) / scale;
  std::cout << "tracking vs spin: max marker deviation / motion amplitude = " << d << " ("
            << rb.stats.restarts << " re-anchors)\n";
  EXPECT_GT(rb.stats.restarts, 30);
  EXPECT_LT(d, 1e-3);
}
