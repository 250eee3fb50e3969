// evas_bench: measured cost tables for docs/performance.md.
//  1. One evaluation of Eq. 1 for one body: invariant form (O(n^2)) against the
//     paper's literal node sums (O(N n)), for N = 1k, 10k, 100k nodes.
//  2. IDA with KLU against IDA with dense LU as the number of modes grows, on a
//     chain of flexible bodies coupled by spring-dampers.
//  3. The paper's engine, Case 1 and Case 2 (bench/bench_engine.h).
//  4. Scaling of the engine's cost per step with modes and elements
//     (bench/bench_scaling.h).
//  5. The journal bearing's film models per evaluation (bench/bench_film.h).
// usage: evas_bench [OUT.md] [ENGINE.yaml] (default validation/engine/engine.yaml,
// relative to the working directory: `make bench` runs it from the source tree)
// Times are the minimum over repeats after a warm-up; ratios measured in one run
// are what the document compares (the machine is shared and noisy).
#include <chrono>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <random>
#include <sstream>

#include "../tests/random_body.h"
#include "bench_baseline.h"
#include "bench_engine.h"
#include "bench_film.h"
#include "bench_periodic.h"
#include "bench_quasi_static.h"
#include "bench_scaling.h"
#include "elements/spring_damper.h"
#include "integrators/integrator.h"
#include "io/results.h"
#include "io/scene.h"
#include "model/invariants.h"
#include "solver/system.h"

using namespace evas;
using Clock = std::chrono::steady_clock;

namespace {

template <class F>
double min_time(F&& f, int repeats) {
  f();  // warm-up
  double best = 1e300;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = Clock::now();
    f();
    best = std::min(best, std::chrono::duration<double>(Clock::now() - t0).count());
  }
  return best;
}

// A body with N nodes and n random (not orthonormal) modes: the cost of both
// evaluations does not depend on the values.
ModalBody bench_body(int N, int n) {
  ModalBody b;
  b.name = "bench";
  std::mt19937 gen(1);
  std::uniform_real_distribution<double> U(-1, 1);
  b.s.resize(N, 3);
  std::vector<Triplet> t;
  for (int i = 0; i < N; ++i) {
    b.node_ids.push_back(i + 1);
    b.s.row(i) << U(gen), U(gen), U(gen);
    t.emplace_back(i, i, 1.0 + 0.1 * U(gen));
  }
  b.mass.resize(N, N);
  b.mass.setFromTriplets(t.begin(), t.end());
  b.modes = Mat::NullaryExpr(3 * N, n, [&]() { return U(gen); });
  b.eigenvalues = Vec::Constant(n, 1e4);
  b.damping = Vec::Constant(n, 1.0);
  b.kinds.assign(n, ModeKind::Elastic);
  return b;
}

std::string residual_table() {
  std::ostringstream os;
  const int n = 48;  // the paper's crankshaft: 6 rigid + 42 elastic modes
  os << "| nodes N | modes n | invariant form [us] | literal node sums [us] | literal / invariant "
        "|\n|---:|---:|---:|---:|---:|\n";
  for (int N : {1000, 10000, 100000}) {
    const ModalBody b = bench_body(N, n);
    const ModalInvariants inv = compute_invariants(b);
    const Mat3 A = rotation_from_vector(Vec3(0.1, 0.2, 0.3));
    const Vec3 a(1, 2, 3), w(300, 10, 5), al(1e3, 0, 0);
    const Vec q = Vec::Random(n) * 1e-4, qd = Vec::Random(n), qdd = Vec::Random(n);
    const Eigen::Matrix<double, Eigen::Dynamic, 3> F =
        Eigen::Matrix<double, Eigen::Dynamic, 3>::Zero(N, 3);
    Vec f0(n), r(n);
    Mat KW(n, n), G(n, n);
    const int reps_inv = 2000;
    const double t_inv =
        min_time(
            [&] {
              for (int k = 0; k < reps_inv; ++k) {
                frame_terms(inv, A.transpose() * a, A.transpose() * w, A.transpose() * al, f0, KW,
                            G);
                r = qdd + f0 + b.eigenvalues.cwiseProduct(q) + b.damping.cwiseProduct(qd);
                r.noalias() += KW * q;
                r.noalias() += G * qd;
              }
            },
            5) /
        reps_inv;
    Vec lit;
    const int reps_lit = N >= 100000 ? 1 : 5;
    const double t_lit = min_time(
                             [&] {
                               for (int k = 0; k < reps_lit; ++k)
                                 lit = eq1_literal(b, A, a, w, al, q, qd, qdd, F);
                             },
                             3) /
                         reps_lit;
    const double diff = (lit - r).cwiseAbs().maxCoeff() / lit.cwiseAbs().maxCoeff();
    os << "| " << N << " | " << n << " | " << std::fixed << std::setprecision(1) << t_inv * 1e6
       << " | " << t_lit * 1e6 << " | " << std::setprecision(0) << t_lit / t_inv << " |\n";
    std::cerr << "residual N=" << N << " done (relative difference of the two forms "
              << std::scientific << diff << ")\n";
    if (diff > 1e-9) throw std::runtime_error("invariant and literal forms disagree");
  }
  return os.str();
}

