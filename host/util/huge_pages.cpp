// huge_pages.cpp - madvise(MADV_HUGEPAGE) over the aligned middle of a block.
#include "util/huge_pages.hpp"

#include <algorithm>
#include <cstdint>

#include "util/parallel.hpp"

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace clrt {

size_t advise_huge_pages(void* p, size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  constexpr uintptr_t kHugePage = kHugePageBytes;
  const uintptr_t start = reinterpret_cast<uintptr_t>(p);
  if (p == nullptr || bytes < kHugePage || start > UINTPTR_MAX - bytes) return 0;
  const uintptr_t begin = (start + kHugePage - 1) & ~(kHugePage - 1);
  const uintptr_t end = (start + bytes) & ~(kHugePage - 1);
  if (end <= begin) return 0;
  // (the memory is the caller's and stays valid whatever madvise answers)
  if (madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE) != 0) return 0;
  return size_t(end - begin);
#else
  (void)p;
  (void)bytes;
  return 0;
#endif
}

size_t place_on_huge_pages(void* p, size_t bytes) {
  const size_t advised = advise_huge_pages(p, bytes);
  if (advised == 0) return 0;
  char* c = static_cast<char*>(p);
  const size_t pages = (bytes + kHugePageBytes - 1) / kHugePageBytes;
  parallel_chunks(pages, 1, [c](size_t begin, size_t end) {
    for (size_t page = begin; page < end; ++page) c[page * kHugePageBytes] = 0;
  });
  return advised;
}

}  // namespace clrt
