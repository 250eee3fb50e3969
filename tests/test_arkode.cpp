// The arkode integrator (integrators/arkode.cpp): ARKODE's Runge-Kutta tables
// by name, checked against the tables themselves and on the paper's engine.
#include <gtest/gtest.h>

#include <cstdio>  // (ARKODE's headers use FILE without including it)
// clang-format off
#include <arkode/arkode_butcher_dirk.h>
#include <arkode/arkode_butcher_erk.h>
// clang-format on

#include <Eigen/Dense>
#include <cmath>
#include <complex>
#include <iostream>

#include "engine_compare.h"
#include "integrators/settings.h"
#include "run_faults_support.h"
#include "sdof_run.h"
#include "study/amplification.h"

using namespace evas;
using namespace run_faults;

namespace {

using Cx = std::complex<double>;

// The stability function of a Runge-Kutta table, R(z) = 1 + z b^T (I - z A)^-1 1
// (Hairer & Wanner, Solving ODEs II, section IV.3, eq. 3.2), from ARKODE's own
// coefficients of the named table.
Cx stability_function(const std::string& name, bool implicit, Cx z) {
  ARKodeButcherTable t = implicit ? ARKodeButcherTable_LoadDIRKByName(name.c_str())
                                  : ARKodeButcherTable_LoadERKByName(name.c_str());
  EXPECT_NE(t, nullptr) << name;
  if (!t) return 0.0;
  const int s = t->stages;
  Eigen::MatrixXcd M = Eigen::MatrixXcd::Identity(s, s);
  Eigen::VectorXcd b(s);
  for (int i = 0; i < s; ++i) {
    b[i] = t->b[i];
    for (int j = 0; j < s; ++j) M(i, j) -= z * t->A[i][j];
  }
  ARKodeButcherTable_Free(t);
  const Eigen::VectorXcd k = M.partialPivLu().solve(Eigen::VectorXcd::Ones(s));
  return 1.0 + z * b.dot(k);  // (b real: dot's conjugate changes nothing)
}

IntegratorSettings arkode(const std::string& table) {
  IntegratorSettings s;
  s.name = "arkode";
  apply_setting_assignment(s, "table=" + table);
  return s;
}

}  // namespace

// Fixed steps of y' = z y: |R(z)| measured from the integrator's steps equals
// the table's stability function over the region's grid, for an implicit
// (ESDIRK, the default; L-stable: |R| < 1 left of the axis) and an explicit
// table (Dormand-Prince: its bounded region). Right of the imaginary axis a
// point where the implicit stages' Newton iteration fails is left out.
TEST(Arkode, RegionIsTheTablesStabilityFunction) {
  for (const auto& [table, implicit] :
       {std::pair<std::string, bool>{"ARKODE_ESDIRK324L2SA_4_2_3", true},
        {"ARKODE_SDIRK_2_1_2", true},
        {"ARKODE_DORMAND_PRINCE_7_4_5", false}}) {
    SCOPED_TRACE(table);
    const std::vector<study::RegionPoint> region = study::measure_region(arkode(table), 6.0, 12);
    ASSERT_EQ(region.size(), 13u * 7u);
    int stable_left = 0, left = 0, failed_right = 0;
    for (const auto& p : region) {
      const Cx z(p.re, p.im);
      if (p.re <= 0.0) {
        ASSERT_TRUE(std::isfinite(p.abs_R)) << z;
      } else if (!std::isfinite(p.abs_R)) {
        // right of the axis, where 1 - z a_ii nears 0 or the steps grow, the
        // fixed step's Newton iteration may fail: recorded, not compared
        ++failed_right;
        continue;
      }
      const double R = std::abs(stability_function(table, implicit, z));
      EXPECT_NEAR(p.abs_R, R, std::max(1e-6, (p.im == 0.0 ? 1e-5 : 1e-8) * std::max(1.0, R))) << z;
      if (p.re < 0.0) {
        ++left;
        stable_left += p.abs_R < 1.0;
      }
    }
    EXPECT_LT(failed_right, 13 * 7 / 4);
    if (implicit) {
      EXPECT_EQ(stable_left, left);  // A-stable
    } else {
      EXPECT_LT(stable_left, left);  // explicit: bounded region
    }
  }
}

// An unknown table is refused naming the choices; the default is implicit
// and adaptive (fixed steps only with step_control=fixed).
TEST(Arkode, SettingsAndRefusals) {
  IntegratorSettings s;
  s.name = "arkode";
  EXPECT_THROW(apply_setting_assignment(s, "table=RK4"), InputError);
  EXPECT_FALSE(takes_fixed_steps(s));
  s.step_control = StepControl::fixed;
  EXPECT_TRUE(takes_fixed_steps(s));
}

