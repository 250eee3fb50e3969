// The residual and Jacobian evaluations allocate no memory once a run has
// started (issue: "allocate no memory once a run has started"). Counts calls
// of the global operator new around warm evaluations.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "elements/spring_damper.h"
#include "integrators/second_order_ls.h"
#include "random_body.h"
#include "solver/first_order.h"
#include "solver/system.h"

namespace {
std::atomic<long> g_news{0};
std::atomic<long> g_mallocs{0};
}  // namespace

// Eigen allocates with malloc, not operator new: count malloc too, by
// interposing it on glibc's own (__libc_malloc) in this test executable.
extern "C" void* __libc_malloc(std::size_t);
extern "C" void* malloc(std::size_t n) {
  ++g_mallocs;
  return __libc_malloc(n);
}

// The replacement operators pair malloc with free; GCC cannot see that pairing.
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void* operator new(std::size_t n) {
  ++g_news;
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

using namespace evas;

TEST(NoAllocation, ResidualAndJacobianAfterWarmUp) {
  Model model;
  auto a = std::make_shared<ModalBody>(test_bodies::random_body(40, 20, 1));
  auto b = std::make_shared<ModalBody>(test_bodies::random_body(40, 30, 2));
  model.add_body("a", a,
                 Lof::spin(Vec3::Zero(), Mat3::Identity(), Vec3::UnitX(), 0, {0.0}, {300.0}));
  model.add_body("b", b, Lof::fixed(Vec3::Zero(), Mat3::Identity()));
  const int ma = model.add_marker(make_set_marker("a", 0, *a, a->node_sets.at("first4"), {}));
  const int mb = model.add_marker(make_set_marker("b", 1, *b, b->node_sets.at("first4"), {}));
  const int g = model.add_marker(make_ground_marker("g", Vec3::Zero(), Mat3::Identity()));
  model.add_element(std::make_unique<SpringDamper>(
      "k", std::vector<int>{ma, mb}, Vec3(1e6, 1e6, 1e6), Vec3(10, 10, 10), Vec3(1, 1, 1),
      Vec3::Zero(), Vec3::Zero(), Vec3::Zero()));
  model.add_element(std::make_unique<SpringDamper>(
      "g", std::vector<int>{g, mb}, Vec3(1e6, 1e6, 1e6), Vec3(10, 10, 10), Vec3::Zero(),
      Vec3::Zero(), Vec3::Zero(), Vec3::Zero()));
  System sys(model);
  FirstOrderForm fo(sys);
  const int n = sys.size();
  Vec q = Vec::Random(n) * 1e-4, v = Vec::Random(n), f(n);
  SpMat K = sys.jacobian_pattern(), C = sys.jacobian_pattern();
  Vec y(2 * n), yd(2 * n), F(2 * n);
  y << q, v;
  yd.setRandom();
  SpMat Jr = fo.residual_pattern(), Je = fo.rhs_pattern();
  // warm up
  sys.force(0.1, q.data(), v.data(), f.data());
  sys.force_jacobian(0.1, q.data(), v.data(), K, C);
  sys.force_jacobian_combination(0.1, q.data(), v.data(), 1e-10, 1e-5, K);
  fo.residual(0.1, y.data(), yd.data(), F.data());
  fo.residual_jacobian(0.1, y.data(), 2.0, Jr);
  fo.rhs(0.1, y.data(), F.data());
  fo.rhs_jacobian(0.1, y.data(), Je);
  const long before = g_news.load();
  const long mallocs = g_mallocs.load();
  for (int k = 0; k < 10; ++k) {
    const double t = 0.2 + 0.01 * k;
    sys.force(t, q.data(), v.data(), f.data());
    sys.force_jacobian(t, q.data(), v.data(), K, C);
    sys.force_jacobian_combination(t, q.data(), v.data(), 1e-10, 1e-5, K);
    fo.residual(t, y.data(), yd.data(), F.data());
    fo.residual_jacobian(t, y.data(), 1.5, Jr);
    fo.rhs(t, y.data(), F.data());
    fo.rhs_jacobian(t, y.data(), Je);
  }
  EXPECT_EQ(g_news.load() - before, 0) << "heap allocations in residual/Jacobian evaluations";
  EXPECT_EQ(g_mallocs.load() - mallocs, 0) << "mallocs in residual/Jacobian evaluations";
}

// The second-order solver's factorization and solve, dense (n <= 200) and KLU
// (above), after the first factorization, including the dense path's inverse
// (formed after 40 solves on one factorization).
TEST(NoAllocation, SecondOrderSolverAfterWarmUp) {
  for (int n : {60, 300}) {
    std::vector<Triplet> trip;
    for (int c = 0; c < n; ++c)
      for (int r = std::max(0, c - 2); r <= std::min(n - 1, c + 2); ++r)
        trip.emplace_back(r, c, r == c ? 1e4 : 1.0);
    SpMat P(n, n);
    P.setFromTriplets(trip.begin(), trip.end());
    SecondOrderSolver so(P);
    so.K() = P;
    so.C() = P * 1e-3;
    so.set_coefficients(1e3, -1.0, 1.0, 1e3, 1.0);
    Vec r = Vec::Ones(2 * n);
    ASSERT_TRUE(so.factor());
    so.solve(r.data(), r.data());
    const long news = g_news.load(), mallocs = g_mallocs.load();
    for (int k = 0; k < 5; ++k) {
      so.set_coefficients(1e3 + k, -1.0, 1.0, 1e3 + k, 1.0);
      ASSERT_TRUE(so.factor());
      so.solve(r.data(), r.data());
    }
    // many solves on one factorization: the dense path inverts it on the way
    for (int k = 0; k < 100; ++k) so.solve(r.data(), r.data());
    EXPECT_EQ(g_news.load() - news, 0) << "n = " << n;
    EXPECT_EQ(g_mallocs.load() - mallocs, 0) << "n = " << n;
  }
}
