// evas report (plot/report_page.h): the report of a short run of the
// validation engine has every section and figure, its links are relative and
// resolve, a real browser (headless Chromium) displays every figure without a
// console error; bad inputs are errors naming what is wrong, and a report is
// not replaced without --overwrite.
#include <gtest/gtest.h>

#include <cstdlib>
#include <regex>
#include <set>

#include "run_faults_support.h"

namespace {

const std::string kEngine = std::string(EVAS_SOURCE_DIR) + "/validation/engine/engine.yaml";

TempFolder& shared_folder() {
  static TempFolder tmp;
  return tmp;
}

// One engine run shared by the tests: 0.05 s at 3000 rpm, 2.5 revolutions
// (one whole 720-deg cycle) on the 1-deg crank-angle grid.
const fs::path& engine_results() {
  static const fs::path results = [] {
    const fs::path& dir = shared_folder().path();
    const Outcome o = run_evas({"run", kEngine, "--t-end", "0.05", "--out", (dir / "e").string()},
                               dir / "run.log");
    EXPECT_EQ(o.code, 0) << o.log;
    return dir / "e" / "results.h5";
  }();
  return results;
}

// Its report, written once.
const fs::path& engine_report() {
  static const fs::path index = [] {
    const fs::path dir = shared_folder().path() / "report";
    const Outcome o = run_evas({"report", engine_results().string(), "--out", dir.string()},
                               shared_folder().path() / "report.log");
    EXPECT_EQ(o.code, 0) << o.log;
    return dir / "index.html";
  }();
  return index;
}

// Every value of attribute `attr` (src, href) in the page.
std::vector<std::string> attribute_values(const std::string& html, const std::string& attr) {
  std::vector<std::string> out;
  const std::regex re("\\s" + attr + "=\"([^\"]*)\"");
  for (auto it = std::sregex_iterator(html.begin(), html.end(), re); it != std::sregex_iterator();
       ++it)
    out.push_back((*it)[1]);
  return out;
}

std::string which(const std::string& program) {
  const char* path = std::getenv("PATH");
  std::stringstream ss(path ? path : "/usr/bin:/bin");
  std::string dir;
  while (std::getline(ss, dir, ':'))
    if (!dir.empty() && access((fs::path(dir) / program).c_str(), X_OK) == 0)
      return (fs::path(dir) / program).string();
  return "";
}

// Headless Chromium's DOM of `page` after the load (and its stderr log).
struct Browser {
  int code = -1;
  std::string dom, log;
};
Browser chromium_dump(const std::string& chromium, const fs::path& page, const fs::path& work) {
  const fs::path dom = work / "dom.html", log = work / "chromium.log";
  const std::string cmd = "timeout 180 " + chromium +
                          " --headless --no-sandbox --disable-gpu --no-first-run"
                          " --user-data-dir=" +
                          (work / "profile").string() +
                          " --enable-logging=stderr --v=0 --virtual-time-budget=5000"
                          " --dump-dom 'file://" +
                          fs::absolute(page).string() + "' > " + dom.string() + " 2> " +
                          log.string();
  Browser b;
  const int status = std::system(cmd.c_str());
  b.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  b.dom = read_text(dom);
  b.log = read_text(log);
  return b;
}

std::string body_attribute(const std::string& dom, const std::string& name) {
  std::smatch m;
  if (std::regex_search(dom, m, std::regex("<body[^>]*\\s" + name + "=\"([^\"]*)\""))) return m[1];
  return "(none)";
}

}  // namespace