// The additive pair ARK3(2)4L[2]SA (Kennedy & Carpenter 2003) at fixed steps
// on the forced, damped oscillators of sdof_problem.h, split both ways:
// imex=body (the oscillators' own stiffness and damping implicit, their
// forcing explicit) and imex=elements (the reverse): the additive method
// keeps its order 3 in either.
TEST(Arkode, ImexPairKeepsItsOrder) {
  for (const std::string split : {"body", "elements"}) {
    SCOPED_TRACE(split);
    IntegratorSettings s = arkode("ARKODE_ARK324L2SA_DIRK_4_2_3");
    apply_setting_assignment(s, "imex=" + split);
    apply_setting_assignment(s,
                             split == "body" ? "linear_solver=second-order" : "linear_solver=klu");
    apply_setting_assignment(s, "step_control=fixed");
    s.rtol = 1e-12;  // (the stages' Newton iteration far below the truncation error)
    s.atol = 1e-14;
    double e[3];
    for (int k = 0; k < 3; ++k) {
      s.step = 0.004 / std::pow(2.0, k);
      test::SdofProblem p(test::oscillators(), true);
      e[k] = test::run_sdof(s, p, {1.0}).q;
    }
    const double o1 = std::log2(e[0] / e[1]), o2 = std::log2(e[1] / e[2]);
    std::cout << "ARK324 imex=" << split << " |q err|(t=1): " << e[0] << ", " << e[1] << ", "
              << e[2] << "; orders " << o1 << ", " << o2 << "\n";
    EXPECT_GE(o2, 2.7);
    EXPECT_LE(o2, 3.3);
  }
}

// imex=body refuses a table that is no additive pair's half, a linear solver
// other than second-order, and a problem without a body part, each naming why.
TEST(Arkode, ImexRefusals) {
  auto refusal = [](IntegratorSettings s, bool body_part) {
    test::SdofProblem p(test::oscillators(), body_part);
    try {
      test::run_sdof(s, p, {0.1});
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  IntegratorSettings s = arkode("ARKODE_ESDIRK324L2SA_4_2_3");
  apply_setting_assignment(s, "imex=body");
  apply_setting_assignment(s, "linear_solver=second-order");
  EXPECT_NE(refusal(s, true).find("additive pair"), std::string::npos) << refusal(s, true);
  apply_setting_assignment(s, "table=ARKODE_ARK436L2SA_ERK_6_3_4");
  EXPECT_EQ(refusal(s, true), "(accepted)");
  EXPECT_NE(refusal(s, false).find("modal bodies"), std::string::npos) << refusal(s, false);
  apply_setting_assignment(s, "linear_solver=klu");
  EXPECT_NE(refusal(s, true).find("second-order"), std::string::npos) << refusal(s, true);
  apply_setting_assignment(s, "imex=elements");
  EXPECT_EQ(refusal(s, true), "(accepted)");
  apply_setting_assignment(s, "linear_solver=second-order");
  EXPECT_NE(refusal(s, true).find("klu or dense"), std::string::npos) << refusal(s, true);
}

// The paper's engine (validation/engine/engine.yaml, Case 1) to t = 0.01 s
// with the default implicit table and the second-order linear solver: the main
// bearing loads within 1 % of their swing of IDA's at rtol 1e-7.
TEST(Arkode, RunsThePapersEngine) {
  TempFolder tmp;
  const auto ref = engine_compare::run_engine_reference(tmp.path() / "ida");
  ASSERT_EQ(ref.code, 0) << ref.log;
  const auto ark = engine_compare::run_engine_briefly(
      tmp.path() / "ark", {"--integrator", "arkode", "--set", "rtol=1e-5", "--set", "atol=1e-9",
                           "--set", "linear_solver=second-order"});
  ASSERT_EQ(ark.code, 0) << ark.log;
  engine_compare::expect_main_bearings_within(ref.columns, ark.columns, 0.01, "ESDIRK3(2)");
  // the additive pair ARK3(2)4L[2]SA split both ways: the same bound
  for (const std::string split : {"body", "elements"}) {
    const auto imex = engine_compare::run_engine_briefly(
        tmp.path() / ("imex-" + split),
        {"--integrator", "arkode", "--set", "table=ARKODE_ARK324L2SA_DIRK_4_2_3", "--set",
         "imex=" + split, "--set", "rtol=1e-5", "--set", "atol=1e-9", "--set",
         split == "body" ? "linear_solver=second-order" : "linear_solver=klu"});
    ASSERT_EQ(imex.code, 0) << imex.log;
    engine_compare::expect_main_bearings_within(ref.columns, imex.columns, 0.01, "imex=" + split);
  }
}
