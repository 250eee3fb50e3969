// The problem library (problems/library.h): each problem's analytic parts
// against central differences, its start on the constraints, and IDA and
// generalized-alpha reaching stated significant digits at the end point against
// the published references of the Test Set for IVP Solvers (Mazzia &
// Magherini, Bari: problems andrews and caraxis) and the pendulum's exact
// solution; the `evas problem` command.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>

#include "dae/implicit_form.h"
#include "integrators/implicit_ida.h"
#include "integrators/implicit_radau.h"
#include "integrators/integrator.h"
#include "integrators/settings.h"
#include "problems/library.h"

namespace evas {
namespace {

using problems::LibraryProblem;

// A state near the start with every velocity and coordinate perturbed.
void perturbed(Problem& p, Vec& q, Vec& v) {
  p.initial_state(q, v);
  for (int i = 0; i < q.size(); ++i) {
    q(i) += 1e-2 * std::sin(1.0 + i);
    v(i) += 0.5 * std::cos(2.0 + i);
  }
}

double rel_err(const Mat& a, const Mat& b) {
  return (a - b).cwiseAbs().maxCoeff() / (1.0 + b.cwiseAbs().maxCoeff());
}

TEST(Problems, PartsMatchDifferences) {
  for (const LibraryProblem& lp : problems::library()) {
    SCOPED_TRACE(lp.name);
    if (lp.implicit()) continue;  // ImplicitPartsMatchDifferences
    auto p = lp.make();
    const int n = p->size(), m = p->constraint_count();
    Vec q, v;
    perturbed(*p, q, v);
    const double t = 0.3 * lp.t_end, h = 1e-5;
    SpMat K = p->jacobian_pattern(), C = K, G = p->constraint_pattern(), M = p->mass_pattern();
    p->force_jacobian(t, q.data(), v.data(), K, C);
    p->constraint_jacobian(t, q.data(), G);
    Mat Kfd(n, n), Cfd(n, n), Gfd(m, n), Mq(n, n);
    Vec fp(n), fm(n), gp(m), gm(m);
    for (int c = 0; c < n; ++c) {
      for (int which : {0, 1}) {
        // a step relative to the coordinate; larger in v, where the crank's
        // rod stiffness (forces ~1e5 N) leaves rounding of 1e-11 in f
        const double hc = (which ? 10.0 * h : h) * std::max(1.0, std::abs((which ? v : q)(c)));
        Vec qp = q, qm = q, vp = v, vm = v;
        (which ? vp : qp)(c) += hc;
        (which ? vm : qm)(c) -= hc;
        p->force(t, qp.data(), vp.data(), fp.data());
        p->force(t, qm.data(), vm.data(), fm.data());
        (which ? Cfd : Kfd).col(c) = (fp - fm) / (2 * hc);
        if (!which) {
          p->constraint(t, qp.data(), v.data(), gp.data(), nullptr, nullptr);
          p->constraint(t, qm.data(), v.data(), gm.data(), nullptr, nullptr);
          Gfd.col(c) = (gp - gm) / (2 * hc);
        }
      }
    }
    EXPECT_LT(rel_err(Mat(K), Kfd), 1e-7);
    EXPECT_LT(rel_err(Mat(C), Cfd), 1e-7);
    EXPECT_LT(rel_err(Mat(G), Gfd), 1e-7);
    // g' = d/dt g(t, q + t v) and ga = d/dt g'(t, q + t v, v) (q'' = 0), over a
    // time step that moves q by about h
    Vec g(m), gv(m), ga(m), gvp(m), gvm(m);
    p->constraint(t, q.data(), v.data(), g.data(), gv.data(), ga.data());
    const double ht = 0.1 * h / std::max(1.0, v.cwiseAbs().maxCoeff());
    const Vec q1 = q + ht * v, q0 = q - ht * v;
    p->constraint(t + ht, q1.data(), v.data(), gp.data(), gvp.data(), nullptr);
    p->constraint(t - ht, q0.data(), v.data(), gm.data(), gvm.data(), nullptr);
    EXPECT_LT(rel_err(gv, (gp - gm) / (2 * ht)), 1e-7);
    EXPECT_LT(rel_err(ga, (gvp - gvm) / (2 * ht)), 1e-6);
    // M symmetric positive definite
    if (p->has_mass()) {
      p->mass(t, q.data(), M);
      const Mat Md(M);
      EXPECT_LT((Md - Md.transpose()).cwiseAbs().maxCoeff(), 1e-18);
      EXPECT_GT(Eigen::SelfAdjointEigenSolver<Mat>(Md).eigenvalues().minCoeff(), 0.0);
    }
    // the published start lies on the constraints, with consistent velocities
    p->initial_state(q, v);
    p->constraint(0.0, q.data(), v.data(), g.data(), gv.data(), nullptr);
    EXPECT_LT(g.cwiseAbs().maxCoeff(), 1e-14);
    EXPECT_LT(gv.cwiseAbs().maxCoeff(), 1e-14);
  }
}

// The first-order implicit problems (chemakzo, transamp, wheelset): df/dy against central
// differences at a state near the start, and the published start consistent
// (M y'(0) = f(0, y(0)) to the digits the test set gives y'(0) with).
TEST(Problems, ImplicitPartsMatchDifferences) {
  int seen = 0;
  for (const LibraryProblem& lp : problems::library()) {
    if (!lp.implicit()) continue;
    SCOPED_TRACE(lp.name);
    ++seen;
    auto p = lp.make_implicit();
    const int n = p->size();
    Vec y, yp;
    p->initial(y, yp);
    const Mat M = p->mass();
    Vec f(n), fp(n), fm(n);
    p->f_at(0.0, y, f);
    EXPECT_LT((M * yp - f).cwiseAbs().maxCoeff(), 1e-9 * (1.0 + f.cwiseAbs().maxCoeff()))
        << "M yp - f = " << (M * yp - f).transpose();
    for (int i = 0; i < n; ++i) y(i) *= 1.0 + 1e-3 * std::sin(1.0 + i);
    const double t = 0.3 * lp.t_end;
    Mat J(n, n), Jfd(n, n);
    p->rhs_jacobian(t, y.data(), J);
    for (int c = 0; c < n; ++c) {
      const double h = 1e-7 * (1.0 + std::abs(y(c)));
      Vec a = y, b = y;
      a(c) += h;
      b(c) -= h;
      p->f_at(t, a, fp);
      p->f_at(t, b, fm);
      Jfd.col(c) = (fp - fm) / (2 * h);
    }
    EXPECT_LT(rel_err(J, Jfd), 1e-6) << "J\n" << J << "\nJfd\n" << Jfd;
  }
  EXPECT_EQ(seen, 3);
}

// The slider crank as transcribed (problems/slider_crank.cpp) against the
// report's consistent start (Mazzia & Magherini 2008, II.19: its
// accelerations and multipliers): M(p) a + f + G^T lambda = 0 to the 10 digits
// the report gives its data with.
TEST(Problems, SliderCrankMatchesTheReportsStart) {
  auto p = problems::library_problem("crank").make();
  Vec q, v;
  p->initial_state(q, v);
  Vec a(7), lam(3), f(7);
  a << 0.0, -1.344541576709835e-3, -5.062194924490193e3, -6.829725665986310e-5,
      1.813207639590617e-20, -4.268463266810281, 2.098339029337557e-1;
  lam << -6.552727150584648e-8, 3.824589509350831e2, -4.635908708561371e-9;
  SpMat M = p->mass_pattern(), G = p->constraint_pattern();
  p->mass(0.0, q.data(), M);
  p->constraint_jacobian(0.0, q.data(), G);
  p->force(0.0, q.data(), v.data(), f.data());
  const Vec r = M * a + f + G.transpose() * lam;
  const double scale = (M * a).cwiseAbs().maxCoeff() + f.cwiseAbs().maxCoeff();
  EXPECT_LT(r.cwiseAbs().maxCoeff(), 1e-8 * scale) << r.transpose();
  Vec g(3), gv(3);
  p->constraint(0.0, q.data(), v.data(), g.data(), gv.data(), nullptr);
  EXPECT_LT(g.cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT(gv.cwiseAbs().maxCoeff(), 1e-9);
}

struct EndPoint {
  problems::Score s;
  long steps = 0;
};

EndPoint solve(const std::string& name, const std::string& integrator, const std::string& form,
               double rtol, double atol, double step = 0.0) {
  const LibraryProblem& lp = problems::library_problem(name);
  auto p = lp.make();
  IntegratorSettings s;
  s.name = integrator;
  s.formulation = form;
  s.rtol = rtol;
  s.atol = atol;
  if (step > 0.0) s.step = step;
  s.step_control = step > 0.0 ? StepControl::fixed : s.step_control;
  auto integ = make_integrator(integrator);
  Vec q, v, lam;
  p->initial_state(q, v);
  integ->init(*p, 0.0, q, v, s);
  integ->advance(lp.t_end, true, q, v);
  if (!integ->multipliers(lam)) lam.resize(0);
  EndPoint e;
  e.s = problems::score(lp, q, v, lam, rtol, atol);
  e.steps = integ->stats().steps;
  std::printf("%-9s %-18s %-8s rtol %.0e  mescd %5.2f  scd %5.2f  lambda %5.2f  steps %ld\n",
              name.c_str(), integrator.c_str(), form.c_str(), rtol, e.s.mescd, e.s.scd,
              e.s.mescd_lambda, e.steps);
  return e;
}

// IDA at rtol 1e-8, atol 1e-10 in each formulation: mixed-error digits at the
// end point, floors a little below the values measured (2026-11-24, in the
// comments; for Andrews the portable build / the x86-64-v3 build, whose FMA
// rounds differently). GGL reaches 5 digits on both test-set problems (the
// issue's bar); index-3 leaves v out of the error test and loses accuracy in it.
// Andrews' end-point digits scatter by about +-0.7 from one rtol to the next
// and with the rounding (GGL, portable / x86-64-v3: 4.36 / 4.05 at rtol 3e-8,
// 5.23 / 4.49 at 1e-8, 4.97 / 5.70 at 3e-9, 6.30 / 6.25 at 1e-9): its 5 digits
// are asked at rtol 1e-9.
TEST(Problems, IdaReachesTheReference) {
  struct Case {
    const char* name;
    const char* form;
    double floor;
  };
  const Case cases[] = {
      {"andrews", "ggl", 4.2},       // 5.23 / 4.49
      {"andrews", "index-2", 3.6},   // 4.36 / 3.84
      {"andrews", "index-1", 3.7},   // 4.00 / 3.83
      {"andrews", "index-3", 1.0},   // 1.40 / 1.17
      {"car-axis", "ggl", 5.0},      // 5.51
      {"car-axis", "index-2", 4.9},  // 5.18
      {"car-axis", "index-1", 4.3},  // 4.61
      {"car-axis", "index-3", 2.6},  // 2.96
      {"pendulum", "ggl", 5.0},      // 5.36
      {"pendulum", "index-2",
       4.5},  // 5.19; 5.33 (x86-64-v3) / 4.73 (sanitizer build) on 2026-11-28
      {"pendulum", "index-1", 4.2},  // 4.48
      {"pendulum", "index-3", 2.0},  // 2.24
  };
  for (const Case& c : cases)
    EXPECT_GE(solve(c.name, "ida", c.form, 1e-8, 1e-10).s.mescd, c.floor)
        << c.name << " " << c.form;
  EXPECT_GE(solve("andrews", "ida", "ggl", 1e-9, 1e-11).s.mescd, 5.0);  // 6.30 / 6.25
  // the multipliers of car axis (published) with GGL: 7.04 digits
  EXPECT_GE(solve("car-axis", "ida", "ggl", 1e-8, 1e-10).s.mescd_lambda, 6.5);
}

// GGL on Andrews at a tight tolerance (rtol 1e-10, atol 1e-12). The
// multipliers' weights are scaled by h (Brenan, Campbell & Petzold 1996,
// ch. 5) and must follow the step IDA actually tries: after a failed Newton
// iteration IDA retries at h / 4 with the weights of the first try, and the
// round-off of g in mu's correction grows as 1/h. Without the rescaling every
// retry failed (IDA_CONV_FAIL at t = 0.0293 s, h = 2.4e-15 s). Measured with
// it (x86-64-v3): 6.35 digits, 6.64 with the atol floors of the next test.
TEST(Problems, GglCompletesAndrewsAtRtol1e10) {
  EXPECT_GE(solve("andrews", "ida", "ggl", 1e-10, 1e-12).s.mescd, 5.8);
}

// Every IDA formulation completes both test-set problems at the tightest
// tolerance asked (rtol 1e-12, atol 1e-14). atol is floored at what rounding
// lets each variable reach (10 eps |y_i|max; 1000 eps |q|max for the h-scaled
// multipliers): before, GGL failed in its first steps and index-2 stalled at
// steps of 5e-19 s on Andrews (docs/problems.md). Measured (x86-64-v3):
// Andrews 7.27 / 7.27 / 6.92 / 4.57, car axis 8.39 / 8.32 / 7.73 / 5.25 digits
// for GGL / index-2 / index-1 / index-3; the floors are index-3's.
TEST(Problems, EveryFormulationCompletesAtRtol1e12) {
  const double floor[2][4] = {{6.5, 6.5, 6.2, 3.8}, {7.6, 7.6, 7.0, 4.5}};
  const char* forms[] = {"ggl", "index-2", "index-1", "index-3"};
  const char* names[] = {"andrews", "car-axis"};
  for (int p = 0; p < 2; ++p)
    for (int f = 0; f < 4; ++f)
      EXPECT_GE(solve(names[p], "ida", forms[f], 1e-12, 1e-14).s.mescd, floor[p][f])
          << names[p] << " " << forms[f];
}

// A failure names a variable the error test checks: one made to fail by a step
// limit of 50 (IDA's max_steps) at rtol 1e-12. The message used to name one
// of mu, which IDASetSuppressAlg leaves out of that test.
TEST(Problems, AFailureNamesAVariableInTheErrorTest) {
  const LibraryProblem& lp = problems::library_problem("andrews");
  auto p = lp.make();
  IntegratorSettings s;
  s.name = "ida";
  s.formulation = "ggl";
  s.rtol = 1e-12;
  s.atol = 1e-14;
  s.max_steps = 50;
  auto integ = make_integrator("ida");
  Vec q, v;
  p->initial_state(q, v);
  integ->init(*p, 0.0, q, v, s);
  try {
    integ->advance(lp.t_end, true, q, v);
    FAIL() << "50 steps reached the end";
  } catch (const RunError& e) {
    const std::string msg = e.what();
    std::printf("[ message ] %s\n", msg.c_str());
    EXPECT_NE(msg.find("largest local error"), std::string::npos) << msg;
    EXPECT_EQ(msg.find("algebraic variable"), std::string::npos) << msg;
    EXPECT_EQ(msg.find("(multipliers)"), std::string::npos) << msg;
  }
}

// One run of `evas problem`'s path (apps are not linked into the tests: the
// same calls): IDA or Radau IIA on a first-order implicit problem, or Radau on
// the first-order form of a mechanical one.
problems::Score first_order(const std::string& name, const std::string& integrator,
                            const std::string& form, double rtol, double atol,
                            long* steps = nullptr) {
  const LibraryProblem& lp = problems::library_problem(name);
  IntegratorSettings s;
  s.name = integrator;
  s.rtol = rtol;
  s.atol = atol;
  s.step = lp.t_end / 2000.0;
  ImplicitRun run;
  problems::Score sc;
  if (lp.implicit()) {
    auto p = lp.make_implicit();
    run = integrator == "radau" ? integrate_implicit_radau(*p, lp.t_end, s)
                                : integrate_implicit_ida(*p, lp.t_end, s);
    if (run.failure.empty()) sc = problems::score_implicit(lp, run.y, rtol, atol);
  } else {
    auto p = lp.make();
    dae::ImplicitForm f(*p, form);
    run = integrate_implicit_radau(f, lp.t_end, s);
    const int n = f.n();
    if (run.failure.empty())
      sc = problems::score(lp, run.y.head(n), run.y.segment(n, n), run.y.tail(f.m()), rtol, atol);
  }
  EXPECT_EQ(run.failure, "") << name << " " << integrator << " " << form << " rtol " << rtol;
  if (!run.failure.empty()) sc.mescd = -99.0;
  if (steps) *steps = run.stats.steps;
  std::printf("%-9s %-6s %-8s rtol %.0e atol %.0e  mescd %5.2f  scd %5.2f  steps %ld\n",
              name.c_str(), integrator.c_str(), form.c_str(), rtol, atol, sc.mescd, sc.scd,
              run.stats.steps);
  return sc;
}

// The first-order implicit problems of the IVP Test Set with IDA (atol = rtol,
// as the test set runs them). Measured (2026-11-28, x86-64-v3 without FMA
// contraction) beside the test set's DDASSL (release 2.4, Tables II.12.2 and
// II.14.3): chemakzo at 1e-10 10.02 digits in 521 steps (DDASSL 10.04, 522);
// transamp at 1e-4 4.38 in 5134 steps (DDASSL 4.60, 9759), at 1e-7 7.45 in
// 24760 (DDASSL 7.24, 40810); transamp's digits move by 0.6 with rounding
// (5.05 and 8.03 with FMA contraction). Fekete (index 2, the test set's GGL
// form) with IDA's ggl at 1e-6: 5.09.
TEST(Problems, IdaOnTheFirstOrderProblems) {
  EXPECT_GE(first_order("chemakzo", "ida", "", 1e-10, 1e-10).mescd, 9.0);
  EXPECT_GE(first_order("transamp", "ida", "", 1e-4, 1e-4).mescd, 4.0);
  EXPECT_GE(first_order("transamp", "ida", "", 1e-7, 1e-7).mescd, 7.0);
  EXPECT_GE(solve("fekete", "ida", "ggl", 1e-6, 1e-8).s.mescd, 4.5);
}

// Radau IIA on the first-order forms (Hairer & Wanner 1996, VII.8; the car
// axis, whose M is constant, in the form without accelerations): every index
// of Andrews and the car axis completes at rtol 1e-4 ... 1e-12 with atol =
// rtol / 100, but one: the car axis in index-3 at rtol 1e-4, which completes
// only with atol = rtol (1.54 digits; the test set runs it so), and with atol
// = rtol / 100 fails with its step falling to 1e-12 s at t = 0.05 s (the
// multipliers of one long step are left loose by the h^2-scaled tolerance,
// and every shorter step after it fails the error test on them). Floors below
// the digits measured (2026-11-28, x86-64-v3 without FMA contraction), rtol
// 1e-4, 1e-8, 1e-10, 1e-12:
//   andrews  index-3 -0.39 2.71 4.31 4.96 (4.31: 3.79 in the clang sanitizer
//            build, Eigen's vector width; 3.43 with the start solved in a
//            fixed order, 2026-11-29, the portable build 4.30; with Radau's
//            dense kernels in a fixed order, 2026-11-29, every build 0.33
//            2.71 3.70 5.57), index-2 2.19 5.59 7.02 7.30,
//            index-1 3.53 7.41 7.32 7.30;
//   car-axis index-3 1.54 (atol = rtol) 4.46 6.17 8.32, index-2 2.74 5.95
//            7.61 9.26, index-1 2.83 6.08 7.75 9.41.
// The first-order problems beside the test set's RADAU (release 2.4, Tables
// II.12.2, II.14.3; rtol = atol): chemakzo at 1e-10 10.57 digits in 90 steps
// (RADAU 10.71 in 43), transamp at 1e-7 7.17 in 1655 (RADAU 7.11 in 1775).
TEST(Problems, RadauSolvesEveryIndex) {
  const double rtols[] = {1e-4, 1e-8, 1e-10, 1e-12};
  const double floor[2][3][4] = {
      {{-0.8, 2.3, 3.3, 4.5}, {1.7, 5.1, 6.5, 6.8}, {3.1, 6.8, 6.8, 6.8}},
      {{1.0, 4.0, 5.7, 5.6}, {2.2, 5.5, 7.1, 8.8}, {2.3, 5.6, 7.3, 8.9}}};
  const char* names[] = {"andrews", "car-axis"};
  const char* forms[] = {"index-3", "index-2", "index-1"};
  for (int p = 0; p < 2; ++p)
    for (int f = 0; f < 3; ++f)
      for (int r = 0; r < 4; ++r) {
        const bool loose_index3 = p == 1 && f == 0 && r == 0;  // see above
        const double atol = loose_index3 ? rtols[r] : rtols[r] / 100;
        EXPECT_GE(first_order(names[p], "radau", forms[f], rtols[r], atol).mescd, floor[p][f][r])
            << names[p] << " " << forms[f] << " rtol " << rtols[r];
      }
  EXPECT_GE(first_order("chemakzo", "radau", "", 1e-10, 1e-10).mescd, 10.0);
  EXPECT_GE(first_order("transamp", "radau", "", 1e-7, 1e-7).mescd, 6.7);
}

// The flexible slider crank (index 2 as the test set states it; its smooth
// start) completes with IDA in every formulation and Radau IIA in every index
// at rtol = atol = 1e-4, 1e-6, 1e-8 (the test set's tolerances). Its digits
// are low at loose tolerances for every solver (test set, Table II.19.3: mescd
// 0.20 / 0.14 / 1.65 for RADAU, 0.22 / 0.03 / 2.72 for MEBDFI). Measured
// (x86-64-v3, mescd): IDA index-2 1.97 / 3.47 / 4.64 (2.09 / 2.98 / 4.67 in
// every build with the start solved in a fixed order, 2026-11-29), radau
// index-2 2.76 / 3.24 / 4.09, radau index-1 5.58 / 7.16 / 8.70.
TEST(Problems, SliderCrankCompletes) {
  const double rtols[] = {1e-4, 1e-6, 1e-8};
  const double ida2[] = {1.5, 2.8, 4.2}, radau2[] = {2.3, 2.8, 3.6}, radau1[] = {5.1, 6.7, 8.2};
  for (int r = 0; r < 3; ++r) {
    EXPECT_GE(solve("crank", "ida", "index-2", rtols[r], rtols[r]).s.mescd, ida2[r]);
    EXPECT_GE(first_order("crank", "radau", "index-2", rtols[r], rtols[r]).mescd, radau2[r]);
    EXPECT_GE(first_order("crank", "radau", "index-1", rtols[r], rtols[r]).mescd, radau1[r]);
  }
}

// Radau IIA's order on fixed steps (Hairer & Wanner 1996, VII.4, Table 4.1):
// for an index-2 system the differential components converge at order
// 2s - 1 = 5, the algebraic ones (the multiplier) at order s = 3. The pendulum
// in its index-2 form over one period, h = T/40 and T/80: the error of the
// positions and velocities at the end falls by 2^5 = 32, the multiplier's by
// 2^3 = 8 (at least; measured: see the printout).
TEST(Problems, RadauConvergesAtOrderFiveAndThreeOnIndexTwo) {
  const LibraryProblem& lp = problems::library_problem("pendulum");
  double err_y[2], err_l[2];
  for (int k = 0; k < 2; ++k) {
    auto p = lp.make();
    dae::ImplicitForm f(*p, "index-2");
    IntegratorSettings s;
    s.name = "radau";
    s.rtol = 1e-10;  // only Newton's stopping test reads them here
    s.atol = 1e-10;
    s.step_control = StepControl::fixed;
    s.step = lp.t_end / (40.0 * (1 << k));
    const ImplicitRun run = integrate_implicit_radau(f, lp.t_end, s);
    ASSERT_EQ(run.failure, "");
    const int n = f.n();
    double ey = 0.0;
    for (int i = 0; i < 2 * n; ++i)
      ey = std::max(ey, std::abs(run.y(i) - lp.reference_qv[static_cast<std::size_t>(i)]));
    err_y[k] = ey;
    err_l[k] = std::abs(run.y(f.lambda_offset()) - lp.reference_lambda[0]);
    std::printf("radau fixed h = T/%d: |error| q,v %.3e  lambda %.3e  steps %ld\n", 40 << k, ey,
                err_l[k], run.stats.steps);
  }
  const double order_y = std::log2(err_y[0] / err_y[1]), order_l = std::log2(err_l[0] / err_l[1]);
  std::printf("observed order: q, v %.2f  lambda %.2f\n", order_y, order_l);
  EXPECT_NEAR(order_y, 5.0, 0.5);
  EXPECT_GE(order_l, 2.7);
}

// Reproducible digits (issue 37 part 2): the end-point digits of the car
// axis and of Andrews' squeezer in this build against those of the portable
// build (EVAS_ARCH=portable, GCC 12, recorded 2026-11-29 on branch repro:
// -ffp-contract=off and the consistent start solved in a fixed order,
// dae/fixed_order_dense.h), at every rtol 1e-4 ... 1e-12 (atol = rtol / 100)
// with IDA (ggl, index-2) and Radau IIA (index-2). The x86-64-v3 build gives
// IDA's digits to every printed place and Radau's within 0.07
// (docs/problems.md, "Reproducible digits"); before, they differed by up to
// 0.47 (car axis) and 1.55 (Andrews). The sanitizer build (clang, -O1) is
// another compiler: skipped there.
#if defined(__SANITIZE_ADDRESS__)
#define EVAS_SANITIZED_BUILD 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define EVAS_SANITIZED_BUILD 1
#endif
#endif
TEST(Problems, DigitsAgreeWithThePortableBuild) {
#ifdef EVAS_SANITIZED_BUILD
  GTEST_SKIP() << "the recorded digits are of the GCC builds";
#endif
  const double car_axis[9][3] = {{1.24, 1.36, 2.74}, {2.38, 2.20, 3.53}, {3.35, 3.76, 4.34},
                                 {4.59, 4.72, 5.13}, {5.15, 5.32, 5.95}, {5.92, 5.98, 6.77},
                                 {6.72, 6.62, 7.61}, {7.48, 7.44, 8.44}, {8.43, 8.26, 9.26}};
  const double andrews[9][3] = {{1.01, 0.85, 2.33}, {1.91, 1.55, 2.79}, {3.27, 2.43, 3.97},
                                {4.08, 3.67, 5.09}, {6.48, 5.12, 5.60}, {6.41, 5.53, 6.35},
                                {7.16, 6.26, 7.02}, {7.31, 7.84, 7.27}, {7.29, 7.26, 7.30}};
  // Radau IIA on Andrews in index-3, the portable build's digits (2026-11-29;
  // the same in the x86-64-v3 build since Radau's dense kernels run in a fixed
  // order, dae/fixed_order_lu.h, and its transformation V, V^-1 is the same in
  // both: at rtol 1e-10 the builds gave 3.43 / 4.30 before)
  const double andrews_radau3[9] = {0.33, 0.78, 1.16, 1.51, 2.71, 3.35, 3.70, 5.06, 5.57};
  for (int k = 0; k < 9; ++k) {
    const double rtol = std::pow(10.0, -4 - k), atol = rtol / 100;
    for (const auto& [name, portable] :
         {std::pair<std::string, const double*>{"car-axis", car_axis[k]},
          {"andrews", andrews[k]}}) {
      EXPECT_NEAR(solve(name, "ida", "ggl", rtol, atol).s.mescd, portable[0], 0.2) << name;
      EXPECT_NEAR(solve(name, "ida", "index-2", rtol, atol).s.mescd, portable[1], 0.2) << name;
      EXPECT_NEAR(first_order(name, "radau", "index-2", rtol, atol).mescd, portable[2], 0.2)
          << name;
    }
    EXPECT_NEAR(first_order("andrews", "radau", "index-3", rtol, atol).mescd, andrews_radau3[k],
                0.2);
  }
}

// Generalized-alpha (index-3, Arnold & Bruls 2007, rho_inf 0.9): second order,
// so halving the step adds log10(4) = 0.60 digits. Measured: andrews 2.60,
// 3.20 (h = 1e-5, 5e-6); car-axis 1.08, 1.69 (1e-3, 5e-4); pendulum 2.55, 3.15.
TEST(Problems, GeneralizedAlphaConvergesAtOrderTwo) {
  for (const std::string name : {"andrews", "car-axis", "pendulum"}) {
    const double h = name == "andrews" ? 1e-5 : 1e-3;
    const EndPoint a = solve(name, "generalized-alpha", "index-3", 1e-8, 1e-10, h);
    const EndPoint b = solve(name, "generalized-alpha", "index-3", 1e-8, 1e-10, h / 2);
    EXPECT_NEAR(b.s.mescd - a.s.mescd, std::log10(4.0), 0.1) << name;
    EXPECT_GE(a.s.mescd, 1.0) << name;
  }
}

// `evas problem`: the end point, its digits and the statistics; errors name the input.
std::string run_evas(const std::string& args, int& code) {
  const std::string out = std::string(EVAS_BINARY_DIR) + "/tests/problem_cli.txt";
  code =
      std::system((std::string(EVAS_BINARY_DIR) + "/evas " + args + " > " + out + " 2>&1").c_str());
  code = WIFEXITED(code) ? WEXITSTATUS(code) : -1;
  std::ifstream f(out);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

TEST(Problems, Command) {
  int code = 0;
  std::string text = run_evas("problem car-axis --rtol 1e-6", code);
  EXPECT_EQ(code, 0) << text;
  EXPECT_NE(text.find("mescd"), std::string::npos) << text;
  EXPECT_NE(text.find("car-axis"), std::string::npos) << text;
  text = run_evas("problem andrews --integrator generalized-alpha --step 1e-5", code);
  EXPECT_EQ(code, 0) << text;
  EXPECT_NE(text.find("mescd"), std::string::npos) << text;
  // the sweep: every family, a table with a row per case
  const std::string dir = std::string(EVAS_BINARY_DIR) + "/tests/problem_wp";
  text = run_evas("problem pendulum --work-precision --out " + dir, code);
  EXPECT_EQ(code, 0) << text;
  std::ifstream csv(dir + "/work_precision.csv");
  std::string line;
  int lines = 0;
  while (std::getline(csv, line)) ++lines;
  // ida x 4, radau x 3, generalized-alpha and hht-alpha
  EXPECT_EQ(lines, 1 + 4 * 8 + 3 * 8 + 8 + 8) << text;
  EXPECT_NE(text.find("radau index-2"), std::string::npos) << text;
  EXPECT_NE(text.find("generalized-alpha index-3"), std::string::npos) << text;
  EXPECT_NE(text.find("hht-alpha index-3"), std::string::npos) << text;
  text = run_evas("problem pendulum --work-precision", code);
  EXPECT_EQ(code, 1) << text;
  text = run_evas("problem --list", code);
  EXPECT_EQ(code, 0) << text;
  for (const char* n :
       {"andrews", "car-axis", "pendulum", "fekete", "crank", "chemakzo", "transamp"})
    EXPECT_NE(text.find(n), std::string::npos) << text;
  text = run_evas("problem andrew", code);
  EXPECT_EQ(code, 1) << text;
  EXPECT_NE(text.find("no problem named 'andrew' (known: andrews, car-axis, pendulum, fekete, "
                      "crank, chemakzo, transamp, wheelset)"),
            std::string::npos)
      << text;
  // a first-order problem: its components, digits and summary; integrators it refuses
  const std::string akzo_dir = std::string(EVAS_BINARY_DIR) + "/tests/problem_akzo";
  std::filesystem::remove_all(akzo_dir);
  text = run_evas("problem chemakzo --integrator radau --rtol 1e-8 --out " + akzo_dir, code);
  EXPECT_EQ(code, 0) << text;
  EXPECT_NE(text.find("y6 [FLB.ZHU]"), std::string::npos) << text;
  EXPECT_NE(text.find("mescd"), std::string::npos) << text;
  std::ifstream js_akzo(akzo_dir + "/summary.json");
  std::stringstream summary_akzo;
  summary_akzo << js_akzo.rdbuf();
  EXPECT_NE(summary_akzo.str().find("\"y\": ["), std::string::npos) << summary_akzo.str();
  text = run_evas("problem chemakzo --integrator cvode", code);
  EXPECT_EQ(code, 1) << text;
  EXPECT_NE(text.find("ida and radau run it"), std::string::npos) << text;
  text = run_evas("problem transamp --formulation index-2", code);
  EXPECT_EQ(code, 1) << text;
  EXPECT_NE(text.find("has no formulations"), std::string::npos) << text;
  text = run_evas("problem andrews --integrator radau --formulation ggl", code);
  EXPECT_EQ(code, 1) << text;
  EXPECT_NE(text.find("takes index-3, index-2 or index-1"), std::string::npos) << text;
  text = run_evas("problem car-axis --formulation index-7", code);
  EXPECT_EQ(code, 1) << text;
  // linear acceleration's index-3 form diverges (docs/theory.md section 10.5): exit 2,
  // and with --out the summary still records the case: its status and statistics
  const std::string fail_dir = std::string(EVAS_BINARY_DIR) + "/tests/problem_failed";
  std::filesystem::remove_all(fail_dir);
  text = run_evas(
      "problem pendulum --integrator linear-acceleration --formulation index-3 --out " + fail_dir,
      code);
  EXPECT_EQ(code, 2) << text;
  EXPECT_NE(text.find("FAILED"), std::string::npos) << text;
  std::ifstream js(fail_dir + "/summary.json");
  std::stringstream summary;
  summary << js.rdbuf();
  EXPECT_NE(summary.str().find("\"status\": \"failed: "), std::string::npos) << summary.str();
  EXPECT_NE(summary.str().find("\"steps\": "), std::string::npos) << summary.str();
  EXPECT_EQ(summary.str().find("\"mescd\""), std::string::npos) << summary.str();
  // a completed run's summary says so
  const std::string ok_dir = std::string(EVAS_BINARY_DIR) + "/tests/problem_completed";
  std::filesystem::remove_all(ok_dir);  // (a summary left by an earlier run must not count)
  text = run_evas("problem car-axis --rtol 1e-6 --out " + ok_dir, code);
  EXPECT_EQ(code, 0) << text;
  std::ifstream js_ok(ok_dir + "/summary.json");
  std::stringstream summary_ok;
  summary_ok << js_ok.rdbuf();
  EXPECT_NE(summary_ok.str().find("\"status\": \"completed\""), std::string::npos)
      << summary_ok.str();
  EXPECT_NE(summary_ok.str().find("\"mescd\": "), std::string::npos) << summary_ok.str();
  // its summary is not replaced without --overwrite (docs/errors.md)
  text = run_evas("problem car-axis --rtol 1e-5 --out " + ok_dir, code);
  EXPECT_EQ(code, 1) << text;
  EXPECT_NE(text.find("holds an earlier run's summary: give --overwrite"), std::string::npos)
      << text;
  text = run_evas("problem car-axis --rtol 1e-5 --overwrite --out " + ok_dir, code);
  EXPECT_EQ(code, 0) << text;
  text = run_evas("problem car-axis --integrator cvode", code);  // a combination refused
  EXPECT_EQ(code, 1) << text;
  EXPECT_NE(text.find("formulation=penalty"), std::string::npos) << text;
}

}  // namespace
}  // namespace evas