TEST(Report, HasEverySectionAndFigureAndItsLinksResolve) {
  const fs::path& index = engine_report();
  ASSERT_TRUE(fs::exists(index));
  const fs::path dir = index.parent_path();
  const std::string html = read_text(index);
  EXPECT_EQ(html.rfind("<!DOCTYPE html>\n<html lang=\"en\">", 0), 0u);
  EXPECT_TRUE(contains(html, "<meta charset=\"utf-8\">"));
  EXPECT_TRUE(contains(html, "<title>Engine report: "));
  for (const char* id :
       {"summary", "bearings", "loads", "orders", "friction", "torsion", "surface"})
    EXPECT_TRUE(contains(html, std::string("<h2 id=\"") + id + "\">")) << id;
  // the summary: scene, grid, statistics
  for (const char* s : {"crank-angle, 1 deg per row", "Integrator statistics", "residual_evals",
                        "main1, main2, main3, main4, main5", "3000.0 rpm"})
    EXPECT_TRUE(contains(html, s)) << s;
  // every expected figure, each once, each a file of the folder with its script and data
  // (the engine scene's block side walls: {surface: side_walls, ..., name: skin})
  std::set<std::string> expected = {
      "loads_fx.png",          "loads_fy.png",     "friction_power.png",   "torsion_crank.png",
      "order_crank_twist.png", "torsion_dyno.png", "order_dyno_twist.png", "surface_vn_rms.png",
      "surface_vn_mean.png",   "surface_erp.png",  "erp_spectrum_skin.png"};
  for (int b = 1; b <= 5; ++b)
    for (const char* k : {"polar_main", "orbit_main", "film_main"})
      expected.insert(k + std::to_string(b) + ".png");
  for (int b = 1; b <= 5; ++b)
    for (const char* c : {"_fx", "_fy"})
      expected.insert("order_main" + std::to_string(b) + c + ".png");
  const auto srcs = attribute_values(html, "src");
  EXPECT_EQ(std::set<std::string>(srcs.begin(), srcs.end()), expected);
  EXPECT_EQ(srcs.size(), expected.size());
  // every figure has a caption
  EXPECT_EQ(attribute_values(html, "id").size() >= expected.size(), true);
  std::size_t captions = 0;
  for (auto p = html.find("<figcaption>Figure "); p != std::string::npos;
       p = html.find("<figcaption>Figure ", p + 1))
    ++captions;
  EXPECT_EQ(captions, expected.size());
  for (const auto& s : srcs) {
    EXPECT_GT(fs::file_size(dir / s), 5000u) << s;
    EXPECT_TRUE(fs::exists(dir / fs::path(s).replace_extension(".gp"))) << s;
  }
  // links: relative, into the folder or the page itself, and they resolve
  for (const auto& h : attribute_values(html, "href")) {
    if (h.rfind("#", 0) == 0) {
      EXPECT_TRUE(contains(html, "id=\"" + h.substr(1) + "\"")) << h;
      continue;
    }
    EXPECT_FALSE(contains(h, ":")) << h;
    EXPECT_NE(h.rfind("/", 0), 0u) << h;
    EXPECT_FALSE(contains(h, "..")) << h;
    EXPECT_TRUE(fs::exists(dir / h)) << h;
  }
  // no external resource
  EXPECT_FALSE(contains(html, "http:"));
  EXPECT_FALSE(contains(html, "https:"));
  EXPECT_FALSE(contains(html, "<link"));
  // valid HTML5 by HTML Tidy (5.x reads HTML5) when it is installed
  if (const std::string tidy = which("tidy"); !tidy.empty()) {
    const fs::path log = dir.parent_path() / "tidy.log";
    const int rc =
        std::system((tidy + " -q -e " + index.string() + " > " + log.string() + " 2>&1").c_str());
    EXPECT_EQ(rc, 0);
    EXPECT_EQ(read_text(log), "") << "tidy -q -e " << index;
  }
  // the order table in kN and the notes of what the file does not hold
  EXPECT_TRUE(contains(html, "largest engine orders"));
  EXPECT_TRUE(contains(html, "equivalent radiated power spectrum of skin"));
}

TEST(Report, ARealBrowserShowsEveryFigure) {
  std::string chromium = which("chromium");
  if (chromium.empty()) chromium = which("chromium-browser");
  if (chromium.empty()) {
    if (std::getenv("CI"))
      FAIL() << "chromium is not installed (make deps installs it; CI must have it)";
    GTEST_SKIP() << "chromium is not installed (apt-get install chromium): the report is not "
                    "checked in a browser";
  }
  const fs::path& index = engine_report();
  ASSERT_TRUE(fs::exists(index));
  const std::size_t figures = attribute_values(read_text(index), "src").size();
  ASSERT_GE(figures, 25u);
  TempFolder work;
  const Browser b = chromium_dump(chromium, index, work.path());
  ASSERT_EQ(b.code, 0) << b.log;
  EXPECT_EQ(body_attribute(b.dom, "data-images"), std::to_string(figures)) << b.log;
  EXPECT_EQ(body_attribute(b.dom, "data-images-loaded"), std::to_string(figures)) << b.log;
  EXPECT_EQ(body_attribute(b.dom, "data-images-failed"), "");
  // a console message (an error in the page's script: "Uncaught ...") is
  // logged as "INFO:CONSOLE:LINE] ..."; the page writes none
  for (const char* bad : {"Uncaught", "Failed to load", "ERR_FILE_NOT_FOUND", ":CONSOLE"})
    EXPECT_FALSE(contains(b.log, bad)) << bad << "\n" << b.log;
  std::cout << "chromium: " << body_attribute(b.dom, "data-images-loaded") << " of "
            << body_attribute(b.dom, "data-images") << " figures displayed\n";

  // the count is a measurement: a copy of the report moved elsewhere still
  // shows every figure, and one figure taken away is seen missing
  const fs::path moved = work.path() / "moved";
  fs::copy(index.parent_path(), moved, fs::copy_options::recursive);
  fs::remove(moved / "orbit_main2.png");
  TempFolder work2;
  const Browser m = chromium_dump(chromium, moved / "index.html", work2.path());
  ASSERT_EQ(m.code, 0) << m.log;
  EXPECT_EQ(body_attribute(m.dom, "data-images"), std::to_string(figures));
  EXPECT_EQ(body_attribute(m.dom, "data-images-loaded"), std::to_string(figures - 1));
  EXPECT_EQ(body_attribute(m.dom, "data-images-failed"), "orbit_main2.png");
  std::cout << "chromium, one figure removed: " << body_attribute(m.dom, "data-images-loaded")
            << " of " << body_attribute(m.dom, "data-images")
            << " displayed, failed: " << body_attribute(m.dom, "data-images-failed") << "\n";
}

