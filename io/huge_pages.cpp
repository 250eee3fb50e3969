// Large buffers on transparent huge pages (huge_pages.h).
#include "io/huge_pages.h"

#include <sys/mman.h>

#include <cstdint>

namespace evas {

void advise_huge_pages(void* p, std::size_t bytes) {
#ifdef MADV_HUGEPAGE
  constexpr std::uintptr_t kHuge = std::uintptr_t{1} << 21;  // 2 MiB on x86-64
  if (p == nullptr || bytes < 2 * kHuge) return;
  const auto a = reinterpret_cast<std::uintptr_t>(p);
  const std::uintptr_t first = (a + kHuge - 1) & ~(kHuge - 1);
  const std::uintptr_t last = (a + bytes) & ~(kHuge - 1);
  if (last > first) ::madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
#else
  (void)p;
  (void)bytes;
#endif
}

}  // namespace evas
