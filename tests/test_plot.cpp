// evas plot (plot/figures.h): every kind draws the validation engine's results
// as PNG and SVG, with its data beside it; the data are the results' own values
// (the polar diagram's load on the shell is -f in kN, the orbit's clearance
// circle has the scene's clearance, read back from |e| / eps), and a figure the
// file cannot give is an error naming what is there.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "io/results.h"
#include "plot/gnuplot.h"
#include "plot/gnuplot_process.h"
#include "post/radiation.h"
#include "run_faults_support.h"

namespace {

const std::string kEngine = std::string(EVAS_SOURCE_DIR) + "/validation/engine/engine.yaml";

// One engine run shared by the tests: 0.05 s at 3000 rpm, 2.5 revolutions
// (more than one 720-deg cycle) on the 1-deg crank-angle grid.
const fs::path& engine_results() {
  static TempFolder tmp;
  static const fs::path results = [] {
    const Outcome o =
        run_evas({"run", kEngine, "--t-end", "0.05", "--out", (tmp.path() / "e").string()},
                 tmp.path() / "run.log");
    EXPECT_EQ(o.code, 0) << o.log;
    return tmp.path() / "e" / "results.h5";
  }();
  return results;
}

// Rows of numbers of block `index` of a gnuplot data file (blocks are
// separated by two blank lines).
std::vector<std::vector<double>> data_block(const fs::path& dat, int index) {
  std::ifstream f(dat);
  std::vector<std::vector<double>> rows;
  std::string line;
  int block = 0, blanks = 0;
  while (std::getline(f, line)) {
    if (line.empty()) {
      if (++blanks == 2) ++block;
      continue;
    }
    blanks = 0;
    if (block != index) continue;
    std::istringstream is(line);
    std::vector<double> r;
    double x;
    while (is >> x) r.push_back(x);
    rows.push_back(r);
  }
  return rows;
}

Outcome plot(const std::vector<std::string>& extra, const fs::path& out) {
  std::vector<std::string> args = {"plot"};
  args.insert(args.end(), extra.begin(), extra.end());
  args.push_back("--out");
  args.push_back(out.string());
  return run_evas(args, out.parent_path() / "plot.log");
}

}  // namespace

TEST(Plot, EveryKindDrawsPngAndSvgWithItsData) {
  TempFolder tmp;
  const std::string r = engine_results().string();
  const std::vector<std::vector<std::string>> kinds = {
      {"channels", r, "--channel", "main*.fy"},
      {"polar", r, "--element", "main3"},
      {"orbit", r, "--element", "main3"},
      {"film", r, "--element", "main3"},
      {"order", r, "--channel", "main3.fy", "--cycles", "1"},
      {"spectrum", r, "--channel", "main3.fy", "--window", "flattop"},
      {"erp", r, "--channel", "skin"}};
  for (const auto& k : kinds)
    for (const char* ext : {".png", ".svg"}) {
      SCOPED_TRACE(k[0] + ext);
      const fs::path out = tmp.path() / (k[0] + ext);
      const Outcome o = plot(k, out);
      ASSERT_EQ(o.code, 0) << o.log;
      EXPECT_GT(fs::file_size(out), 5000u);
      EXPECT_TRUE(fs::exists(tmp.path() / (k[0] + ".gp")));
      EXPECT_TRUE(fs::exists(tmp.path() / (k[0] + ".dat")));
    }
}