TEST(Report, IsNotReplacedWithoutOverwrite) {
  const fs::path& index = engine_report();
  ASSERT_TRUE(fs::exists(index));
  TempFolder tmp;
  const fs::path dir = tmp.path() / "r";
  fs::create_directories(dir);
  write_text(dir / "index.html", "an earlier report");
  const Outcome refused =
      run_evas({"report", engine_results().string(), "--out", dir.string()}, tmp.path() / "1.log");
  EXPECT_EQ(refused.code, 1) << refused.log;
  EXPECT_TRUE(contains(refused.log, "index.html: a report is there already; give --overwrite"))
      << refused.log;
  EXPECT_EQ(read_text(dir / "index.html"), "an earlier report");
  const Outcome replaced = run_evas({"report", engine_results().string(), "--out", dir.string(),
                                     "--overwrite", "--title", "Case <1> & more", "--cycles", "1"},
                                    tmp.path() / "2.log");
  EXPECT_EQ(replaced.code, 0) << replaced.log;
  const std::string html = read_text(dir / "index.html");
  EXPECT_TRUE(contains(html, "<title>Case &lt;1&gt; &amp; more</title>"));
  EXPECT_TRUE(contains(html, "the last 1 cycle(s) of 720 deg"));
}

TEST(Report, BadInputsAreErrorsNamingWhatIsWrong) {
  TempFolder tmp;
  const std::string r = engine_results().string();
  write_text(tmp.path() / "a_file", "x");
  // the demo runs on the time grid, with spring-damper bearings
  const Outcome demo = run_evas({"run", std::string(EVAS_SOURCE_DIR) + "/scenes/demo.yaml",
                                 "--t-end", "0.01", "--out", (tmp.path() / "d").string()},
                                tmp.path() / "d.log");
  ASSERT_EQ(demo.code, 0) << demo.log;
  struct Bad {
    std::vector<std::string> args;
    std::string says;
  };
  for (const Bad& b : std::vector<Bad>{
           {{(tmp.path() / "none.h5").string(), "--out", (tmp.path() / "x").string()},
            "none.h5: no such results file"},
           {{r, "--out", (tmp.path() / "a_file").string()}, "a_file: is a file, not a folder"},
           {{(tmp.path() / "d" / "results.h5").string(), "--out", (tmp.path() / "x").string()},
            "not an engine run on the crank-angle grid (output grid 'time')"},
           {{(tmp.path() / "d" / "results.h5").string(), "--out", (tmp.path() / "x").string()},
            "channels (bearing_left.fx"},
           {{r, "--out", (tmp.path() / "x").string(), "--cycles", "3"},
            "--cycles 3: " + r + " covers"},
           {{r}, "need RESULTS.h5 and --out DIR"}}) {
    SCOPED_TRACE(b.says);
    std::vector<std::string> args = {"report"};
    args.insert(args.end(), b.args.begin(), b.args.end());
    const Outcome o = run_evas(args, tmp.path() / "bad.log");
    EXPECT_EQ(o.code, 1) << o.log;
    EXPECT_TRUE(contains(o.log, b.says)) << o.log;
    EXPECT_FALSE(fs::exists(tmp.path() / "x" / "index.html"));
  }
}

