// test_image.cpp - 8-bit quantization (canvas semantics) of image values.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "image/image.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_image {

using namespace clrt;

TEST_CASE("8-bit values round to nearest, ties to even, like a canvas", "[image]") {
  CHECK(to_u8(0.4) == 0);
  CHECK(to_u8(0.6) == 1);
  // Exact halves go to the even neighbour, not up: 0.5 -> 0, 1.5 -> 2, 2.5 -> 2.
  CHECK(to_u8(0.5) == 0);
  CHECK(to_u8(1.5) == 2);
  CHECK(to_u8(2.5) == 2);
  CHECK(to_u8(254.5) == 254);
  // Just off a tie goes to the nearer value.
  CHECK(to_u8(std::nextafter(2.5, 3.0)) == 3);
  CHECK(to_u8(std::nextafter(2.5, 2.0)) == 2);
}

TEST_CASE("8-bit values clamp to [0, 255], NaN becomes 0", "[image]") {
  CHECK(to_u8(-1e30) == 0);
  CHECK(to_u8(-0.0) == 0);
  CHECK(to_u8(255.4) == 255);
  CHECK(to_u8(1e300) == 255);
  CHECK(to_u8(std::numeric_limits<double>::infinity()) == 255);
  CHECK(to_u8(-std::numeric_limits<double>::infinity()) == 0);
  CHECK(to_u8(std::numeric_limits<double>::quiet_NaN()) == 0);
}

TEST_CASE("an image quantizes channel by channel", "[image]") {
  Image img(2, 1);
  img.rgb = {0.5, 1.5, 300, -2, 127.49, 127.51};
  CHECK(to_u8(img) == std::vector<uint8_t>{0, 2, 255, 0, 127, 128});
}

TEST_CASE("the float files' scale keeps the canvas value of the kernel's float: every tie and beside it",
          "[image]") {
  // to_u8(from_unit(to_unit(c))) == to_u8(c) for every float c (checked once
  // over every float in [0, 256]); here every half level, its neighbours and
  // a sweep. The half levels themselves come back exactly.
  std::vector<float> cs;
  for (int k = -4; k <= 516; ++k) {
    const float c = float(k) / 2;
    cs.insert(cs.end(), {c, std::nextafter(c, -1e9f), std::nextafter(c, 1e9f)});
  }
  for (float c = 0; c < 256; c += 0.0137f) cs.push_back(c);
  for (const float c : cs) {
    INFO(c);
    CHECK(to_u8(from_unit(to_unit(c))) == to_u8(c));
    if (c >= 0 && c <= 256 && c * 2 == std::floor(c * 2)) CHECK(from_unit(to_unit(c)) == c);
  }
  CHECK(to_unit(255.0) == 1.0f);
  CHECK(to_u8(from_unit(std::numeric_limits<float>::quiet_NaN())) == 0);
  // A Unit image quantizes through from_unit.
  Image img(2, 1, FrameContents{PixelFormat::Unit, false});
  img.unit = {to_unit(0.5), to_unit(1.5), 2.0f, -1.0f, to_unit(127.49), to_unit(127.5)};
  CHECK(img.holds(2, 1, FrameContents{PixelFormat::Unit, false}));
  CHECK(img.rgb.empty());
  CHECK(to_u8(img) == std::vector<uint8_t>{0, 2, 255, 0, 127, 128});
}

}  // namespace test_image
