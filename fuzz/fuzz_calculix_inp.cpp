// libFuzzer harness: CalculiX/Abaqus decks (io/calculix.h, read_inp), written to
// <tmp>/inp/deck.inp. *INCLUDE is followed relative to that folder (the deck
// can include itself: the reader's depth limit must stop it). A successful read
// is also written back with write_ccx_mesh.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_common.h"
#include "io/calculix.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = (evas_fuzz::temp_dir() / "inp/deck.inp").string();
  static const std::string out = (evas_fuzz::temp_dir() / "out/mesh.inp").string();
  if (evas_fuzz::skipped(data, size)) return 0;
  evas_fuzz::write_file(path, data, size);
  evas_fuzz::expect_only_input_errors([&] {
    const evas::InpMesh mesh = evas::read_inp(path);
    evas::write_ccx_mesh(out, mesh);
  });
  return 0;
}
