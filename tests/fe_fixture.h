// A test suite on one run of the FE pipeline (gmsh -> ccx -> evas), made once
// per test process. ctest runs every case as its own process, in parallel, so
// each process works in its own directory. A pipeline error fails every test
// of the suite (never a skip); missing gmsh or ccx skips, except under CI,
// which installs them (make deps), where it fails.
//
// Use: class Cylinder : public PipelineSuite<Cylinder> { static PipelineParams
// params(); ... };  the tests read result_.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "io/fe_pipeline.h"

namespace evas::test_fe {

inline bool have_fe_programs() {
  return !find_program({"gmsh"}).empty() && !find_program({"ccx", "ccx_2.20"}).empty();
}

template <class Suite>
class PipelineSuite : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    if (!have_fe_programs()) return;
    try {
      PipelineParams p = Suite::params();
      p.work_dir = (std::filesystem::temp_directory_path() /
                    ("evas_test_" + p.name + "_" + std::to_string(::getpid())))
                       .string();
      p.output = p.work_dir + "/" + p.name + ".h5";
      work_dir_ = p.work_dir;
      result_ = new PipelineResult(run_pipeline(p, true));
    } catch (const std::exception& e) {
      error_ = e.what();
    }
  }
  static void TearDownTestSuite() {
    delete result_;
    result_ = nullptr;
    std::error_code ec;  // meshes, decks and matrices: hundreds of MB per run
    if (!work_dir_.empty()) std::filesystem::remove_all(work_dir_, ec);
  }
  void SetUp() override {
    if (!error_.empty()) FAIL() << "FE pipeline failed: " << error_;
    if (!result_) {
      if (std::getenv("CI")) FAIL() << "gmsh or ccx not installed";
      GTEST_SKIP() << "gmsh or ccx not installed";
    }
  }
  static inline PipelineResult* result_ = nullptr;
  static inline std::string error_;
  static inline std::string work_dir_;
};

}  // namespace evas::test_fe
