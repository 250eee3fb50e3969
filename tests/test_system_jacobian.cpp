// The analytic sparse Jacobian (K = df/dq, C = df/dv) of a coupled system
// against central finite differences of f, and the spring-damper's own
// derivatives against the element's finite-difference fallback.
#include <gtest/gtest.h>

#include "elements/spring_damper.h"
#include "fd_check.h"
#include "io/scene.h"
#include "random_body.h"
#include "solver/system.h"

using namespace evas;

namespace {

std::unique_ptr<Model> coupled_model() {
  auto m = std::make_unique<Model>();
  m->gravity = Vec3(0, 0, -9.81);
  auto a = std::make_shared<ModalBody>(test_bodies::random_body(20, 4, 1));
  auto b = std::make_shared<ModalBody>(test_bodies::random_body(25, 3, 2));
  m->add_body(
      "shaft", a,
      Lof::spin(Vec3(0, 0, 0), Mat3::Identity(), Vec3::UnitX(), 0.2, {0.0, 1.0}, {100.0, 150.0}));
  m->add_body("block", b, Lof::fixed(Vec3(0, 0.01, 0), Mat3::Identity()));
  const int ma = m->add_marker(make_set_marker("shaft.end", 0, *a, a->node_sets.at("first4"), {}));
  const int mb = m->add_marker(make_set_marker("block.bore", 1, *b, b->node_sets.at("first4"), {}));
  const int mn = m->add_marker(make_node_marker("block.node", 1, *b, b->node_ids[7]));
  const int g = m->add_marker(make_ground_marker("ground", Vec3(0.1, 0.2, -0.1), Mat3::Identity()));
  m->add_element(std::make_unique<SpringDamper>(
      "couple", std::vector<int>{ma, mb}, Vec3(1e6, 2e6, 3e6), Vec3(100, 200, 300),
      Vec3(1e4, 2e4, 3e4), Vec3(1, 2, 3), Vec3(0.01, 0, 0), Vec3(5, 0, 0)));
  m->add_element(std::make_unique<SpringDamper>("mount", std::vector<int>{g, mn},
                                                Vec3(5e5, 5e5, 1e6), Vec3(50, 50, 80), Vec3::Zero(),
                                                Vec3::Zero(), Vec3::Zero(), Vec3::Zero()));
  return m;
}

}  // namespace

TEST(SystemJacobian, MatchesFiniteDifferences) {
  auto model = coupled_model();
  System sys(*model);
  const int n = sys.size();
  Vec q = Vec::Random(n) * 1e-3, v = Vec::Random(n) * 0.1;
  const double t = 0.37;
  // f is affine in v and nearly so in q: steps large enough to keep round-off
  // (|f| ~ 1e6) far below the tolerance. A finite-difference entry outside the
  // fixed sparsity pattern counts as an error too.
  const auto err = test_fd::jacobian_fd_error(sys, t, q, v, 1e-6, 1e-4);
  std::cout << "max relative FD error: K " << err.K << ", C " << err.C << "\n";
  EXPECT_LT(err.K, 1e-6);
  EXPECT_LT(err.C, 1e-6);
}

TEST(SpringDamper, AnalyticDerivativesMatchFallback) {
  SpringDamper sd("k", {0, 1}, Vec3(1e5, 2e5, 3e5), Vec3(10, 20, 30), Vec3(1e3, 2e3, 3e3),
                  Vec3(1, 2, 3), Vec3(0.1, 0, 0), Vec3(0, 0, 7));
  MarkerMotion m[2];
  m[0].p = Vec3(0.1, 0.2, 0.3);
  m[1].p = Vec3(0.25, 0.18, 0.33);
  m[0].v = Vec3(1, 2, 3);
  m[1].v = Vec3(-1, 0.5, 2);
  m[0].psi = Vec3(0.01, 0.02, 0.5);
  m[1].psi = Vec3(0.0, -0.01, 0.7);
  m[0].w = Vec3(3, 2, 1);
  m[1].w = Vec3(0, 1, 2);
  m[0].R = rotation_from_vector(Vec3(0.3, -0.2, 0.5));
  Mat D(12, 24), Dfd(12, 24);
  sd.derivatives(0.0, m, D);
  sd.derivatives_fd(0.0, m, Dfd);
  EXPECT_LT((D - Dfd).cwiseAbs().maxCoeff(), 1e-6 * D.cwiseAbs().maxCoeff());
  // Action and reaction: total force zero and total moment about the origin zero.
  MarkerLoad l[2];
  sd.evaluate(0.0, m, l);
  EXPECT_LT((l[0].F + l[1].F).norm(), 1e-9);
  const Vec3 Mo = l[0].M + l[1].M + m[0].p.cross(l[0].F) + m[1].p.cross(l[1].F);
  EXPECT_LT(Mo.norm(), 1e-9 * l[1].F.norm());
}

// Problem::force_jacobian_combination: ck K + cc C formed directly (System) and
// by the default (force_jacobian, then the sum) equal the sum of force_jacobian's
// K and C, for frames that spin and that stay, and for the paper's engine.
TEST(SystemJacobian, CombinationEqualsTheSumOfKAndC) {
  const std::string engine = std::string(EVAS_SOURCE_DIR) + "/validation/engine/engine.yaml";
  Scene scene = read_scene(engine);
  auto model = coupled_model();
  for (Model* m : {model.get(), scene.model.get()}) {
    System sys(*m);
    const int n = sys.size();
    Vec q0, v0;
    sys.initial_state(q0, v0);
    const Vec q = q0 + Vec::Random(n) * 1e-6, v = v0 + Vec::Random(n) * 1e-2;
    SpMat K = sys.jacobian_pattern(), C = K, S = K;
    const double t = 0.0123, ck = 3.7e-11, cc = 4.6e-6;  // (1 - af) beta h^2, (1 - af) gamma h
    sys.force_jacobian(t, q.data(), v.data(), K, C);
    const Eigen::Map<const Vec> k(K.valuePtr(), K.nonZeros()), c(C.valuePtr(), C.nonZeros());
    const Vec sum = ck * k + cc * c;
    sys.force_jacobian_combination(t, q.data(), v.data(), ck, cc, S);
    const Eigen::Map<const Vec> s(S.valuePtr(), S.nonZeros());
    EXPECT_LE((s - sum).lpNorm<Eigen::Infinity>(), 1e-13 * sum.lpNorm<Eigen::Infinity>()) << n;
    sys.Problem::force_jacobian_combination(t, q.data(), v.data(), ck, cc, S);  // the default
    EXPECT_LE((s - sum).lpNorm<Eigen::Infinity>(), 1e-13 * sum.lpNorm<Eigen::Infinity>()) << n;
    EXPECT_GT(sum.lpNorm<Eigen::Infinity>(), 0.0);
  }
}
