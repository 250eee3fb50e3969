// Large buffers on transparent huge pages: a body file's mode shapes are
// megabytes, and on a virtual machine each 4 kB page's first touch is a costly
// fault (docs/engine-speed.md, "Start-up").
#pragma once

#include <cstddef>

namespace evas {

/// Asks the kernel to back the whole 2 MiB pages inside [p, p + bytes) with
/// transparent huge pages (madvise MADV_HUGEPAGE), for a buffer not yet
/// written: its first touch then costs one fault per 2 MiB, not per 4 kB.
/// Buffers under 4 MiB are left alone. Best effort: a kernel that refuses
/// (THP off, other systems) changes nothing but the speed.
void advise_huge_pages(void* p, std::size_t bytes);

}  // namespace evas
