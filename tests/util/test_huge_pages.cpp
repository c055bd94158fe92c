// test_huge_pages.cpp - advise_huge_pages() (util/huge_pages.hpp) advises
// exactly the whole 2 MiB pages inside a block, none where none fit.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdint>
#include <vector>

#include "util/huge_pages.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_huge_pages {

constexpr size_t kHugePage = clrt::kHugePageBytes;

TEST_CASE("advise_huge_pages advises the whole 2 MiB pages inside a block, no more", "[util]") {
  CHECK(clrt::advise_huge_pages(nullptr, 64 * kHugePage) == 0);
  std::vector<char> small(kHugePage - 1);
  CHECK(clrt::advise_huge_pages(small.data(), small.size()) == 0);  // no whole page can fit

  // 9 MiB from an odd offset: the whole pages are those between the first
  // boundary at or after the start and the last at or before the end.
  std::vector<char> block(9 * (size_t(1) << 20) + 4096);
  char* p = block.data() + 1;
  const size_t bytes = block.size() - 1;
  const uintptr_t start = reinterpret_cast<uintptr_t>(p);
  const uintptr_t begin = (start + kHugePage - 1) / kHugePage * kHugePage;
  const uintptr_t end = (start + bytes) / kHugePage * kHugePage;
  const size_t advised = clrt::advise_huge_pages(p, bytes);
#if defined(__linux__)
  // (0 where the kernel has no transparent huge pages: the hint is refused)
  if (advised != 0) CHECK(advised == size_t(end - begin));
  CHECK(advised % kHugePage == 0);
  CHECK(advised <= 4 * kHugePage);
#else
  CHECK(advised == 0);
#endif
  // place_on_huge_pages() advises the same pages and, where it did, writes a
  // zero at every 2 MiB step from the block's start (the first touches)
  std::fill(block.begin(), block.end(), char(7));
  const size_t placed = clrt::place_on_huge_pages(p, bytes);
  CHECK(placed == advised);
  if (placed != 0) {
    CHECK(p[0] == 0);
    CHECK(p[kHugePage] == 0);
    CHECK(p[1] == 7);
  }
  p[0] = 1;  // the block stays the caller's, readable and writable
  p[bytes - 1] = 2;
  CHECK(block[1] + block[block.size() - 1] == 3);
}

}  // namespace test_huge_pages
