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

#include "integrators/integrator.h"
#include "integrators/plugin.h"
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