// A crank-angle run without journal-bearing channels: a report of what there
// is (summary, torsion), its bearing sections naming the request to add; over
// an earlier report with --overwrite, it leaves none of that one's figures.
TEST(Report, WithoutJournalBearingsShowsWhatThereIs) {
  TempFolder tmp;
  std::string scene = read_text(kEngine);
  const std::string v = std::string(EVAS_SOURCE_DIR) + "/validation/";
  for (const std::string rel : {"../bodies/", "../data/"})
    for (auto p = scene.find(rel); p != std::string::npos; p = scene.find(rel, p))
      scene.replace(p, rel.size(), v + rel.substr(3));
  for (int b = 1; b <= 5; ++b) {
    const std::string line = "    - {element: main" + std::to_string(b) + "}\n";
    const auto p = scene.find(line);
    ASSERT_NE(p, std::string::npos) << line;
    scene.erase(p, line.size());
  }
  write_text(tmp.path() / "engine.yaml", scene);
  const Outcome run = run_evas({"run", (tmp.path() / "engine.yaml").string(), "--t-end", "0.05",
                                "--out", (tmp.path() / "e").string()},
                               tmp.path() / "run.log");
  ASSERT_EQ(run.code, 0) << run.log;
  // written over the full engine's report in the same folder (--overwrite):
  // none of that report's bearing figures may stay behind, a file of the
  // user's there does
  const fs::path dir = tmp.path() / "r";
  const Outcome full = run_evas({"report", engine_results().string(), "--out", dir.string()},
                                tmp.path() / "full.log");
  ASSERT_EQ(full.code, 0) << full.log;
  write_text(dir / "my-notes.txt", "mine");
  const Outcome o = run_evas(
      {"report", (tmp.path() / "e" / "results.h5").string(), "--out", dir.string(), "--overwrite"},
      tmp.path() / "report.log");
  ASSERT_EQ(o.code, 0) << o.log;
  EXPECT_TRUE(contains(o.log, "note: no journal bearing")) << o.log;
  const std::string html = read_text(dir / "index.html");
  std::set<std::string> pngs;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ".png") pngs.insert(e.path().filename().string());
  const auto linked = attribute_values(html, "src");
  EXPECT_EQ(pngs, std::set<std::string>(linked.begin(), linked.end()))
      << "figures in the folder that the page does not show (left by the earlier report?)";
  EXPECT_EQ(read_text(dir / "my-notes.txt"), "mine");
  EXPECT_TRUE(contains(html, "no journal-bearing channels"));
  EXPECT_TRUE(contains(html, "{element: NAME}"));
  const auto srcs = attribute_values(html, "src");
  EXPECT_EQ(
      std::set<std::string>(srcs.begin(), srcs.end()),
      (std::set<std::string>{"torsion_crank.png", "order_crank_twist.png", "torsion_dyno.png",
                             "order_dyno_twist.png", "surface_vn_rms.png", "surface_vn_mean.png",
                             "surface_erp.png", "erp_spectrum_skin.png"}));
}

// The block-surface section from channels ending in .vn_rms, .vn_mean and
// .erp (the surface output request's), here written by hand on a 2-cycle
// crank-angle grid: one figure and one table per kind.
TEST(Report, SurfaceVelocityChannelsGetTheirFigures) {
  TempFolder tmp;
  const fs::path results = tmp.path() / "results.h5";
  {
    evas::ResultsWriter::Options opt;
    opt.grid = "crank-angle";
    opt.scene_text = "name: surface-only\n";
    evas::ResultsWriter w(results.string(),
                          {{"crank_angle", "deg"},
                           {"skin.vn_mean", "m/s"},
                           {"skin.vn_rms", "m/s"},
                           {"skin.erp", "W"}},
                          opt);
    for (int k = 0; k <= 1440; ++k) {
      const double a = k * M_PI / 180.0;
      w.append(k / 18000.0, {static_cast<double>(k), 1e-3 * std::sin(2 * a),
                             2e-3 + 1e-3 * std::cos(a), 0.5 + 0.1 * std::sin(4 * a)});
    }
    w.finish(evas::IntegratorStats{}, "completed");
  }
  const Outcome o = run_evas({"report", results.string(), "--out", (tmp.path() / "r").string()},
                             tmp.path() / "report.log");
  ASSERT_EQ(o.code, 0) << o.log;
  const std::string html = read_text(tmp.path() / "r" / "index.html");
  const auto srcs = attribute_values(html, "src");
  EXPECT_EQ(
      std::set<std::string>(srcs.begin(), srcs.end()),
      (std::set<std::string>{"surface_vn_rms.png", "surface_vn_mean.png", "surface_erp.png"}));
  EXPECT_TRUE(contains(html, "<td>skin.erp</td><td class=\"n\">0.5</td>")) << html;
  EXPECT_TRUE(contains(html, "Engine report: surface-only"));
  EXPECT_TRUE(contains(html, "2 whole cycle(s) of 720 deg"));
  EXPECT_FALSE(contains(html, "no surface-velocity channels"));
}
