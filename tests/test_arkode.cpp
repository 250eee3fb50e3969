// The arkode integrator (integrators/arkode.cpp): ARKODE's Runge-Kutta tables
// by name, checked against the tables themselves and on the paper's engine.
#include <gtest/gtest.h>

#include <cstdio>  // (ARKODE's headers use FILE without including it)
// clang-format off
#include <arkode/arkode_butcher_dirk.h>
#include <arkode/arkode_butcher_erk.h>
// clang-format on

#include <Eigen/Dense>
#include <complex>
#include <fstream>
#include <map>
#include <sstream>

#include "integrators/settings.h"
#include "run_faults_support.h"
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

// The columns of a results.csv by channel name (the header's unit dropped).
std::map<std::string, std::vector<double>> read_csv_columns(const fs::path& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  std::istringstream head(line);
  for (std::string cell; std::getline(head, cell, ',');)
    names.push_back(cell.substr(0, cell.find('[')));
  std::map<std::string, std::vector<double>> out;
  while (std::getline(in, line)) {
    std::istringstream row(line);
    std::size_t k = 0;
    for (std::string cell; std::getline(row, cell, ',') && k < names.size(); ++k)
      out[names[k]].push_back(std::stod(cell));
  }
  return out;
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

// The paper's engine (validation/engine/engine.yaml, Case 1) to t = 0.01 s
// with the default implicit table and the second-order linear solver: the main
// bearing loads within 1 % of their swing of IDA's at rtol 1e-7.
TEST(Arkode, RunsThePapersEngine) {
  TempFolder tmp;
  const std::string scene =
      (fs::path(EVAS_SOURCE_DIR) / "validation" / "engine" / "engine.yaml").string();
  const Outcome ref =
      run_evas({"run", scene, "--param", "time.end=0.01", "--set", "rtol=1e-7", "--set",
                "atol=1e-11", "--csv", "--out", (tmp.path() / "ida").string()},
               tmp.path() / "ida.log");
  ASSERT_EQ(ref.code, 0) << ref.log;
  const Outcome ark =
      run_evas({"run", scene, "--param", "time.end=0.01", "--integrator", "arkode", "--set",
                "rtol=1e-5", "--set", "atol=1e-9", "--set", "linear_solver=second-order", "--csv",
                "--out", (tmp.path() / "ark").string()},
               tmp.path() / "ark.log");
  ASSERT_EQ(ark.code, 0) << ark.log;
  const auto a = read_csv_columns(tmp.path() / "ida" / "results.csv");
  const auto b = read_csv_columns(tmp.path() / "ark" / "results.csv");
  for (const std::string ch : {"main1.fx", "main3.fy", "main5.fy"}) {
    SCOPED_TRACE(ch);
    ASSERT_TRUE(a.count(ch) && b.count(ch));
    const auto& x = a.at(ch);
    const auto& y = b.at(ch);
    ASSERT_EQ(x.size(), y.size());
    double lo = x[0], hi = x[0], diff = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      lo = std::min(lo, x[i]);
      hi = std::max(hi, x[i]);
      diff = std::max(diff, std::abs(x[i] - y[i]));
    }
    EXPECT_LT(diff, 0.01 * (hi - lo)) << "swing " << hi - lo;
  }
}