// Chain of `nb` bodies of n modes each, the first spinning, neighbours coupled.
std::unique_ptr<Model> chain(int nb, int n_el) {
  auto m = std::make_unique<Model>();
  std::vector<int> first, last;
  for (int b = 0; b < nb; ++b) {
    auto body = std::make_shared<ModalBody>(test_bodies::random_body(30, n_el, 100 + b));
    const Lof lof = b == 0
                        ? Lof::spin(Vec3::Zero(), Mat3::Identity(), Vec3::UnitX(), 0, {0.0}, {50.0})
                        : Lof::fixed(Vec3(0, 0, 0), Mat3::Identity());
    m->add_body("b" + std::to_string(b), body, lof);
    first.push_back(
        m->add_marker(make_node_marker("f" + std::to_string(b), b, *body, body->node_ids.front())));
    last.push_back(
        m->add_marker(make_node_marker("l" + std::to_string(b), b, *body, body->node_ids.back())));
  }
  const int g = m->add_marker(make_ground_marker("g", Vec3::Zero(), Mat3::Identity()));
  const Vec3 k(1e5, 1e5, 1e5), c(10, 10, 10);
  for (int b = 0; b + 1 < nb; ++b)
    m->add_element(std::make_unique<SpringDamper>(
        "k" + std::to_string(b), std::vector<int>{last[b], first[b + 1]}, k, c, Vec3::Zero(),
        Vec3::Zero(), Vec3::Zero(), Vec3::Zero()));
  m->add_element(std::make_unique<SpringDamper>("g", std::vector<int>{g, first[0]}, k, c,
                                                Vec3::Zero(), Vec3::Zero(), Vec3::Zero(),
                                                Vec3::Zero()));
  m->bodies()[0].v0 = Vec::Constant(m->bodies()[0].n(), 0.01);
  return m;
}

std::string klu_table() {
  std::ostringstream os;
  os << "| bodies | modes per body | states (2n) | Jacobian nonzeros | dense LU [s] | KLU [s] | "
        "second-order [s] | dense / KLU | second-order / KLU | steps (dense, KLU, second-order) "
        "|\n|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  const int nb = 8;
  const char* solvers[3] = {"dense", "klu", "second-order"};
  for (int n_el : {4, 14, 34, 74}) {
    double times[3];
    long steps[3];
    long nnz = 0;
    for (int s = 0; s < 3; ++s) {
      auto model = chain(nb, n_el);
      System sys(*model);
      nnz = sys.jacobian_pattern().nonZeros();
      IntegratorSettings set;
      set.name = "ida";
      set.rtol = 1e-6;
      set.atol = 1e-9;
      set.linear_solver = solvers[s];
      std::vector<double> outs;
      for (int k = 1; k <= 20; ++k) outs.push_back(0.005 * k);
      times[s] = min_time(
          [&] {
            auto integ = make_integrator("ida");
            Vec q, v;
            sys.initial_state(q, v);
            integ->init(sys, 0.0, q, v, set);
            integrate(*integ, sys, 0.0, outs, [](double, const Vec&, const Vec&) {});
            steps[s] = integ->stats().steps;
          },
          2);
    }
    const int states = 2 * nb * (n_el + 6);
    os << "| " << nb << " | " << n_el + 6 << " | " << states << " | " << 2 * nnz + states << " | "
       << std::fixed << std::setprecision(3) << times[0] << " | " << times[1] << " | " << times[2]
       << " | " << std::setprecision(2) << times[0] / times[1] << " | " << times[2] / times[1]
       << " | " << steps[0] << ", " << steps[1] << ", " << steps[2] << " |\n";
    std::cerr << "ida n=" << n_el + 6 << " done\n";
  }
  return os.str();
}

