// test_program_cache.cpp - the program cache key (no device needed; the
// cache on a device is in tests/render/test_specialize.cpp).
#include <catch2/catch.hpp>

#include "cl/program_cache.hpp"

using namespace clrt;

TEST_CASE("program cache key covers source, options and device", "[cache]") {
  ProgramCacheKey a{"src", "-DX=1", "dev", "drv", "plat"};
  ProgramCacheKey b = a, c = a, d = a;
  b.options = "-DX=2";
  c.source = "src ";
  d.driver = "drv2";
  CHECK(a.hash() != b.hash());
  CHECK(a.hash() != c.hash());
  CHECK(a.hash() != d.hash());
  // Length-prefixed fields: moving text between fields changes the key.
  ProgramCacheKey e{"srcx", "", "dev", "drv", "plat"}, f{"src", "x", "dev", "drv", "plat"};
  CHECK(e.text() != f.text());
}
