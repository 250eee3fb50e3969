// `evas modal build` writes where the user asks, never next to its parameter
// file by default: `geometry` is found relative to the parameter file, while
// `output` and `work_dir` are relative to the output folder (--out, default the
// current folder).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "io/fe_pipeline.h"

namespace fs = std::filesystem;
using namespace evas;

TEST(FeParams, OutputAndWorkFolderFollowTheOutputFolder) {
  const fs::path dir = fs::temp_directory_path() / ("evas-fe-params-" + std::to_string(::getpid()));
  fs::create_directories(dir / "params");
  const fs::path yaml = dir / "params" / "cyl.yaml";
  std::ofstream(yaml) << "geometry: cyl.geo\n";
  const PipelineParams p = read_pipeline_params(yaml.string(), (dir / "out").string());
  EXPECT_EQ(p.geometry, (dir / "params" / "cyl.geo").string());
  EXPECT_EQ(p.output, (dir / "out" / "cyl.h5").string());
  EXPECT_EQ(p.work_dir, (dir / "out" / "cyl-fe").string());

  std::ofstream(yaml) << "geometry: cyl.geo\noutput: b.h5\nwork_dir: fe\n";
  const PipelineParams q = read_pipeline_params(yaml.string());
  EXPECT_EQ(q.output, (fs::current_path() / "b.h5").lexically_normal().string());
  EXPECT_EQ(q.work_dir, (fs::current_path() / "fe").lexically_normal().string());
  std::error_code ec;
  fs::remove_all(dir, ec);
}

// `modes.interface_sets` entries name a set or map it to the loads it takes;
// ranking and Ritz keys need sets; bad loads are refused naming the set.
TEST(FeParams, InterfaceLoadsRankingAndRitzBlocks) {
  const fs::path dir = fs::temp_directory_path() / ("evas-fe-iface-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path yaml = dir / "b.yaml";
  std::ofstream(yaml) << "geometry: b.geo\nmodes: {elastic: 4, interface_sets: [a, {set: j, loads: "
                         "[y, z]}, {set: p, loads: [x, moments]}], interface_tolerance: 0.01, "
                         "interface_count: 7, ritz_blocks: 2}\n";
  const PipelineParams p = read_pipeline_params(yaml.string(), dir.string());
  ASSERT_EQ(p.interface_sets, (std::vector<std::string>{"a", "j", "p"}));
  ASSERT_EQ(p.interface.loads.size(), 3u);
  EXPECT_TRUE(p.interface.loads[0].force[0] && p.interface.loads[0].moments);
  EXPECT_FALSE(p.interface.loads[1].force[0]);
  EXPECT_TRUE(p.interface.loads[1].force[1] && p.interface.loads[1].force[2]);
  EXPECT_FALSE(p.interface.loads[1].moments);
  EXPECT_TRUE(p.interface.loads[2].force[0] && p.interface.loads[2].moments);
  EXPECT_FALSE(p.interface.loads[2].force[1]);
  EXPECT_DOUBLE_EQ(p.interface.rank_tolerance, 0.01);
  EXPECT_EQ(p.interface.max_count, 7);
  EXPECT_EQ(p.interface.krylov_blocks, 2);
  // Names only: no masks (every load of every set).
  std::ofstream(yaml) << "geometry: b.geo\nmodes: {interface_sets: [a, b]}\n";
  EXPECT_TRUE(read_pipeline_params(yaml.string(), dir.string()).interface.loads.empty());
  const auto refused = [&](const std::string& modes, const std::string& needle) {
    std::ofstream(yaml) << "geometry: b.geo\nmodes: " << modes << "\n";
    try {
      read_pipeline_params(yaml.string(), dir.string());
      ADD_FAILURE() << modes << " was accepted";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(needle), std::string::npos) << what;
      EXPECT_NE(what.find("b.yaml"), std::string::npos) << what;
    }
  };
  refused("{interface_sets: [{set: j, loads: [r]}]}", "unknown load 'r' for set 'j'");
  refused("{interface_sets: [{set: j, loads: []}]}", "'loads'");
  refused("{interface_sets: [{loads: [y]}]}", "needs 'set'");
  refused("{interface_sets: [j], interface_tolerance: 2}", "interface_tolerance");
  refused("{interface_sets: [j], interface_count: 0}", "interface_count");
  refused("{ritz_blocks: 1}", "need 'interface_sets'");
  std::error_code ec;
  fs::remove_all(dir, ec);
}

// Every recipe of validation/bodies/ (docs/engine-bodies.md) reads: its keys,
// sets and loads are valid, whatever body it builds.
TEST(FeParams, EveryValidationRecipeReads) {
  int n = 0;
  for (const auto& e :
       fs::recursive_directory_iterator(std::string(EVAS_SOURCE_DIR) + "/validation/bodies")) {
    if (e.path().extension() != ".yaml") continue;
    EXPECT_NO_THROW(read_pipeline_params(e.path().string(), fs::temp_directory_path().string()))
        << e.path();
    ++n;
  }
  EXPECT_GE(n, 10);
}
