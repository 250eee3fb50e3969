// Integrator plug-ins (integrators/plugin.h) with the example plug-in
// examples/radau_plugin (two-stage Radau IIA; Hairer & Wanner, Solving ODEs II,
// 2nd ed. 1996, sec. IV.5): loaded in this process, it is made by name like a
// built-in integrator and shows its order 3 on a damped oscillator with a
// closed-form solution (tests/sdof_problem.h); loaded by the evas program with
// --plugin, it runs the demo scene and agrees with IDA; loading errors name the
// plug-in and what is wrong.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "integrators/integrator.h"
#include "integrators/plugin.h"
#include "integrators/settings.h"
#include "io/results.h"
#include "sdof_problem.h"

using namespace evas;
namespace fs = std::filesystem;

namespace {

const std::string kPlugin = EVAS_RADAU_PLUGIN;
const fs::path kEvas = fs::path(EVAS_BINARY_DIR) / "evas";

double run_error(double h) {
  test::SdofProblem p({{10.0, 0.05, 3.0, 7.0, 0.1, 0.0}, {3.0, 0.0, 0.0, 0.0, 0.0, 1.0}});
  auto integ = make_integrator("radau-iia");
  IntegratorSettings s;
  s.name = "radau-iia";
  s.step = h;
  s.rtol = 1e-12;
  s.atol = 1e-14;
  Vec q0, v0, q, v, qe, ve;
  p.initial_state(q0, v0);
  integ->init(p, 0.0, q0, v0, s);
  double err = 0.0;
  integrate(*integ, p, 0.0, {0.5, 1.0}, [&](double t, const Vec& qq, const Vec& vv) {
    p.exact(t, qe, ve);
    err = std::max({err, (qq - qe).cwiseAbs().maxCoeff(), (vv - ve).cwiseAbs().maxCoeff()});
  });
  return err;
}

struct TempDir {
  fs::path path;
  TempDir() {
    std::string tmpl = (fs::temp_directory_path() / "evas_plugins_XXXXXX").string();
    path = mkdtemp(tmpl.data());
  }
  ~TempDir() { fs::remove_all(path); }
};

int shell(const std::string& cmd) {
  const int rc = std::system(cmd.c_str());
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace

TEST(Plugins, LoadedPluginIsMadeByNameAndIsThirdOrder) {
  const std::vector<std::string> names = load_plugin(kPlugin);
  ASSERT_EQ(names, std::vector<std::string>{"radau-iia"});
  EXPECT_EQ(load_plugin(kPlugin), names);  // a second load: the same, no error
  const auto all = integrator_names();
  EXPECT_NE(std::find(all.begin(), all.end(), "radau-iia"), all.end());
  EXPECT_NE(integrator_description("radau-iia").find("Radau IIA"), std::string::npos);
  // global error at t = 1 against the closed form, step halved three times:
  // Radau IIA with s = 2 stages has order 2s - 1 = 3 (Hairer-Wanner IV.5)
  std::vector<double> err;
  for (double h : {0.02, 0.01, 0.005, 0.0025}) err.push_back(run_error(h));
  const double order = std::log2(err[2] / err[3]);
  std::printf("[ measured ] radau-iia errors %.3e %.3e %.3e %.3e, observed order %.3f\n", err[0],
              err[1], err[2], err[3], order);
  EXPECT_NEAR(order, 3.0, 0.15);
  EXPECT_LT(err[3], 1e-6);
}

TEST(Plugins, RegistryRefusesTakenAndInvalidNames) {
  EXPECT_THROW(register_integrator("ida", [] { return make_integrator("cvode"); }), InputError);
  EXPECT_THROW(register_integrator("Bad Name", [] { return make_integrator("cvode"); }),
               InputError);
  EXPECT_THROW(register_integrator("x", nullptr), InputError);
}

TEST(Plugins, LoadErrorsNameThePlugin) {
  TempDir tmp;
  const fs::path text = tmp.path / "not_a_library.so";
  std::ofstream(text) << "hello\n";
  try {
    load_plugin(text.string());
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot be loaded"), std::string::npos) << e.what();
  }
  try {
    load_plugin("no_such_plugin_anywhere");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("EVAS_PLUGIN_PATH"), std::string::npos) << e.what();
  }
}

TEST(Plugins, EvasRunsTheDemoWithThePluginAndAgreesWithIda) {
  TempDir tmp;
  const std::string scene = std::string(EVAS_SOURCE_DIR) + "/scenes/demo.yaml";
  const std::string base = kEvas.string() + " run " + scene + " -q --t-end 0.02";
  // the plug-in found by name on EVAS_PLUGIN_PATH
  const fs::path dir = fs::path(kPlugin).parent_path();
  ASSERT_EQ(shell("EVAS_PLUGIN_PATH=" + dir.string() + " " + base +
                  " --plugin evas_radau --integrator radau-iia --set step=1e-5 --out " +
                  (tmp.path / "radau").string() + " > " + (tmp.path / "log").string() + " 2>&1"),
            0)
      << read_text(tmp.path / "log");
  ASSERT_EQ(shell(base + " --set rtol=1e-10 --set atol=1e-13 --out " + (tmp.path / "ida").string() +
                  " > " + (tmp.path / "log").string() + " 2>&1"),
            0)
      << read_text(tmp.path / "log");
  const ResultsData a = read_results((tmp.path / "radau" / "results.h5").string());
  const ResultsData b = read_results((tmp.path / "ida" / "results.h5").string());
  EXPECT_EQ(a.integrator, "radau-iia");
  ASSERT_EQ(a.values.rows(), b.values.rows());
  ASSERT_EQ(a.values.cols(), b.values.cols());
  double worst = 0.0;
  for (long c = 0; c < a.values.cols(); ++c) {
    const double scale = b.values.col(c).cwiseAbs().maxCoeff();
    if (scale == 0.0) continue;
    worst = std::max(worst, (a.values.col(c) - b.values.col(c)).cwiseAbs().maxCoeff() / scale);
  }
  std::printf(
      "[ measured ] demo, radau-iia h = 1e-5 vs ida rtol 1e-10: max error %.2e of each "
      "channel's peak\n",
      worst);
  EXPECT_LT(worst, 1e-4);
  // an unknown plug-in file: exit 1 with the file named
  EXPECT_EQ(shell(base + " --plugin " + (tmp.path / "nothing.so").string() + " --out " +
                  (tmp.path / "x").string() + " > " + (tmp.path / "log").string() + " 2>&1"),
            1);
  EXPECT_NE(read_text(tmp.path / "log").find("nothing.so': no such file"), std::string::npos)
      << read_text(tmp.path / "log");
}

// `evas study amplification` measures a plug-in as it measures a built-in:
// HHT-alpha at alpha = -1/3 has the amplification of generalized-alpha at
// rho_inf = 1/2 to the digit, and at alpha = -0.1 a spectral radius at large
// h/T of (1 + alpha) / (1 - alpha) = 0.818 (Hilber, Hughes & Taylor 1977).
TEST(Plugins, AmplificationOfAPlugInIsMeasured) {
  TempDir tmp;
  const std::string plug = " --plugin " + std::string(EVAS_HHT_PLUGIN);
  const std::string log = " > " + (tmp.path / "log").string() + " 2>&1";
  ASSERT_EQ(shell(kEvas.string() + " study amplification" + plug +
                  " --case 'hht-plugin alpha=-0.3333333333333333,-0.1' --case "
                  "'generalized-alpha rho_inf=0.5' --h-over-t 0.01,0.1,1,1000 --no-plot --out " +
                  (tmp.path / "amp").string() + log),
            0)
      << read_text(tmp.path / "log");
  auto column = [&](int k, int col) {
    std::istringstream in(
        read_text(tmp.path / "amp" / ("case" + std::to_string(k)) / "amplification.csv"));
    std::vector<std::string> out;
    std::string line;
    std::getline(in, line);
    while (std::getline(in, line)) {
      std::istringstream f(line);
      std::string x;
      for (int i = 0; i <= col; ++i) std::getline(f, x, ',');
      out.push_back(x);
    }
    return out;
  };
  for (int col : {1, 2, 3}) EXPECT_EQ(column(0, col), column(2, col)) << col;
  EXPECT_NEAR(std::stod(column(1, 1).back()), 0.9 / 1.1, 1e-3);
}

// A plug-in with a setting of its own: examples/hht_plugin (HHT-alpha, Hilber,
// Hughes & Taylor 1977). Its alpha is declared, reached by --set, checked
// against its range, listed by --help-settings, named in the case labels of a
// study; at alpha = -1/3 HHT-alpha is generalized-alpha with rho_inf = 1/2
// (Chung & Hulbert 1993: alpha_m = 0, alpha_f = 1/3, gamma = 5/6, beta = 4/9),
// so the two runs agree to the bit.
TEST(Plugins, HhtPluginDeclaresAlphaThatSetReaches) {
  TempDir tmp;
  const std::string scene = std::string(EVAS_SOURCE_DIR) + "/scenes/demo.yaml";
  const std::string plug = " --plugin " + std::string(EVAS_HHT_PLUGIN);
  const std::string base = kEvas.string() + " run " + scene + " -q --t-end 0.02 --csv";
  const std::string log = " > " + (tmp.path / "log").string() + " 2>&1";
  ASSERT_EQ(shell(base + plug + " --integrator hht-plugin --set alpha=-0.3333333333333333 --out " +
                  (tmp.path / "hht").string() + log),
            0)
      << read_text(tmp.path / "log");
  ASSERT_EQ(shell(base + " --integrator generalized-alpha --set rho_inf=0.5 --out " +
                  (tmp.path / "ga").string() + log),
            0)
      << read_text(tmp.path / "log");
  EXPECT_EQ(read_text(tmp.path / "hht" / "results.csv"),
            read_text(tmp.path / "ga" / "results.csv"));
  EXPECT_NE(read_text(tmp.path / "hht" / "summary.json").find("\"alpha\": -0.33333333333333331"),
            std::string::npos);
  // the default alpha (-0.05) is another method: other numbers
  ASSERT_EQ(
      shell(base + plug + " --integrator hht-plugin --out " + (tmp.path / "hht0").string() + log),
      0);
  EXPECT_NE(read_text(tmp.path / "hht0" / "results.csv"),
            read_text(tmp.path / "ga" / "results.csv"));
  // out of range, and a setting no loaded integrator declares
  EXPECT_EQ(shell(base + plug + " --integrator hht-plugin --set alpha=-0.5 --out " +
                  (tmp.path / "bad").string() + log),
            1);
  EXPECT_NE(read_text(tmp.path / "log").find("alpha: -0.5 is outside [-0.3333333333333333, 0]"),
            std::string::npos)
      << read_text(tmp.path / "log");
  EXPECT_EQ(shell(base + " --integrator generalized-alpha --set alfa=-0.1 --out " +
                  (tmp.path / "bad2").string() + log),
            1);
  EXPECT_NE(read_text(tmp.path / "log").find("'alfa' is not an integrator setting"),
            std::string::npos)
      << read_text(tmp.path / "log");
  // --help-settings lists it; a study's case grid sweeps it and its labels name it
  ASSERT_EQ(shell(kEvas.string() + " run --help-settings" + plug + log), 0);
  EXPECT_NE(read_text(tmp.path / "log").find("| `alpha` | -0.05 | hht-plugin (its own) |"),
            std::string::npos)
      << read_text(tmp.path / "log");
  ASSERT_EQ(shell(kEvas.string() + " study work-precision " + scene + plug +
                  " --t-end 0.02 --no-plot -q --case 'hht-plugin alpha=-0.3,-0.1 step=1e-4' "
                  "--out " +
                  (tmp.path / "study").string() + log),
            0)
      << read_text(tmp.path / "log");
  const std::string csv = read_text(tmp.path / "study" / "study.csv");
  EXPECT_NE(csv.find(" step=0.0001 alpha=-0.3,hht-plugin,"), std::string::npos) << csv;
  EXPECT_NE(csv.find(" step=0.0001 alpha=-0.1,hht-plugin,"), std::string::npos) << csv;
}

TEST(Plugins, RegistryRefusesBadDeclaredSettings) {
  auto make = [] { return make_integrator("cvode"); };
  IntegratorCapabilities caps;
  caps.declared = true;
  caps.settings.push_back({"rtol", false, 0.0, -1.0, 1.0, "clash"});
  EXPECT_THROW(register_integrator("own-a", make, "", caps), InputError);
  caps.settings = {{"Bad Key", false, 0.0, -1.0, 1.0, ""}};
  EXPECT_THROW(register_integrator("own-b", make, "", caps), InputError);
  caps.settings = {{"gain", false, 5.0, -1.0, 1.0, "default outside"}};
  EXPECT_THROW(register_integrator("own-c", make, "", caps), InputError);
  caps.settings = {{"gain", true, 2.0, 0.0, 10.0, "a whole number"}};
  register_integrator("own-d", make, "", caps);
  IntegratorSettings s;
  s.name = "own-d";
  EXPECT_EQ(own_setting(s, "gain"), 2.0);
  set_integrator_setting(s, "gain", "7");
  EXPECT_EQ(own_setting(s, "gain"), 7.0);
  EXPECT_EQ(get_integrator_setting(s, "gain"), "7");
  EXPECT_THROW(set_integrator_setting(s, "gain", "7.5"), InputError);
  EXPECT_NE(settings_label(s).find(" gain=7"), std::string::npos) << settings_label(s);
}
