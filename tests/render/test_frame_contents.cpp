// test_frame_contents.cpp - the kernel writes only what the caller asks for
// (render/build_options.hpp's KernelConfig::output): its 8-bit RGBA must be
// exactly the host's canvas conversion (to_u8) of its float colour, and
// leaving out the classification must not change the colour.
#include <atomic>
#include <catch2/catch.hpp>
#include <tuple>

#include "image/image.hpp"
#include "render/precision.hpp"
#include "render/renderer.hpp"
#include "util/error.hpp"
#include "test_util.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_frame_contents {

using namespace clrt;

namespace {

const FrameContents kFloatAll{PixelFormat::Float, true};
const FrameContents kFloatOnly{PixelFormat::Float, false};
const FrameContents kRgba8Only{PixelFormat::Rgba8, false};
const FrameContents kRgba8All{PixelFormat::Rgba8, true};

Image render_as(const Scene& scene, int width, int height, int depth, KernelConfig cfg, FrameContents contents,
                TilePolicy tiles = {}, bool map_results = true) {
  cfg.output = contents;
  RenderSettings settings{cfg, tiles, {}};
  settings.map_results = map_results;
  Renderer r({clrt_test::test_device()}, settings);
  r.prepare(scene, width, height, depth);
  return r.render();
}

// Every alpha byte of an 8-bit frame is opaque.
bool opaque(const Image& img) {
  for (size_t p = 0; p < img.pixels(); ++p)
    if (img.rgba8[p * 4 + 3] != 255) return false;
  return true;
}

}  // namespace

TEST_CASE("8-bit kernel output is the host's canvas conversion of the float output, bit for bit",
          "[opencl][output][slow]") {
  const DeviceInfo dev = clrt_test::test_device();
  const Scene demo = clrt_test::load("scenes/cgfs-demo.json");
  const Scene camera = clrt_test::load("scenes/cgfs-camera.json");
  // Every precision and both builds on the demo; the camera scene (a
  // rotated camera, other colours) with the default build. (Each pair is two
  // builds: the suite runs on every device, cold caches included.)
  struct Case {
    const Scene* scene;
    const char* name;
    Precision precision;
    bool specialize;
  };
  std::vector<Case> cases;
  for (Precision precision : all_precisions())
    if (precision != Precision::Fp64 || dev.fp64)
      for (const bool specialize : {true, false}) cases.push_back({&demo, "demo", precision, specialize});
  cases.push_back({&camera, "camera", Precision::Robust, true});
  for (const Case& c : cases) {
    INFO(c.name << ", precision " << precision_name(c.precision) << (c.specialize ? ", specialized" : ", generic"));
    KernelConfig cfg;
    cfg.precision = c.precision;
    cfg.specialize = c.specialize;
    // 97x61: lanes and bands that do not divide the image.
    const Image floats = render_as(*c.scene, 97, 61, 3, cfg, kFloatAll);
    const Image bytes = render_as(*c.scene, 97, 61, 3, cfg, kRgba8Only);
    REQUIRE(bytes.contents == kRgba8Only);
    CHECK(bytes.rgb.empty());
    CHECK(bytes.hit.empty());  // not asked for, not stored
    CHECK(opaque(bytes));
    CHECK(to_u8(bytes) == to_u8(floats));
  }
}

