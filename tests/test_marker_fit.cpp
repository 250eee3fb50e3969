// Set markers with `centre: fit`: the centre of the least-squares cylinder
// through the set's nodes (solver/cylinder_fit.h; Kasa, IEEE Trans. Instrum.
// Meas. 25 (1976) 8-14). On the validation engine's crank journals and block
// bores the fitted centres must agree with the axis positions engine.yaml
// gives by hand (the bodies' geometry: validation/bodies/*.yaml), to well
// inside the 30 um film clearance, while the sets' centroids do not.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <regex>
#include <sstream>

#include "io/scene.h"
#include "model/model.h"

using namespace evas;

namespace {

const std::string kEngine = std::string(EVAS_SOURCE_DIR) + "/validation/engine/engine.yaml";

std::string engine_text() {
  std::ifstream in(kEngine);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

TEST(MarkerFit, EngineJournalsAndBoresFitOntoTheirAxes) {
  const std::string given = engine_text();
  // every hand-given centre of a journal or bore marker replaced by `fit`
  const std::string fitted =
      std::regex_replace(given, std::regex(R"(set: (journal|bore)(\d), centre: \[[^\]]*\])"),
                         "set: $1$2, centre: fit");
  ASSERT_NE(fitted, given);
  const Scene a = parse_scene(given, kEngine);
  const Scene b = parse_scene(fitted, kEngine);
  int compared = 0;
  for (const char* prefix : {"j", "b"}) {
    for (int k = 1; k <= 5; ++k) {
      const std::string name = prefix + std::to_string(k);
      const Marker& ma = a.model->markers()[a.model->find_marker(name)];
      const Marker& mb = b.model->markers()[b.model->find_marker(name)];
      // the given centres are points of the axis (x, the crank axis); the fit
      // finds the axis to the accuracy of the FE node positions (radially:
      // measured 4e-16 m), and puts the centre at the nodes' mean axial
      // position, which for a surface set lies within a node spacing of the
      // mid-plane (measured 2e-6 .. 9e-5 m)
      EXPECT_LT(std::hypot(ma.c.y() - mb.c.y(), ma.c.z() - mb.c.z()), 1e-9)
          << name << ": given " << ma.c.transpose() << ", fitted " << mb.c.transpose();
      EXPECT_LT(std::abs(ma.c.x() - mb.c.x()), 2e-4) << name;
      ++compared;
    }
  }
  EXPECT_EQ(compared, 10);
}

TEST(MarkerFit, BadCentreValuesAreNamed) {
  const std::string given = engine_text();
  const std::string bad_word = std::regex_replace(
      given, std::regex(R"(set: journal1, centre: \[[^\]]*\])"), "set: journal1, centre: fitted");
  try {
    parse_scene(bad_word, kEngine);
    FAIL() << "accepted centre: fitted";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("marker 'j1'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("'centre' must be a list of 3 numbers or 'fit'"), std::string::npos) << msg;
  }
  // a node list on one line determines no circle
  const std::string line = std::regex_replace(
      given, std::regex(R"(\{name: j1, body: crank, set: journal1, centre: \[[^\]]*\]\})"),
      "{name: j1, body: crank, nodes: [1, 2], centre: fit}");
  ASSERT_NE(line, given);
  try {
    parse_scene(line, kEngine);
    FAIL() << "accepted a two-node cylinder fit";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("centre: fit"), std::string::npos) << msg;
  }
}
