// libFuzzer harness: modal-body files (io/body_file.h, read_body_file).
//
// The input bytes are written to <tmp>/body.h5 and read back. The HDF5 parser
// itself is libhdf5's: a crash whose stack top is inside libhdf5 is recorded as
// "in HDF5, not evas" (scripts/fuzz.sh classifies it) and its input may be put on
// the skip list fuzz/skip/fuzz_body_file.txt.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_common.h"
#include "io/body_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = (evas_fuzz::temp_dir() / "body.h5").string();
  if (evas_fuzz::skipped(data, size)) return 0;
  evas_fuzz::write_file(path, data, size);
  evas_fuzz::expect_only_input_errors([&] { evas::ModalBody b = evas::read_body_file(path); });
  return 0;
}
