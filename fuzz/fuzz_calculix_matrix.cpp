// libFuzzer harness: CalculiX matrix storage (io/calculix.h, read_inp followed by
// read_matrix_storage).
//
// One input holds four files separated by lines that read exactly "%%evas-part%%":
//     deck (.inp) | stiffness (.sti) | mass (.mas) | dof map (.dof)
// Missing parts are empty files; an empty .sti part is passed as "" (mass only).
// Units are mm-t-s, as in the test data.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz_common.h"
#include "io/calculix.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const auto dir = evas_fuzz::temp_dir() / "mx";
  if (evas_fuzz::skipped(data, size)) return 0;
  std::vector<std::string> parts = evas_fuzz::split_parts(
      std::string(reinterpret_cast<const char*>(data), size), "%%evas-part%%");
  parts.resize(4);
  const std::string inp = (dir / "job.inp").string(), sti = (dir / "job.sti").string(),
                    mas = (dir / "job.mas").string(), dof = (dir / "job.dof").string();
  evas_fuzz::write_file(inp, parts[0]);
  evas_fuzz::write_file(sti, parts[1]);
  evas_fuzz::write_file(mas, parts[2]);
  evas_fuzz::write_file(dof, parts[3]);
  evas_fuzz::expect_only_input_errors([&] {
    const evas::InpMesh mesh = evas::read_inp(inp);
    evas::FeModel fe = evas::read_matrix_storage(mesh, parts[1].empty() ? std::string() : sti, mas,
                                                 dof, evas::unit_system("mm-t-s"));
  });
  return 0;
}