TEST(Plot, PolarAndOrbitDataAreTheResultsOwnValues) {
  TempFolder tmp;
  const evas::ResultsData d = evas::read_results(engine_results().string());
  auto col = [&](const std::string& n) {
    for (std::size_t i = 0; i < d.names.size(); ++i)
      if (d.names[i] == n) return static_cast<Eigen::Index>(i);
    ADD_FAILURE() << "no " << n;
    return Eigen::Index{0};
  };
  ASSERT_EQ(
      plot({"polar", engine_results().string(), "--element", "main2"}, tmp.path() / "p.png").code,
      0);
  // the last cycle: the 720 rows after crank angle end - 720 (1-deg grid; a
  // cycle's rows as evas spectrum counts them, not the row 720 deg back)
  const Eigen::Index n = d.values.rows();
  Eigen::Index r0 = n - 1;
  while (r0 > 0 &&
         d.values(r0 - 1, col("crank_angle")) > d.values(n - 1, col("crank_angle")) - 720 + 0.5)
    --r0;
  ASSERT_EQ(n - r0, 720);
  const auto shell = data_block(tmp.path() / "p.dat", 0),
             journal = data_block(tmp.path() / "p.dat", 1);
  ASSERT_EQ(shell.size(), static_cast<std::size_t>(n - r0));
  ASSERT_EQ(journal.size(), shell.size());
  for (Eigen::Index r = r0; r < n; r += 37) {
    const auto& s = shell[static_cast<std::size_t>(r - r0)];
    const auto& j = journal[static_cast<std::size_t>(r - r0)];
    EXPECT_NEAR(s[0], -1e-3 * d.values(r, col("main2.fx")), 1e-9 * (1 + std::abs(s[0])));
    EXPECT_NEAR(s[1], -1e-3 * d.values(r, col("main2.fy")), 1e-9 * (1 + std::abs(s[1])));
    EXPECT_NEAR(j[0], 1e-3 * d.values(r, col("main2.fx_journal")), 1e-9 * (1 + std::abs(j[0])));
  }
  // labels every 90 deg of the cycle, 4 in each half, each half with the centre
  EXPECT_EQ(data_block(tmp.path() / "p.dat", 2).size(), 5u);
  EXPECT_EQ(data_block(tmp.path() / "p.dat", 3).size(), 5u);
  // the orbit's circle: the scene's clearance 3e-5 m = 30 um
  ASSERT_EQ(
      plot({"orbit", engine_results().string(), "--element", "main2"}, tmp.path() / "o.png").code,
      0);
  const auto circle = data_block(tmp.path() / "o.dat", 1);
  ASSERT_EQ(circle.size(), 361u);
  EXPECT_NEAR(std::hypot(circle[45][0], circle[45][1]), 30.0, 1e-6);
  const auto orbit = data_block(tmp.path() / "o.dat", 0);
  for (const auto& p : orbit) EXPECT_LT(std::hypot(p[0], p[1]), 30.0);
}

TEST(Plot, FiguresTheFileCannotGiveAreErrorsNamingWhatIsThere) {
  TempFolder tmp;
  const std::string r = engine_results().string();
  struct Bad {
    std::vector<std::string> args;
    std::string says;
  };
  for (const Bad& b : std::vector<Bad>{
           {{"polar", r, "--element", "cyl1"},
            "journal bearings in this file: main1, main2, main3, main4, main5"},
           {{"waterfall", r}, "a waterfall is drawn from a sweep over operating points"},
           {{"pie", r},
            "unknown kind 'pie' (known: channels, polar, orbit, film, order, order-track, "
            "spectrum, erp, "
            "waterfall, campbell, order-cuts, work-precision)"},
           {{"channels", r, "--channel", "main9.*"},
            "no channel matches 'main9.*'; channels here: crank_angle"},
           {{"orbit", r}, "give --element NAME"},
           {{"work-precision", r},
            "is not a work-precision study's file (no 'study' attribute: a run's results?)"},
           {{"campbell", r}, "is not a sweep file (no 'study' attribute: a run's results?)"},
           {{"erp", r, "--channel", "main1"}, "no channel 'main1.c0' (the ERP components"},
           {{"film", r, "--element", "main1", "--cycles", "9"}, "less than 9 cycle(s)"},
           {{"order", r, "--channel", "main1.fy", "--element", "main1"},
            "--element applies to polar"}}) {
    SCOPED_TRACE(b.says);
    const Outcome o = plot(b.args, tmp.path() / "x.png");
    EXPECT_EQ(o.code, 1) << o.log;
    EXPECT_NE(o.log.find(b.says), std::string::npos) << o.log;
    EXPECT_FALSE(fs::exists(tmp.path() / "x.png"));
  }
  const Outcome jpg = plot({"polar", r, "--element", "main1"}, tmp.path() / "x.jpg");
  EXPECT_EQ(jpg.code, 1);
  EXPECT_NE(jpg.log.find("ending in .png or .svg"), std::string::npos) << jpg.log;
  // an order spectrum needs the crank-angle grid: the demo runs on the time grid
  const Outcome demo = run_evas({"run", std::string(EVAS_SOURCE_DIR) + "/scenes/demo.yaml",
                                 "--t-end", "0.01", "--out", (tmp.path() / "d").string()},
                                tmp.path() / "d.log");
  ASSERT_EQ(demo.code, 0) << demo.log;
  const Outcome o =
      plot({"order", (tmp.path() / "d" / "results.h5").string(), "--channel", "bearing_left.fx"},
           tmp.path() / "y.png");
  EXPECT_EQ(o.code, 1);
  EXPECT_NE(o.log.find("needs the crank-angle output grid"), std::string::npos) << o.log;
}

