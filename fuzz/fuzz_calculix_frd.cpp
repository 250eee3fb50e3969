// libFuzzer harness: CalculiX result files (io/calculix.h, read_frd_modes).
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_common.h"
#include "io/calculix.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = (evas_fuzz::temp_dir() / "job.frd").string();
  if (evas_fuzz::skipped(data, size)) return 0;
  evas_fuzz::write_file(path, data, size);
  evas_fuzz::expect_only_input_errors([&] { evas::FrdModes m = evas::read_frd_modes(path); });
  return 0;
}