TEST_CASE("the canvas rule in the kernel: clamp, ties to even", "[opencl][output]") {
  // Ambient light 0.5 on colours 1, 3, 5: exactly 0.5, 1.5 and 2.5 (float
  // products of small integers and 0.5 are exact), which round to even:
  // 0, 2, 2. Colour 511 gives 255.5 and clamps to 255; the background is
  // exactly 7.5 -> 8 and 250 stays 250.
  const Scene s = parse_scene(R"({
    "camera": {"position": [0, 0, 0], "viewport": [1, 1], "projection_plane_d": 1},
    "background": [7.5, 250, 0],
    "spheres": [
      {"center": [-0.5, 0, 3], "radius": 0.4, "color": [1, 3, 5], "specular": -1},
      {"center": [0.5, 0, 3], "radius": 0.4, "color": [255, 255, 255], "specular": -1}
    ],
    "lights": [{"type": "ambient", "intensity": 0.5}]
  })",
                              "canvas");
  const int w = 64, h = 32;
  for (Precision precision : {Precision::Naive, Precision::Robust}) {
    KernelConfig cfg;
    cfg.precision = precision;
    const Image img = render_as(s, w, h, 0, cfg, kRgba8All);
    auto pixel = [&](int x, int y) {
      const uint8_t* p = &img.rgba8[(size_t(y) * w + x) * 4];
      return std::tuple{int(p[0]), int(p[1]), int(p[2]), int(p[3])};
    };
    CHECK(img.hit[size_t(h / 2) * w + w / 4] == 0);
    CHECK(pixel(w / 4, h / 2) == std::tuple{0, 2, 2, 255});            // 0.5, 1.5, 2.5
    CHECK(pixel(3 * w / 4, h / 2) == std::tuple{128, 128, 128, 255});  // 127.5 -> 128 (even)
    CHECK(pixel(0, 0) == std::tuple{8, 250, 0, 255});                  // background 7.5 -> 8
  }
}

TEST_CASE("frame contents: classification only when asked, colour unchanged by it", "[opencl][output]") {
  const Scene demo = clrt_test::load("scenes/cgfs-demo.json");
  const Image all = render_as(demo, 80, 50, 3, KernelConfig{}, kFloatAll);
  const Image colour = render_as(demo, 80, 50, 3, KernelConfig{}, kFloatOnly);
  CHECK(colour.rgb == all.rgb);
  CHECK(colour.hit.empty());
  CHECK(colour.shadowed.empty());
  const Image both = render_as(demo, 80, 50, 3, KernelConfig{}, kRgba8All);
  CHECK(both.hit == all.hit);
  CHECK(both.shadowed == all.shadowed);
  CHECK(to_u8(both) == to_u8(all));
}

TEST_CASE("8-bit frames: mapped and read, in bands, fresh and reused: the same bytes", "[opencl][output]") {
  const Scene demo = clrt_test::load("scenes/cgfs-demo.json");
  const Scene camera = clrt_test::load("scenes/cgfs-camera.json");
  KernelConfig cfg;
  cfg.output = kRgba8Only;
  RenderSettings mapped{cfg, TilePolicy{0, 7}, {}};  // bands of 7 rows
  RenderSettings read = mapped;
  read.map_results = false;
  Renderer a({clrt_test::test_device()}, mapped), b({clrt_test::test_device()}, read);
  Image reused;
  for (const auto& [scene, width, height] : {std::tuple{&camera, 120, 90}, std::tuple{&demo, 64, 40},
                                             std::tuple{&demo, 64, 40}, std::tuple{&camera, 33, 61}}) {
    INFO(width << "x" << height);
    a.prepare(*scene, width, height, 3);
    b.prepare(*scene, width, height, 3);
    const Image want = render_as(*scene, width, height, 3, KernelConfig{}, kFloatAll);
    const Image got_read = b.render();
    a.render_into(reused);
    CHECK(reused.holds(width, height, kRgba8Only));
    CHECK(reused.rgba8 == got_read.rgba8);
    CHECK(to_u8(reused) == to_u8(want));
  }
}

TEST_CASE("Unit frames hold the float frame's colour on the float files' scale, mapped and read",
          "[opencl][output]") {
  const Scene demo = clrt_test::load("scenes/cgfs-demo.json");
  const Image want = render_as(demo, 70, 45, 3, KernelConfig{}, kFloatOnly);
  for (const bool map_results : {true, false}) {
    INFO((map_results ? "mapped" : "read"));
    const Image got =
        render_as(demo, 70, 45, 3, KernelConfig{}, {PixelFormat::Unit, false}, TilePolicy{0, 8}, map_results);
    REQUIRE(got.unit.size() == want.rgb.size());
    CHECK(got.rgb.empty());
    bool same = true;
    for (size_t i = 0; i < want.rgb.size(); ++i) same = same && got.unit[i] == to_unit(want.rgb[i]);
    CHECK(same);
    CHECK(to_u8(got) == to_u8(want));
  }
}

