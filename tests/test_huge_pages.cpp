// advise_huge_pages (io/huge_pages.h): what it asks of the kernel for a large
// buffer, and that it leaves buffers it cannot help as they are.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "io/huge_pages.h"

namespace {

// The kernel's transparent huge page mode: "always", "madvise" or "never"
// (empty when the system has none).
std::string thp_mode() {
  std::ifstream f("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string line;
  std::getline(f, line);
  const auto a = line.find('['), b = line.find(']');
  return a == std::string::npos || b == std::string::npos ? "" : line.substr(a + 1, b - a - 1);
}

// The smaps fields of the mapping that holds address p: its size and how much
// of it is on anonymous huge pages [kB]; -1 when not found.
std::pair<long, long> mapping_of(const void* p) {
  std::ifstream f("/proc/self/smaps");
  const auto at = reinterpret_cast<std::uintptr_t>(p);
  std::string line;
  bool in = false;
  long size = -1, huge = -1;
  while (std::getline(f, line)) {
    std::uintptr_t lo = 0, hi = 0;
    char dash = 0;
    std::istringstream head(line);
    if (head >> std::hex >> lo >> dash >> hi && dash == '-') {
      if (in) break;
      in = at >= lo && at < hi;
      continue;
    }
    if (!in) continue;
    if (line.rfind("Size:", 0) == 0) size = std::stol(line.substr(5));
    if (line.rfind("AnonHugePages:", 0) == 0) huge = std::stol(line.substr(14));
  }
  return {size, huge};
}

}  // namespace

// A 16 MiB buffer of its own mapping, advised before its first write: the
// whole 2 MiB pages inside it are huge pages once written (on a kernel in
// "madvise" mode, which backs nothing else that way), and what is written
// reads back.
TEST(HugePages, LargeBufferIsBackedByHugePages) {
  const std::string mode = thp_mode();
  if (mode != "madvise" && mode != "always")
    GTEST_SKIP() << "no transparent huge pages on this system (mode '" << mode << "')";
  const std::size_t bytes = std::size_t{16} << 20;
  char* buf = static_cast<char*>(std::malloc(bytes));  // above the mmap threshold: its own mapping
  ASSERT_NE(buf, nullptr);
  evas::advise_huge_pages(buf, bytes);
  std::memset(buf, 7, bytes);
  const auto [size, huge] = mapping_of(buf + bytes / 2);
  // the advised part is a mapping of its own: the seven whole 2 MiB pages
  // that lie inside any 16 MiB range
  EXPECT_EQ(size, 7L * 2048);
  // at least four of them on huge pages (the kernel may decline some when
  // memory is fragmented)
  EXPECT_GE(huge, 4L * 2048) << "AnonHugePages " << huge << " kB of a " << size << " kB mapping";
  for (std::size_t i = 0; i < bytes; i += 4096) ASSERT_EQ(buf[i], 7);
  std::free(buf);
}

// Small, empty and null buffers are left alone (no call, no fault).
TEST(HugePages, SmallOrNullBuffersAreLeftAlone) {
  evas::advise_huge_pages(nullptr, std::size_t{64} << 20);
  std::vector<double> small(1000, 1.5);
  evas::advise_huge_pages(small.data(), small.size() * sizeof(double));
  evas::advise_huge_pages(small.data(), 0);
  for (double v : small) EXPECT_EQ(v, 1.5);
}
