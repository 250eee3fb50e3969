// `evas study budget` (study/budget.h) on the validation engine: every source
// of error is measured against the variation that removes it, the dominant
// source is the largest, the files hold what the result holds, and the
// report's CSV reader reads them back. The engine on a crankshaft basis cut at
// 1.5 kHz (7 of its 13 elastic modes) makes the basis the dominant source, as
// docs/engine-bodies.md ("Modal convergence") measured for the paper's basis.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "plot/report_budget.h"
#include "study/budget.h"
#include "study/budget_files.h"

namespace evas::study {
namespace {

namespace fs = std::filesystem;

const std::string kEngine = std::string(EVAS_SOURCE_DIR) + "/validation/engine/engine.yaml";

std::string slurp(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

TEST(Budget, EveryMeasurableSourceOfTheEngine) {
  const fs::path out = fs::temp_directory_path() / ("evas_budget_" + std::to_string(::getpid()));
  fs::remove_all(out);
  Options o;
  o.scene = kEngine;
  o.params = {"crank.modes.max_frequency=1500"};
  o.channels = "main3.fx,main3.fy,mount1.fz";
  o.out_dir = out.string();
  o.plot = false;
  const BudgetResult r = budget(o, BudgetOptions{});
  ASSERT_EQ(r.sources.size(), 4u);
  ASSERT_EQ(r.info.channels.size(), 3u);
  const BudgetSource &integ = r.sources[0], &start = r.sources[1], &basis = r.sources[2],
                     &elem = r.sources[3];
  EXPECT_EQ(integ.name, "integration");
  ASSERT_TRUE(integ.measured) << integ.note;
  EXPECT_NE(integ.variation.find("rtol=1e-07"), std::string::npos) << integ.variation;
  // IDA at rtol 1e-5 on the engine: a few 1e-4 of a channel's swing at most
  EXPECT_GT(integ.error, 0.0);
  EXPECT_LT(integ.error, 3e-3);
  EXPECT_GT(integ.steps, r.base_steps);
  // six cycles from rest: the mounts are still settling (docs/periodic.md)
  ASSERT_TRUE(start.measured) << start.note;
  EXPECT_NE(start.variation.find("periodic"), std::string::npos) << start.variation;
  EXPECT_GT(start.error, 1e-3);
  EXPECT_LT(start.error, 0.5);
  // the crank cut at 1.5 kHz against its whole file (13 modes to 2.5 kHz)
  ASSERT_TRUE(basis.measured) << basis.note;
  EXPECT_NE(basis.variation.find("crank"), std::string::npos) << basis.variation;
  EXPECT_GT(basis.error, 10.0 * integ.error);
  // the five main bearings on the Reynolds film (tabulated) against the paper's
  // short film: a few per cent in the loads (docs/elements-journal-bearing.md,
  // "The films on the engine"), far above the integration, below the cut basis
  ASSERT_TRUE(elem.measured) << elem.note;
  EXPECT_NE(elem.variation.find("film reynolds"), std::string::npos) << elem.variation;
  EXPECT_NE(elem.variation.find("main5"), std::string::npos) << elem.variation;
  EXPECT_GT(elem.error, 10.0 * integ.error);
  EXPECT_LT(elem.error, basis.error);
  ASSERT_GE(r.dominant, 0);
  for (const auto& s : r.sources)
    if (s.measured) {
      EXPECT_LE(s.error, r.sources[static_cast<std::size_t>(r.dominant)].error);
      // the largest channel's error is the source's error
      EXPECT_DOUBLE_EQ(s.channel_error[static_cast<std::size_t>(s.channel)], s.error);
    }
  EXPECT_EQ(r.sources[static_cast<std::size_t>(r.dominant)].name, "basis");

  // The files: the report's reader reads the sources back, one row each and the base.
  const auto rows = parse_csv(slurp(out / "budget_sources.csv"));
  ASSERT_EQ(rows.size(), 6u);
  EXPECT_EQ(rows[0][0], "source");
  EXPECT_EQ(rows[3][0], "basis");
  EXPECT_EQ(rows[3][1], "yes");
  EXPECT_NEAR(std::stod(rows[3][2]), basis.error, 1e-6 * basis.error);
  EXPECT_EQ(rows[3][3], r.info.channels[static_cast<std::size_t>(basis.channel)]);
  EXPECT_EQ(rows[4][0], "element");
  EXPECT_EQ(rows[4][1], "yes");
  EXPECT_EQ(rows[5][0], "base");
  const auto per = parse_csv(slurp(out / "budget.csv"));
  ASSERT_EQ(per.size(), 4u);
  EXPECT_EQ(per[0], (std::vector<std::string>{"channel", "unit", "integration", "start-up", "basis",
                                              "element"}));
  for (std::size_t c = 1; c < per.size(); ++c) {
    EXPECT_EQ(per[c].size(), 6u);
    EXPECT_GT(std::stod(per[c][5]), 0.0);  // element: measured
  }
  const std::string md = slurp(out / "budget.md");
  EXPECT_NE(md.find("**Dominant source: basis**"), std::string::npos) << md;
  // The report page of a results file in that folder shows the budget.
  report::Page page("t");
  budget_section((out / "results.h5").string(), page);
  const std::string html = page.html();
  EXPECT_NE(html.find("Dominant source of error: basis"), std::string::npos);
  EXPECT_NE(html.find("element"), std::string::npos);
  report::Page none("t");
  budget_section((out / "elsewhere" / "results.h5").string(), none);
  EXPECT_NE(none.html().find("evas study budget SCENE"), std::string::npos);
  std::ofstream(out / "budget_sources.csv") << "a,b\n";
  report::Page bad("t");
  budget_section((out / "results.h5").string(), bad);
  EXPECT_NE(bad.html().find("is not a budget_sources.csv"), std::string::npos);
  fs::remove_all(out);
}

// A scene without a finer element model: the element row is not measured, with
// the reason, and its cells are empty (no NaN written).
TEST(Budget, NoFinerElementIsSaidSo) {
  const fs::path out = fs::temp_directory_path() / ("evas_budget_d_" + std::to_string(::getpid()));
  fs::remove_all(out);
  Options o;
  o.scene = std::string(EVAS_SOURCE_DIR) + "/scenes/demo.yaml";
  o.t_end = 0.01;
  o.out_dir = out.string();
  o.plot = false;
  const BudgetResult r = budget(o, BudgetOptions{});
  ASSERT_EQ(r.sources.size(), 4u);
  const BudgetSource& elem = r.sources[3];
  EXPECT_FALSE(elem.measured);
  EXPECT_NE(elem.note.find("no element of the scene has a finer model"), std::string::npos)
      << elem.note;
  const auto per = parse_csv(slurp(out / "budget.csv"));
  ASSERT_GE(per.size(), 2u);
  for (std::size_t c = 1; c < per.size(); ++c) EXPECT_EQ(per[c][5], "");
  fs::remove_all(out);
}

// --orders N keeps the Fourier series of one cycle up to engine order N
// (harmonic k of the 720-deg cycle is order k / 2); a time grid refuses it.
TEST(Budget, LowOrdersOfACycle) {
  const int n = 720;
  Vec low(n), high(n);
  for (int i = 0; i < n; ++i) {
    const double th = 4.0 * M_PI * i / n;  // crank angle [rad] over two revolutions
    low[i] = 3.0 + 2.0 * std::cos(th - 0.3) + 0.5 * std::sin(0.5 * th) + std::cos(12.0 * th);
    high[i] = 0.7 * std::sin(12.5 * th + 1.0) + 0.2 * std::cos(30.0 * th);
  }
  EXPECT_LT((low_orders(low + high, 12) - low).cwiseAbs().maxCoeff(), 1e-11);
  Vec half(n);  // orders 0 and 0.5 of `low`
  for (int i = 0; i < n; ++i) half[i] = 3.0 + 0.5 * std::sin(2.0 * M_PI * i / n);
  EXPECT_LT((low_orders(low + high, 0.5) - half).cwiseAbs().maxCoeff(), 1e-11);
  Options o;
  o.scene = std::string(EVAS_SOURCE_DIR) + "/scenes/demo.yaml";
  o.out_dir =
      (fs::temp_directory_path() / ("evas_budget_t_" + std::to_string(::getpid()))).string();
  BudgetOptions bo;
  bo.orders = 12;
  EXPECT_THROW(budget(o, bo), InputError);
  fs::remove_all(o.out_dir);
}

TEST(Budget, ModeCutsRemovedAndCsvFields) {
  std::string changed;
  const std::string text =
      "bodies:\n"
      "  - {name: a, file: a.h5, modes: {max_frequency: 100, quasi_static_above: 50}}\n"
      "  - {name: b, file: b.h5}\n"
      "  - {name: c, file: c.h5, modes: {elastic: 4, damping: 0.1}}\n";
  const std::string out = without_mode_cuts(text, changed);
  EXPECT_EQ(changed, "a, c");
  EXPECT_EQ(out.find("max_frequency"), std::string::npos);
  EXPECT_EQ(out.find("quasi_static_above"), std::string::npos);
  EXPECT_EQ(out.find("elastic"), std::string::npos);
  EXPECT_NE(out.find("damping"), std::string::npos);
  EXPECT_EQ(without_mode_cuts("bodies:\n  - {name: b, file: b.h5}\n", changed),
            "bodies:\n  - {name: b, file: b.h5}\n");
  EXPECT_EQ(changed, "");
  // the finer films: every journal bearing coarser than Reynolds' equation
  const std::string els =
      "elements:\n"
      "  - {name: m1, type: journal-bearing, radius: 0.04}\n"
      "  - {name: m2, type: journal-bearing, film: finite}\n"
      "  - {name: m3, type: journal-bearing, film: reynolds}\n"
      "  - {name: m4, type: journal-bearing, film: short, cavitation: none}\n"
      "  - {name: s, type: spring-damper}\n";
  EXPECT_EQ(finer_element_edits(els, changed),
            (std::vector<std::string>{"m1.film=reynolds", "m1.solve=table", "m2.film=reynolds",
                                      "m2.solve=table", "m4.film=reynolds", "m4.solve=grid"}));
  EXPECT_EQ(changed, "m1, m2, m4");
  EXPECT_TRUE(finer_element_edits("elements: []\n", changed).empty());
  EXPECT_EQ(changed, "");
  const auto rows = parse_csv("a,\"b, \"\"c\"\"\",\r\n,x\n");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0], (std::vector<std::string>{"a", "b, \"c\"", ""}));
  EXPECT_EQ(rows[1], (std::vector<std::string>{"", "x"}));
}

}  // namespace
}  // namespace evas::study
