// test_options.cpp - the command line's option groups turned into settings
// (no device needed).
#include <catch2/catch.hpp>

#include "app/options.hpp"
#include "clrt_layout.h"
#include "util/error.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_options {

using namespace clrt;

TEST_CASE("local sizes WxH parse, anything else is bad input", "[options]") {
  CHECK(parse_local_size("").x == 0);
  CHECK(parse_local_size("").y == 0);
  const LocalSize s = parse_local_size("8x4");
  CHECK(s.x == 8);
  CHECK(s.y == 4);
  for (const char* bad : {"8", "8x", "x4", "0x4", "8x0", "-8x4", "8x4x2", "8 x4", "8x4 ", "axb", "99999999999x1"}) {
    INFO(bad);
    CHECK_THROWS_AS(parse_local_size(bad), UserError);
  }
}

TEST_CASE("kernel options become a kernel configuration", "[options]") {
  KernelOptions o;
  KernelConfig c = o.config();
  CHECK(c.precision == Precision::Robust);
  CHECK(c.specialize);
  CHECK(c.denorms_zero);
  CHECK(c.use_cache);
  o.precision = "fp64";
  o.no_specialize = o.no_ftz = o.no_cache = true;
  o.lanes = 1;
  c = o.config();
  CHECK(c.precision == Precision::Fp64);
  CHECK_FALSE(c.specialize);
  CHECK_FALSE(c.denorms_zero);
  CHECK_FALSE(c.use_cache);
  o.precision = "double";
  CHECK_THROWS_AS(o.config(), UserError);
  o.precision = "robust";
  o.lanes = 3;
  CHECK_THROWS_AS(o.config(), UserError);
}

TEST_CASE("render options become render settings and are checked", "[options]") {
  RenderOptions o;
  o.launch.local_size = "16x2";
  o.launch.band_rows = 7;
  o.launch.max_launch_ms = 40;
  const RenderSettings s = o.settings();
  CHECK(s.local.x == 16);
  CHECK(s.local.y == 2);
  CHECK(s.tiles.band_rows == 7);
  CHECK(s.tiles.max_launch_ms == 40);
  o.validate();
  o.image.width = 0;
  CHECK_THROWS_AS(o.validate(), UserError);
  o.image.width = kMaxImageEdge + 1;
  CHECK_THROWS_AS(o.validate(), UserError);
  o.image.width = 600;
  o.engine = "vulkan";
  CHECK_THROWS_AS(o.validate(), UserError);
  o.engine = "reference";
  o.launch.band_rows = -1;
  CHECK_THROWS_AS(o.validate(), UserError);
}

TEST_CASE("the depth defaults to the scene's", "[options]") {
  ImageOptions o;
  Scene s;
  s.recursion_depth = 4;
  CHECK(o.effective_depth(s) == 4);
  o.depth = 0;
  CHECK(o.effective_depth(s) == 0);
}

TEST_CASE("the spp option: 1 by default, checked against 1 to CLRT_MAX_SPP", "[options][spp]") {
  ImageOptions o;
  CHECK(o.spp == 1);
  o.validate();
  o.spp = CLRT_MAX_SPP;
  o.validate();
  o.spp = 0;
  CHECK_THROWS_AS(o.validate(), UserError);
  o.spp = CLRT_MAX_SPP + 1;
  CHECK_THROWS_AS(o.validate(), UserError);
}

TEST_CASE("sweep depth ranges: A:B or N within [0, CLRT_MAX_DEPTH]", "[options]") {
  int from = -1, to = -1;
  parse_depth_range("0:10", from, to);
  CHECK(from == 0);
  CHECK(to == 10);
  parse_depth_range("3", from, to);
  CHECK(from == 3);
  CHECK(to == 3);
  for (const char* bad : {"", ":", "1:", ":2", "2:1", "-1:2", "1:2:3", "a:b", "1 :2", "0:99999", "99999999999"}) {
    INFO(bad);
    CHECK_THROWS_AS(parse_depth_range(bad, from, to), UserError);
  }
}

}  // namespace test_options
