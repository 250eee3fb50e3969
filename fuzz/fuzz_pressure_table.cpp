// libFuzzer harness: cylinder-pressure tables (elements/gas_pressure.h,
// PressureTable::read), then the periodic PCHIP interpolation at a few angles.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "elements/gas_pressure.h"
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = (evas_fuzz::temp_dir() / "pressure.txt").string();
  if (evas_fuzz::skipped(data, size)) return 0;
  evas_fuzz::write_file(path, data, size);
  evas_fuzz::expect_only_input_errors([&] {
    const evas::PressureTable t = evas::PressureTable::read(path);
    volatile double sink = t.max_pressure();
    for (double theta :
         {0.0, 1e-9, 0.5, -0.5, 2.0 * M_PI, 4.0 * M_PI - 1e-12, 4.0 * M_PI, 13.7, -100.0, 1e6}) {
      double slope = 0.0;
      sink = sink + t(theta, &slope) + slope;
    }
    (void)sink;
  });
  return 0;
}