// The block's side walls (engine.yaml: {surface: side_walls, ...}): the mean
// ERP that `evas spectrum --erp` forms from the components c_k equals the mean
// of the skin.erp channel over the same samples; its third-octave bands are
// the figure's; a name that is no surface output is an error naming those
// there are.
TEST(Plot, ErpOfTheBlockSideWallsFromItsComponents) {
  TempFolder tmp;
  const std::string r = engine_results().string();
  const Outcome s = run_evas({"spectrum", r, "--erp", "skin", "--from", "0.02", "--bands",
                              "third-octave", "--csv", (tmp.path() / "bands.csv").string()},
                             tmp.path() / "spectrum.log");
  ASSERT_EQ(s.code, 0) << s.log;
  const auto at = s.log.find("mean ERP ");
  ASSERT_NE(at, std::string::npos) << s.log;
  const double mean = std::stod(s.log.substr(at + 9));
  const evas::ResultsData d = evas::read_results(r);
  int erp = -1;
  for (std::size_t i = 0; i < d.names.size(); ++i)
    if (d.names[i] == "skin.erp") erp = static_cast<int>(i);
  ASSERT_GE(erp, 0);
  double sum = 0.0;
  int n = 0;
  for (std::size_t k = 0; k < d.time.size(); ++k)
    if (d.time[k] >= 0.02) {
      sum += d.values(static_cast<Eigen::Index>(k), erp);
      ++n;
    }
  ASSERT_GT(sum, 0.0);
  EXPECT_NEAR(mean, sum / n, 1e-5 * mean);  // printed with 6 digits
  std::ifstream bands(tmp.path() / "bands.csv");
  std::string header;
  std::getline(bands, header);
  EXPECT_EQ(header,
            "centre[Hz],lower[Hz],upper[Hz],erp[W],level[dB re 1 pW],bins,erp_elastic[W],"
            "level_elastic[dB re 1 pW],level_elastic_A[dB(A) re 1 pW]");
  // the elastic part from the components e_k is the channel skin.erp_elastic,
  // and below the whole (the block rocks on its mounts)
  const std::string key =
      "elastic part (the body's deformation; the rigid-body motion left out): mean ";
  const auto at_e = s.log.find(key);
  ASSERT_NE(at_e, std::string::npos) << s.log;
  const double mean_e = std::stod(s.log.substr(at_e + key.size()));
  int erp_e = -1;
  for (std::size_t i = 0; i < d.names.size(); ++i)
    if (d.names[i] == "skin.erp_elastic") erp_e = static_cast<int>(i);
  ASSERT_GE(erp_e, 0);
  double sum_e = 0.0;
  for (std::size_t k = 0; k < d.time.size(); ++k)
    if (d.time[k] >= 0.02) sum_e += d.values(static_cast<Eigen::Index>(k), erp_e);
  EXPECT_NEAR(mean_e, sum_e / n, 1e-5 * mean_e);
  EXPECT_LT(mean_e, mean);
  // --radiation: sigma and the radiated power sigma * elastic per band
  const Outcome r2 =
      run_evas({"spectrum", r, "--erp", "skin", "--from", "0.02", "--bands", "third-octave",
                "--radiation", "piston:0.3", "--csv", (tmp.path() / "radiated.csv").string()},
               tmp.path() / "radiated.log");
  ASSERT_EQ(r2.code, 0) << r2.log;
  std::ifstream rad(tmp.path() / "radiated.csv");
  std::getline(rad, header);
  EXPECT_NE(header.find(",sigma,radiated[W],level_radiated[dB re 1 pW],"
                        "level_radiated_A[dB(A) re 1 pW]"),
            std::string::npos)
      << header;
  std::string line;
  int rows = 0;
  while (std::getline(rad, line)) {
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string x; std::getline(ss, x, ',');) f.push_back(x);
    ASSERT_GE(f.size(), 11u) << line;
    const double centre = std::stod(f[0]), elastic = std::stod(f[6]), sigma = std::stod(f[9]),
                 radiated = std::stod(f[10]);
    EXPECT_NEAR(sigma, evas::piston_radiation_efficiency(centre, 0.3), 1e-5 * sigma) << line;
    EXPECT_NEAR(radiated, sigma * elastic, 1e-5 * radiated + 1e-300) << line;
    ++rows;
  }
  EXPECT_GT(rows, 20);
  EXPECT_EQ(run_evas({"spectrum", r, "--channel", "skin.erp", "--radiation", "piston:0.3"},
                     tmp.path() / "r3.log")
                .code,
            1);
  ASSERT_EQ(plot({"erp", r, "--channel", "skin", "--from", "0.02"}, tmp.path() / "erp.png").code,
            0);
  EXPECT_FALSE(data_block(tmp.path() / "erp.dat", 1).empty());
  const Outcome bad = run_evas({"spectrum", r, "--erp", "walls"}, tmp.path() / "bad.log");
  EXPECT_EQ(bad.code, 1);
  EXPECT_NE(bad.log.find("no surface output 'walls' (no channels walls.c0, ...; surface outputs "
                         "in the file: skin)"),
            std::string::npos)
      << bad.log;
}

