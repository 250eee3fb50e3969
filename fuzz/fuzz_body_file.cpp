// libFuzzer harness: modal-body files (io/body_file.h, read_body_file).
//
// The input bytes are written to <tmp>/body.h5 and read back. The HDF5 parser
// itself is libhdf5's: a crash whose stack top is inside libhdf5 is recorded as
// "in HDF5, not evas" (scripts/fuzz.sh classifies it) and its input may be put on
// the skip list fuzz/skip/fuzz_body_file.txt. The variable-length strings,
// which evas reads in a child process to survive such faults, are read in this
// one here, so that libFuzzer sees them.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_common.h"
#include "io/body_file.h"
#include "io/isolated_read.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = (evas_fuzz::temp_dir() / "body.h5").string();
  evas::h5::set_read_isolation(false);  // libhdf5's faults in sight of libFuzzer (isolated_read.h)
  if (evas_fuzz::skipped(data, size)) return 0;
  evas_fuzz::write_file(path, data, size);
  evas_fuzz::expect_only_input_errors([&] { evas::ModalBody b = evas::read_body_file(path); });
  return 0;
}
