// evas_bench, the journal bearing's film models (docs/elements-journal-bearing.md,
// "Film models"): the cost of one film evaluation (force only, and force with
// its Jacobian) for the validation engine's main bearing (R 40 mm, B 35 mm,
// c 30 um, eta 0.015 Pa s) at 3000 rpm, averaged over 64 states spread over
// eccentricity ratios 0.05 to 0.95, every direction and a squeeze velocity.
#pragma once

#include <chrono>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include "elements/journal_bearing.h"

namespace evas::bench {

inline std::string film_cost_table() {
  using Clock = std::chrono::steady_clock;
  struct Case {
    std::string label, film;
    int phi, axial;
    bool table;
  };
  const std::vector<Case> cases = {{"short (the paper's)", "short", 72, 8, false},
                                   {"finite (Butenschoen)", "finite", 72, 8, false},
                                   {"reynolds, grid 36 x 4", "reynolds", 36, 4, false},
                                   {"reynolds, grid 72 x 8 (default)", "reynolds", 72, 8, false},
                                   {"reynolds, grid 144 x 16", "reynolds", 144, 16, false},
                                   {"reynolds, table of grid 72 x 8", "reynolds", 72, 8, true}};
  const double om = 3000.0 * M_PI / 30.0, c = 3e-5;
  std::vector<Eigen::Vector2d> es, eds;
  for (int k = 0; k < 64; ++k) {
    const double eps = 0.05 + 0.9 * std::fmod(0.618034 * k, 1.0);
    const double th = 2.0 * M_PI * std::fmod(0.414214 * k, 1.0);
    es.emplace_back(eps * c * std::cos(th), eps * c * std::sin(th));
    eds.emplace_back(0.004 * std::cos(3.0 * k), 0.004 * std::sin(5.0 * k));
  }
  std::ostringstream os;
  os << "| film | set-up [ms] | force [us] | force and Jacobian [us] |\n|---|---:|---:|---:|\n";
  for (const Case& cs : cases) {
    JournalBearingParams p;
    p.radius = 0.04;
    p.width = 0.035;
    p.clearance = c;
    p.viscosity = 0.015;
    p.film = cs.film;
    p.grid_phi = cs.phi;
    p.grid_axial = cs.axial;
    p.table = cs.table;
    const auto t0 = Clock::now();
    const JournalBearing b("main", {0, 1}, p);
    const double setup = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    double best[2] = {1e300, 1e300};
    double sink = 0.0;
    for (int rep = 0; rep < 3; ++rep)
      for (int d = 0; d < 2; ++d) {
        const auto s = Clock::now();
        for (std::size_t k = 0; k < es.size(); ++k)
          sink += b.hydro(es[k], eds[k], om, 1.0, d == 1, true).f.x();
        best[d] =
            std::min(best[d], std::chrono::duration<double, std::micro>(Clock::now() - s).count() /
                                  static_cast<double>(es.size()));
      }
    os << "| " << cs.label << " | " << std::fixed << std::setprecision(1) << setup << " | "
       << std::setprecision(2) << best[0] << " | " << best[1] << " |" << (sink == 0.123 ? " " : "")
       << "\n";
  }
  return os.str();
}

}  // namespace evas::bench
