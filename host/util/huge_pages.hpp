// huge_pages.hpp - a hint that a large block of memory be backed by 2 MiB
// pages (Linux transparent huge pages, madvise mode), so that reads spread
// over it miss the TLB less often.
#pragma once
#include <cstddef>

namespace clrt {

constexpr size_t kHugePageBytes = size_t(2) << 20;

// Whether a scene buffer of `bytes` is worth 2 MiB pages: from 8 MiB (four
// of them); a smaller one is read from few 4 KiB pages' TLB entries anyway.
// The one rule for the hierarchy's buffers and the triangles'
// (render/device_buffers.hpp).
constexpr bool worth_huge_pages(size_t bytes) {
  return bytes >= 4 * kHugePageBytes;
}

// Advises the whole 2 MiB pages inside [p, p + bytes) before they are first
// written. A hint: where the system refuses it or has no such pages, nothing
// changes. Returns the bytes advised.
size_t advise_huge_pages(void* p, size_t bytes);

// Advises them as above and, where that was taken, writes a zero at every
// kHugePageBytes step of the block from every core's thread, so that the
// pages' first touch (a huge page is cleared then: ~1 ms each on this
// project's KVM machine) is shared out instead of falling on the one thread
// that fills the block. For memory about to be overwritten. Returns the
// bytes advised.
size_t place_on_huge_pages(void* p, size_t bytes);

}  // namespace clrt