// "72 modal coordinates, 16 elements" of the engine scene, as it stands.
std::string engine_size(const std::string& path) {
  const Scene scene = read_scene(path);
  return std::to_string(scene.model->size()) + " modal coordinates, " +
         std::to_string(scene.model->elements().size()) + " elements";
}

}  // namespace

int main(int argc, char** argv) {
  // `evas_bench --periodic ENGINE`: that section alone, to stdout
  if (argc > 1 && std::string(argv[1]) == "--periodic") {
    std::cout << bench::periodic_table(argc > 2 ? argv[2] : "validation/engine/engine.yaml",
                                       EVAS_PROGRAM);
    return 0;
  }
  // `evas_bench --quasi-static ENGINE`: that section alone, to stdout
  if (argc > 1 && std::string(argv[1]) == "--quasi-static") {
    std::cout << bench::quasi_static_table(argc > 2 ? argv[2] : "validation/engine/engine.yaml");
    return 0;
  }
  // `evas_bench --films`: the film models' cost per evaluation alone, to stdout
  if (argc > 1 && std::string(argv[1]) == "--films") {
    std::cout << bench::film_cost_table();
    return 0;
  }
  const std::string out = argc > 1 ? argv[1] : "";
  const std::string engine = argc > 2 ? argv[2] : "validation/engine/engine.yaml";
  // the evas of 2026-11-24 and its engine scene (bench/baseline.sh)
  const std::string old_evas = argc > 3 ? argv[3] : "";
  const std::string old_engine = argc > 4 ? argv[4] : "";
  std::ostringstream doc;
  doc << "# Performance\n\n"
      << "Measured by `make bench` (`evas_bench`, which regenerates this file, and "
         "`bench/sweep_scaling.py`, which appends its last section). Times are the "
         "minimum over repeats after a warm-up on the machine that ran it (2 cores, shared); "
         "compare the ratios within a table, not absolute times across machines (nor across "
         "tables: a shared machine's speed can drift within one run, docs/engine-speed.md, "
         "eighth session). evas was built "
         "for "
      << build_arch()
      << " (`EVAS_ARCH`, README). What limits the "
         "engine's speed, why steps are rejected and how its solver settings were chosen: "
         "`docs/engine-speed.md`.\n\n"
      << "## One evaluation of Eq. 1: invariants against literal node sums\n\n"
      << "One body, lumped masses, all frame terms active (spin, Euler, LOF acceleration). "
         "The invariant form costs O(n^2) whatever the node count; the literal form, the "
         "paper's sums over nodes, costs O(N n). Both give the same vector (checked in the "
         "run, relative difference < 1e-9, and in `tests/test_invariants.cpp`).\n\n"
      << residual_table() << "\n"
      << "## The journal bearing's film models: cost per evaluation\n\n"
      << "The validation engine's main bearing at 3000 rpm, averaged over 64 states "
         "(eccentricity ratio 0.05 to 0.95, every direction, a squeeze velocity); set-up is "
         "the element's construction (the table's Reynolds solves). "
         "docs/elements-journal-bearing.md, \"Film models\".\n\n"
      << bench::film_cost_table() << "\n"
      << "## IDA: dense LU, KLU and the second-order solver as the number of modes grows\n\n"
      << "A chain of 8 flexible bodies (6 rigid + elastic modes each), the first spinning at "
         "50 rad/s, neighbours coupled by spring-dampers, 0.1 s simulated, rtol 1e-6, atol "
         "1e-9, analytic Jacobian. The iteration matrix has dense diagonal body blocks and "
         "coupling blocks only between neighbours. dense and KLU factorize the 2n x 2n "
         "first-order matrix; second-order the n x n matrix K + cj C + cj^2 I (dense LU up to "
         "n = 200, KLU above; Jacobians reused over up to 10 steps).\n\n"
      << klu_table() << "\n"
      << "## The paper's engine: cost, parts and accuracy\n\n"
      << "`validation/engine/engine.yaml` (" << engine_size(engine)
      << ", 0.24 s = six "
         "720 deg cycles at 3000 rpm), Case 1 (soft mounts) and Case 2 (mounts at 1e9 N/m): "
         "IDA with KLU or the second-order solver, atol = rtol / 1e4, and generalized-alpha "
         "(rho_inf 0.8, effective mass, increment test at rtol 1e-5, atol 1e-9) at fixed steps (a "
         "step whose iteration fails taken as sub-steps; the step of 9.26e-6 s is 1/6 deg of "
         "crank angle, so that the steps land on the 1 deg outputs, with the increment test at "
         "rtol 3e-5), and adaptive (PI step control of the "
         "local error at rtol 3e-4, atol 3e-8, first step 8e-6 s); "
         "wall time of init + integrate (minimum of 3 runs, the repeats interleaved over the "
         "table's runs so that a slow phase of the shared machine rarely spans all three) "
         "including the outputs (4,320 rows "
         "of 63 channels). Real-time factor = wall / simulated time (1 = real time). Errors "
         "over the last 720 deg of the ten main-bearing load channels (main1..5 fx, fy) against "
         "a reference run (IDA, rtol 1e-9, atol 1e-12): *of the largest load*, the largest "
         "difference divided by the largest reference load among them; *per channel* (the "
         "measure of `evas study` and of the real-time goal), the largest difference of each "
         "channel divided by that channel's amplitude about its mean, the largest over the "
         "channels.\n\n"
      << bench::engine_table(engine) << "\n"
      << "## Side by side with the code of 2026-11-24\n\n"
      << "The evas that issue 12 measured its starting point with (commit baefa5a, "
         "2026-11-24: IDA with KLU on the 144 x 144 first-order matrix, the portable x86-64 "
         "build of then, its own scene, bodies and pressure table), built from this clone's "
         "history by `bench/baseline.sh`, and today's evas, as `evas run` processes in "
         "turn on the same machine (old, new, old, new, ...; 3 pairs, medians). IDA at the "
         "same rtol (atol = rtol / 1e4), today with the scene's second-order solver; and "
         "today's cheapest setting below 1e-3 per channel (generalized-alpha at 1/6 deg, "
         "effective mass, increment test at rtol 3e-5) against the old IDA at rtol 1e-5. us "
         "per step: the integrator's own wall time (summary.json) over its steps; ratio: old / "
         "new, pair by pair (how many times fewer us per step, or how many times faster the "
         "whole process). Real-time factor: today's whole process (start-up, reading the "
         "bodies, results file) over the 0.24 s simulated.\n\n"
      << bench::baseline_table(engine, EVAS_PROGRAM, old_evas, old_engine) << "\n"
      << "## Scaling of the engine's cost per step\n\n"
      << "IDA with the second-order solver, rtol 1e-5, atol 1e-9, the first 0.06 s of Case 1; "
         "wall time of init + integrate (minimum of 2 runs) per step; peak memory of the same "
         "run as an `evas run` process (its maximum resident set, outputs included).\n\n"
      << bench::scaling_table(engine, EVAS_PROGRAM) << "\n"
      << "## Quasi-static modes: the model's error and the cost\n\n"
      << "Case 1 with the elastic modes of both bodies above a threshold quasi-static "
         "(`modes: {quasi_static_above: F}`, docs/theory.md section 11): their inertia left "
         "out, their static compliance kept. Errors per channel (as above) against the full, "
         "all-dynamic model's reference (IDA, KLU, rtol 1e-9, atol 1e-12): the tight run "
         "(IDA, rtol 1e-8) is the model's error alone, the others add their integration "
         "error. Generalized-alpha with the increment test at rtol 3e-5, atol 1e-9, a failed "
         "step taken as sub-steps; IDA with the second-order solver, atol = rtol / 1e4. Wall "
         "time of init + integrate, minimum of 3 runs (the tight run once). Conclusion in "
         "docs/engine-speed.md (\"Quasi-static modes\").\n\n"
      << bench::quasi_static_table(engine) << "\n"
      << "## The steady cycle: evas periodic against a run from rest\n\n"
      << "Case 1: `evas periodic` (recursive projection, defect 3e-4: within 2.4e-4 of the "
         "settled cycle, docs/periodic.md) against `evas run` to the scene's 0.24 s (six "
         "cycles from rest, whose last is 1.2e-2 from the settled cycle in the bearing loads "
         "and 0.29 in the mount forces), whole processes in turn; each method of evas "
         "periodic once; the 8-point sweep (1500-5000 rpm) on periodic points against 0.12-s "
         "runs, serial.\n\n"
      << bench::periodic_table(engine, EVAS_PROGRAM) << "\n";
  std::cout << doc.str();
  if (!out.empty()) {
    std::ofstream f(out);
    f << doc.str();
    std::cerr << "wrote " << out << "\n";
  }
  return 0;
}
