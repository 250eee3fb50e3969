// libFuzzer harness: scene files (io/scene.h, parse_scene).
//
// The input is the scene text, parsed as if read from <tmp>/scene/scene.yaml.
// The folder holds no body files, so a scene with `file:` bodies stops with an
// InputError; scenes with `generate:` truss bodies reach markers, elements,
// integrator and output. The cylinder-pressure table of the repository is
// placed at scene/data/p.txt and data/cylinder_pressure_3000rpm.txt (the paths
// the test and validation scenes use), so `pressure_file:` can be read.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "fuzz_common.h"
#include "io/scene.h"

namespace {

std::string scene_path() {
  namespace fs = std::filesystem;
  const fs::path dir = evas_fuzz::temp_dir();
  const fs::path src = fs::path(EVAS_SOURCE_DIR) / "validation/data/cylinder_pressure_3000rpm.txt";
  for (const fs::path& dst :
       {dir / "scene/data/p.txt", dir / "data/cylinder_pressure_3000rpm.txt"}) {
    fs::create_directories(dst.parent_path());
    std::error_code ec;
    fs::copy_file(src, dst, fs::copy_options::overwrite_existing, ec);
  }
  return (dir / "scene/scene.yaml").string();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = scene_path();
  if (evas_fuzz::skipped(data, size)) return 0;
  const std::string text(reinterpret_cast<const char*>(data), size);
  evas_fuzz::expect_only_input_errors([&] { evas::Scene s = evas::parse_scene(text, path); });
  return 0;
}
