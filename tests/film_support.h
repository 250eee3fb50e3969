// Helpers of the film tests (test_film_models.cpp, test_film_feed.cpp,
// test_film_cavitation.cpp): Raimondi & Boyd's table, a film's Jacobian against
// central differences, and `evas bearing` run as a process.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "elements/journal_bearing.h"

namespace evas::film_test {

// One row of Raimondi & Boyd's table: eps, S, attitude [deg], (R/c) f.
struct RBRow {
  double eps, S, phi, f;
};
struct RBTable {
  double l_over_d;
  std::vector<RBRow> rows;
};
inline const std::vector<RBTable>& raimondi_boyd() {
  static const std::vector<RBTable> t = {{1.0,
                                          {{0.2, 0.631, 74.02, 12.8},
                                           {0.4, 0.264, 63.10, 5.79},
                                           {0.6, 0.121, 50.58, 3.22},
                                           {0.8, 0.0446, 36.24, 1.70},
                                           {0.9, 0.0188, 26.45, 1.05}}},
                                         {0.5,
                                          {{0.2, 2.03, 74.94, 40.9},
                                           {0.4, 0.779, 61.45, 17.0},
                                           {0.6, 0.319, 48.14, 8.10},
                                           {0.8, 0.0923, 33.31, 3.26},
                                           {0.9, 0.0313, 23.66, 1.60}}},
                                         {0.25,
                                          {{0.2, 7.57, 75.18, 153.0},
                                           {0.4, 2.83, 60.86, 61.1},
                                           {0.6, 1.07, 46.72, 26.7},
                                           {0.8, 0.261, 31.04, 8.80},
                                           {0.9, 0.0736, 21.85, 3.50}}}};
  return t;
}

using V2 = Eigen::Vector2d;

// The analytic Jacobian of a bearing's film (through the element's hydro)
// against central differences (steps h c in e, h m/s in ed, h 1e3 rad/s in om)
// at three states with squeeze and whirl.
inline void expect_jacobians_match(const JournalBearing& b, const std::string& label, double h) {
  const double c = b.params().clearance;
  for (const auto& st : std::vector<std::array<double, 5>>{{0.5, 0.2, 0.01, -0.004, 300.0},
                                                           {-0.3, 0.6, -0.006, 0.002, 250.0},
                                                           {0.1, -0.85, 0.0, 0.003, 400.0}}) {
    const V2 e = V2(st[0], st[1]) * c, ed(st[2], st[3]);
    const double om = st[4];
    const FilmForce a = b.hydro(e, ed, om, 1.0, true, true);
    auto f = [&](const V2& ee, const V2& edd, double w) {
      return b.hydro(ee, edd, w, 1.0, false, true).f;
    };
    Eigen::Matrix2d ne, ned;
    for (int j = 0; j < 2; ++j) {
      V2 dp = V2::Zero();
      dp[j] = h * c;
      ne.col(j) = (f(e + dp, ed, om) - f(e - dp, ed, om)) / (2 * h * c);
      dp[j] = h;
      ned.col(j) = (f(e, ed + dp, om) - f(e, ed - dp, om)) / (2 * h);
    }
    const V2 nom = (f(e, ed, om + 1e3 * h) - f(e, ed, om - 1e3 * h)) / (2e3 * h);
    const double se = ne.norm(), sd = ned.norm(), so = nom.norm();
    std::printf(
        "%-8s eps (%.2f, %.2f): |dF/de err| %.2e, |dF/ded err| %.2e, |dF/dom err| %.2e "
        "(relative)\n",
        label.c_str(), st[0], st[1], (a.df_de - ne).norm() / se, (a.df_ded - ned).norm() / sd,
        (a.df_dom - nom).norm() / so);
    EXPECT_LT((a.df_de - ne).norm(), 1e-5 * se) << label;
    EXPECT_LT((a.df_ded - ned).norm(), 1e-5 * sd) << label;
    EXPECT_LT((a.df_dom - nom).norm(), 1e-5 * so) << label;
  }
}

// Runs `evas bearing ARGS` and returns its stdout and exit code.
inline std::string run_bearing(const std::string& args, int& code) {
  const std::string cmd = std::string(EVAS_BINARY_DIR) + "/evas bearing " + args + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  std::string out;
  char buf[512];
  while (p && fgets(buf, sizeof buf, p)) out += buf;
  const int st = p ? pclose(p) : -1;
  code = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return out;
}

inline double json_number(const std::string& json, const std::string& key) {
  const std::size_t k = json.find("\"" + key + "\": ");
  if (k == std::string::npos) return std::nan("");
  return std::stod(json.substr(k + key.size() + 4));
}

}  // namespace evas::film_test
