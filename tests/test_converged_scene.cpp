// validation/engine/converged.yaml is the validation engine on the converged
// basis (docs/engine-bodies.md, "A converged basis"): engine.yaml line for
// line but for the scene's name and its two body files, which
// validation/engine/run.sh builds from the recipes named here. A change to
// engine.yaml that is not made to converged.yaml fails this test.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace {

const std::string kDir = std::string(EVAS_SOURCE_DIR) + "/validation";

// The lines that are not comments (a line whose first non-blank is '#').
std::vector<std::string> scene_lines(const std::string& path) {
  std::ifstream f(path);
  EXPECT_TRUE(f) << path;
  std::vector<std::string> out;
  for (std::string line; std::getline(f, line);) {
    const auto p = line.find_first_not_of(' ');
    if (p != std::string::npos && line[p] == '#') continue;
    out.push_back(line);
  }
  return out;
}

TEST(ConvergedScene, IsTheEngineOnOtherBodies) {
  const auto engine = scene_lines(kDir + "/engine/engine.yaml");
  const auto conv = scene_lines(kDir + "/engine/converged.yaml");
  ASSERT_EQ(engine.size(), conv.size());
  std::vector<std::string> differ;
  for (std::size_t i = 0; i < engine.size(); ++i)
    if (engine[i] != conv[i]) differ.push_back(conv[i]);
  ASSERT_EQ(differ.size(), 3u);
  EXPECT_EQ(differ[0], "name: engine-converged-case1");
  EXPECT_EQ(differ[1], "    file: ../../validation-out/bodies/crank_conv.h5");
  EXPECT_EQ(differ[2], "    file: ../../validation-out/bodies/block_conv.h5");
  // the recipes run.sh builds them from
  for (const char* recipe : {"crank_conv.yaml", "block_conv.yaml"})
    EXPECT_TRUE(std::filesystem::exists(kDir + "/bodies/convergence/" + recipe)) << recipe;
}

}  // namespace
