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
    auto p = lp.make();
    const int n = p->size(), m = p->constraint_count();
    Vec q, v;
    perturbed(*p, q, v);
    const double t = 0.3 * lp.t_end, h = 1e-6;
    SpMat K = p->jacobian_pattern(), C = K, G = p->constraint_pattern(), M = p->mass_pattern();
    p->force_jacobian(t, q.data(), v.data(), K, C);
    p->constraint_jacobian(t, q.data(), G);
    Mat Kfd(n, n), Cfd(n, n), Gfd(m, n), Mq(n, n);
    Vec fp(n), fm(n), gp(m), gm(m);
    for (int c = 0; c < n; ++c) {
      for (int which : {0, 1}) {
        Vec qp = q, qm = q, vp = v, vm = v;
        (which ? vp : qp)(c) += h;
        (which ? vm : qm)(c) -= h;
        p->force(t, qp.data(), vp.data(), fp.data());
        p->force(t, qm.data(), vm.data(), fm.data());
        (which ? Cfd : Kfd).col(c) = (fp - fm) / (2 * h);
        if (!which) {
          p->constraint(t, qp.data(), v.data(), gp.data(), nullptr, nullptr);
          p->constraint(t, qm.data(), v.data(), gm.data(), nullptr, nullptr);
          Gfd.col(c) = (gp - gm) / (2 * h);
        }
      }
    }
    EXPECT_LT(rel_err(Mat(K), Kfd), 1e-7);
    EXPECT_LT(rel_err(Mat(C), Cfd), 1e-7);
    EXPECT_LT(rel_err(Mat(G), Gfd), 1e-7);
    // g' = d/dt g(t, q + t v) and ga = d/dt g'(t, q + t v, v) (q'' = 0)
    Vec g(m), gv(m), ga(m), gvp(m), gvm(m);
    p->constraint(t, q.data(), v.data(), g.data(), gv.data(), ga.data());
    const Vec q1 = q + h * v, q0 = q - h * v;
    p->constraint(t + h, q1.data(), v.data(), gp.data(), gvp.data(), nullptr);
    p->constraint(t - h, q0.data(), v.data(), gm.data(), gvm.data(), nullptr);
    EXPECT_LT(rel_err(gv, (gp - gm) / (2 * h)), 1e-7);
    EXPECT_LT(rel_err(ga, (gvp - gvm) / (2 * h)), 1e-6);
    // M symmetric positive definite
    p->mass(t, q.data(), M);
    const Mat Md(M);
    EXPECT_LT((Md - Md.transpose()).cwiseAbs().maxCoeff(), 1e-18);
    EXPECT_GT(Eigen::SelfAdjointEigenSolver<Mat>(Md).eigenvalues().minCoeff(), 0.0);
    // the published start lies on the constraints, with consistent velocities
    p->initial_state(q, v);
    p->constraint(0.0, q.data(), v.data(), g.data(), gv.data(), nullptr);
    EXPECT_LT(g.cwiseAbs().maxCoeff(), 1e-14);
    EXPECT_LT(gv.cwiseAbs().maxCoeff(), 1e-14);
  }
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
  EXPECT_EQ(lines, 1 + 4 * 8 + 8) << text;
  EXPECT_NE(text.find("generalized-alpha index-3"), std::string::npos) << text;
  text = run_evas("problem pendulum --work-precision", code);
  EXPECT_EQ(code, 1) << text;
  text = run_evas("problem --list", code);
  EXPECT_EQ(code, 0) << text;
  for (const char* n : {"andrews", "car-axis", "pendulum"})
    EXPECT_NE(text.find(n), std::string::npos) << text;
  text = run_evas("problem andrew", code);
  EXPECT_EQ(code, 1) << text;
  EXPECT_NE(text.find("no problem named 'andrew' (known: andrews, car-axis, pendulum)"),
            std::string::npos)
      << text;
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
  text = run_evas("problem car-axis --integrator cvode", code);  // a combination refused
  EXPECT_EQ(code, 1) << text;
  EXPECT_NE(text.find("formulation=penalty"), std::string::npos) << text;
}

}  // namespace
}  // namespace evas
