// huge_pages.hpp - a hint that a large block of memory be backed by 2 MiB
// pages (Linux transparent huge pages, madvise mode), so that reads spread
// over it miss the TLB less often.
#pragma once
#include <cstddef>

namespace clrt {

// Advises the whole 2 MiB pages inside [p, p + bytes) before they are first
// written. A hint: where the system refuses it or has no such pages, nothing
// changes. Returns the bytes advised.
size_t advise_huge_pages(void* p, size_t bytes);

}  // namespace clrt