// A gnuplot process started before its figures (plot/gnuplot_process.h), as a
// sweep starts it: it draws the scripts it is given in their folder, says when
// gnuplot failed on one, and one that never draws ends with its owner.
TEST(Plot, AStartedGnuplotDrawsItsScriptsLater) {
  if (!evas::have_gnuplot()) GTEST_SKIP() << "gnuplot is not installed";
  TempFolder tmp;
  const std::vector<fs::path> scripts = {tmp.path() / "a.gp", tmp.path() / "b.gp"};
  for (const auto& s : scripts) {
    std::ofstream f(s);
    f << evas::gp_terminal(fs::path(s).replace_extension(".png"), 200, 150) << "plot sin(x)\n";
  }
  {
    evas::GnuplotProcess gp;
    ASSERT_TRUE(gp.ready());
    EXPECT_TRUE(gp.draw(scripts));
    EXPECT_FALSE(gp.ready());
    EXPECT_FALSE(gp.draw(scripts));  // once only
  }
  for (const char* png : {"a.png", "b.png"}) {
    ASSERT_TRUE(fs::exists(tmp.path() / png)) << png;
    EXPECT_GT(fs::file_size(tmp.path() / png), 500u) << png;
  }
  // a script gnuplot refuses: false, and the figure is not there
  {
    std::ofstream f(tmp.path() / "bad.gp");
    f << evas::gp_terminal(tmp.path() / "bad.png", 200, 150) << "plot $NoSuchBlock\n";
  }
  evas::GnuplotProcess gp;
  EXPECT_FALSE(gp.draw({tmp.path() / "bad.gp"}));
  EXPECT_FALSE(fs::exists(tmp.path() / "bad.png") && fs::file_size(tmp.path() / "bad.png") > 500);
  evas::GnuplotProcess unused;  // ends with the test, drawing nothing
  EXPECT_TRUE(unused.ready());
}

// have_gnuplot looks for an executable regular file `gnuplot` in the folders
// of PATH, as the shell's `command -v` does: not a folder of that name, not a
// file without execute permission, and an empty PATH entry is the current
// folder.
TEST(Plot, GnuplotIsLookedUpOnThePath) {
  TempFolder tmp;
  const fs::path none = tmp.path() / "none", exe = tmp.path() / "exe", dir = tmp.path() / "dir",
                 plain = tmp.path() / "plain";
  for (const auto& d : {none, exe, dir, plain}) fs::create_directories(d);
  write_text(exe / "gnuplot", "#!/bin/sh\n");
  fs::permissions(exe / "gnuplot", fs::perms::owner_all);
  fs::create_directories(dir / "gnuplot");
  write_text(plain / "gnuplot", "not a program\n");
  fs::permissions(plain / "gnuplot", fs::perms::owner_read | fs::perms::owner_write);
  const char* old = std::getenv("PATH");
  const std::string saved = old ? old : "";
  auto with_path = [](const std::string& p) {
    ::setenv("PATH", p.c_str(), 1);
    return evas::have_gnuplot();
  };
  EXPECT_FALSE(with_path(none.string()));
  EXPECT_FALSE(with_path(dir.string() + ":" + none.string()));
  EXPECT_TRUE(with_path(none.string() + ":" + exe.string()));
  EXPECT_TRUE(with_path(dir.string() + "::" + exe.string()));
  const fs::path here = fs::current_path();
  fs::current_path(exe);
  EXPECT_TRUE(with_path(none.string() + ":"));  // the empty entry: this folder
  fs::current_path(here);
  EXPECT_FALSE(with_path(none.string() + ":"));
  EXPECT_FALSE(with_path(plain.string()));  // no execute bit (refused to root as well)
  ::setenv("PATH", saved.c_str(), 1);
}
