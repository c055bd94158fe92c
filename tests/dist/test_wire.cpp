// test_wire.cpp - what travels between ranks: scenes exactly, rows of every
// frame format, and malformed messages refused (dist/wire.hpp).
#include <catch2/catch.hpp>
#include <cstring>

#include "dist/wire.hpp"
#include "flat_scene.hpp"
#include "scene/builtin_scene.hpp"
#include "scene/scene_json.hpp"
#include "test_util.hpp"
#include "util/error.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_wire {

using namespace clrt;
using namespace clrt::dist;

namespace {

// Every field of a scene, compared bit for bit through its JSON text (which
// holds every field with round-trip precision) and the few the text does not.
void require_same_scene(const Scene& a, const Scene& b) {
  CHECK(scene_to_json(a, JsonStyle::Compact) == scene_to_json(b, JsonStyle::Compact));
  CHECK(a.camera.aspect_from_image == b.camera.aspect_from_image);
  REQUIRE(a.spheres.size() == b.spheres.size());
  for (size_t i = 0; i < a.spheres.size(); ++i) {
    CHECK(std::memcmp(&a.spheres[i].center, &b.spheres[i].center, sizeof(Vec3)) == 0);
    CHECK(a.spheres[i].refractive_index == b.spheres[i].refractive_index);
    CHECK(a.spheres[i].transparency == b.spheres[i].transparency);
  }
  REQUIRE(a.lights.size() == b.lights.size());
  for (size_t i = 0; i < a.lights.size(); ++i) {
    CHECK(std::memcmp(&a.lights[i].vec, &b.lights[i].vec, sizeof(Vec3)) == 0);
    CHECK(a.lights[i].scale_exponent == b.lights[i].scale_exponent);  // the shadow range (Light::shadow_t_min)
  }
}

}  // namespace

TEST_CASE("a scene crosses the wire exactly", "[dist]") {
  for (const Scene& s : {builtin_demo_scene(), clrt_test::flat_scene(), clrt_test::load("scenes/glass.json")}) {
    Scene t = decode_scene(encode_scene(s));
    require_same_scene(s, t);
  }
  // Doubles travel as bits, not as text: a value with no short decimal form.
  Scene s = builtin_demo_scene();
  s.spheres[0].radius = 0.1 + 0.2;
  s.camera.aspect_from_image = true;
  s.epsilon = 1e-300;
  const Scene t = decode_scene(encode_scene(s));
  CHECK(t.spheres[0].radius == 0.1 + 0.2);
  CHECK(t.camera.aspect_from_image);
  CHECK(t.epsilon == 1e-300);
}

TEST_CASE("a malformed scene message is refused, never read past its end", "[dist]") {
  const Bytes good = encode_scene(clrt_test::flat_scene());
  // Every truncation: a DeviceError, not a crash (ASan checks the reads).
  for (size_t n = 0; n < good.size(); n += 7) {
    const Bytes cut(good.begin(), good.begin() + long(n));
    CHECK_THROWS_AS(decode_scene(cut), DeviceError);
  }
  Bytes longer = good;
  longer.push_back(0);
  CHECK_THROWS_AS(decode_scene(longer), DeviceError);
  // A count far larger than the message: refused before any allocation.
  Bytes huge = encode_scene(Scene{});
  const size_t spheres_at = huge.size() - 4 * sizeof(uint64_t);  // the four counts end an empty scene
  const uint64_t absurd = uint64_t(1) << 60;
  std::memcpy(huge.data() + spheres_at, &absurd, sizeof absurd);
  CHECK_THROWS_AS(decode_scene(huge), DeviceError);
}

TEST_CASE("rows of every frame format cross the wire into their place", "[dist]") {
  for (FrameContents contents : {FrameContents{PixelFormat::Rgba8, false}, FrameContents{PixelFormat::Float, true}}) {
    Image src(7, 9, contents), dst(7, 9, contents);
    for (size_t i = 0; i < src.rgb.size(); ++i) src.rgb[i] = double(i) * 0.5;
    for (size_t i = 0; i < src.rgba8.size(); ++i) src.rgba8[i] = uint8_t(i * 13);
    for (size_t i = 0; i < src.hit.size(); ++i) src.hit[i] = int32_t(i) - 3, src.shadowed[i] = int32_t(i % 5);
    int y0 = -1, y1 = -1;
    decode_rows(encode_rows(src, 2, 5), dst, y0, y1);
    CHECK(y0 == 2);
    CHECK(y1 == 5);
    decode_rows(encode_rows(src, 0, 2), dst, y0, y1);
    decode_rows(encode_rows(src, 5, 9), dst, y0, y1);
    CHECK(dst.rgb == src.rgb);
    CHECK(dst.rgba8 == src.rgba8);
    CHECK(dst.hit == src.hit);
    CHECK(dst.shadowed == src.shadowed);
    // Rows outside the frame, or a message of the wrong size: refused.
    Image small(7, 4, contents);
    CHECK_THROWS_AS(decode_rows(encode_rows(src, 2, 5), small, y0, y1), DeviceError);
    Bytes cut = encode_rows(src, 2, 5);
    cut.pop_back();
    CHECK_THROWS_AS(decode_rows(cut, dst, y0, y1), DeviceError);
  }
}

}  // namespace test_wire
