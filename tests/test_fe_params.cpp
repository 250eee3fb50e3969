// `evas modal build` writes where the user asks, never next to its parameter
// file by default: `geometry` is found relative to the parameter file, while
// `output` and `work_dir` are relative to the output folder (--out, default the
// current folder).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

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