TEST_CASE("a cancel function stops a frame between bands, and the renderer renders again", "[opencl][output]") {
  const Scene demo = clrt_test::load("scenes/cgfs-demo.json");
  KernelConfig cfg;
  cfg.output = kFloatOnly;
  std::atomic<int> asked{0};
  RenderSettings settings{cfg, TilePolicy{0, 4}, {}};  // bands of 4 rows: 15 of them
  settings.cancel = [&asked] { return ++asked > 3; };  // stop before the fourth band
  Renderer r({clrt_test::test_device()}, settings);
  r.prepare(demo, 48, 60, 3);
  Image img;
  CHECK_THROWS_AS(r.render_into(img), Cancelled);
  CHECK(asked == 4);
  CHECK(r.stats().launches == 0);  // (the stats of a frame are those of the last whole one)
  asked = -1000;  // (no stop now)
  r.render_into(img);
  CHECK(r.stats().launches == 15);
  CHECK(img.rgb == render_as(demo, 48, 60, 3, KernelConfig{}, kFloatOnly).rgb);
}

TEST_CASE("a warm frame's first band is sized from the last frame's rate, where no launch limit binds",
          "[opencl][output]") {
  const Scene demo = clrt_test::load("scenes/cgfs-demo.json");
  KernelConfig cfg;
  cfg.output = kFloatOnly;
  RenderSettings settings{cfg, TilePolicy{0, 0}, {}};
  settings.cancel = [] { return false; };  // a frame that may be stopped: bands of about 250 ms
  Renderer r({clrt_test::test_device()}, settings);
  r.prepare(demo, 64, 64, 1);
  r.render();
  CHECK(r.stats().launches >= 2);  // the 16-row calibration band first
  r.render();
  CHECK(r.stats().launches == 1);  // 64 rows take far less than 250 ms
  r.prepare(demo, 64, 64, 1);      // (another prepare: measured again)
  r.render();
  CHECK(r.stats().launches >= 2);
}

TEST_CASE("Image holds exactly the buffers of its contents", "[output]") {
  const Image f(3, 2);
  CHECK(f.contents == kFloatAll);
  CHECK(f.rgb.size() == 18);
  CHECK(f.rgba8.empty());
  CHECK(f.hit.size() == 6);
  CHECK(f.holds(3, 2, kFloatAll));
  CHECK_FALSE(f.holds(3, 2, kRgba8Only));
  CHECK_FALSE(f.holds(2, 3, kFloatAll));
  const Image b(3, 2, kRgba8Only);
  CHECK(b.rgb.empty());
  CHECK(b.rgba8.size() == 24);
  CHECK(b.hit.empty());
  CHECK(b.holds(3, 2, kRgba8Only));
  // to_u8 of an 8-bit frame drops the alpha
  Image c(2, 1, kRgba8Only);
  c.rgba8 = {1, 2, 3, 255, 4, 5, 6, 255};
  CHECK(to_u8(c) == std::vector<uint8_t>{1, 2, 3, 4, 5, 6});
}

TEST_CASE("bands in flight two at a time (read path): the same image and ray counts as mapped bands",
          "[opencl][output]") {
  const Scene demo = clrt_test::load("scenes/cgfs-demo.json");
  KernelConfig cfg;
  cfg.count_rays = true;
  RenderSettings mapped{cfg, TilePolicy{0, 5}, {}};  // bands of 5 rows: 13 of them
  RenderSettings read = mapped;
  read.map_results = false;
  Renderer a({clrt_test::test_device()}, mapped), b({clrt_test::test_device()}, read);
  a.prepare(demo, 70, 63, 3);
  b.prepare(demo, 70, 63, 3);
  const Image want = a.render(), got = b.render();
  CHECK(got.rgb == want.rgb);
  CHECK(got.hit == want.hit);
  CHECK(got.shadowed == want.shadowed);
  CHECK(b.stats().launches == 13);
  CHECK(b.stats().rays.primary == 70u * 63u);
  CHECK(b.stats().rays.total() == a.stats().rays.total());
  CHECK(b.stats().rays.sphere_tests == a.stats().rays.sphere_tests);
}

}  // namespace test_frame_contents
