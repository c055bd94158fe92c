// test_subsampling.cpp - the book's subsampling (--subsample shade |
// interpolate, scene/sampling.hpp): the reference's rules against the exact
// render, the kernel against the reference's subsampled twin across builds,
// primitive kinds and the hierarchy, both output formats, band
// independence, the rays each mode saves, what each gets wrong (a sphere
// narrower than two pixels), and the combinations the options refuse.
#include <catch2/catch.hpp>
#include <iterator>
#include <string>

#include "cli_run.hpp"
#include "eval/compare.hpp"
#include "flat_scene.hpp"
#include "reference/reference.hpp"
#include "render/build_options.hpp"
#include "render/renderer.hpp"
#include "scene/scene_json.hpp"
#include "test_util.hpp"
#include "util/error.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_subsampling {

using namespace clrt;

namespace {

// 157 x 118: an odd width (the last column is even, so every odd column has
// two neighbours) and partial work-item blocks at the right and bottom.
constexpr int kW = 157, kH = 118;
const Sampling kShade(1, -1, Subsample::Shade), kInterpolate(1, -1, Subsample::Interpolate);
const Sampling kModes[] = {kShade, kInterpolate};

Image render(const KernelConfig& cfg, const Scene& s, int w, int h, int depth, Sampling sampling, TilePolicy tiles = {},
             FrameStats* stats = nullptr) {
  Renderer r = clrt_test::renderer(cfg, tiles);
  r.prepare(s, w, h, depth, sampling);
  Image img = r.render();
  if (stats) *stats = r.stats();
  return img;
}

// A 9 x 9 image (camera at the origin, viewport 1, d = 1) and a sphere of
// radius 0.02 at distance ~10 on the ray of pixel (col 5, row 3): it covers
// that pixel's ray only (the rays are 1.1 apart there), and its neighbours in
// columns 4 and 6 see the background.
constexpr int kThinSize = 9, kThinCol = 5, kThinRow = 3;
Scene thin_sphere() {
  return parse_scene(R"({"background": [0, 0, 0], "spheres": [{"center": [1.1111111111, 0, 10], "radius": 0.02,
      "color": [255, 255, 255]}], "lights": [{"type": "ambient", "intensity": 1}]})",
                     "thin");
}

// Pixels whose colour (8-bit, canvas rule) or hit differ.
size_t pixels_differing(const Image& a, const Image& b) {
  size_t n = 0;
  for (size_t p = 0; p < a.hit.size(); ++p) {
    bool differs = a.hit[p] != b.hit[p];
    for (int c = 0; c < 3; ++c) differs = differs || to_u8(a.rgb[p * 3 + c]) != to_u8(b.rgb[p * 3 + c]);
    n += differs;
  }
  return n;
}

}  // namespace

TEST_CASE("subsampling in the reference: even columns exact, odd ones from their neighbours",
          "[reference][subsample]") {
  const Scene s = clrt_test::load("scenes/cgfs-demo.json");
  const Image exact = render_reference(s, kW, kH, 3);
  const Image shade = render_reference(s, kW, kH, 3, kShade);
  const Image interpolate = render_reference(s, kW, kH, 3, kInterpolate);
  size_t assumed = 0, interpolated_changed = 0;
  for (int row = 0; row < kH; ++row)
    for (int col = 0; col < kW; ++col) {
      INFO("row " << row << " col " << col);
      const size_t p = size_t(row) * kW + col;
      const bool neighbours_agree = col % 2 == 1 && col + 1 < kW && exact.hit[p - 1] == exact.hit[p + 1];
      auto same = [&](const Image& img) {
        bool equal = exact.hit[p] == img.hit[p] && exact.shadowed[p] == img.shadowed[p];
        for (int c = 0; c < 3; ++c) equal = equal && exact.rgb[p * 3 + c] == img.rgb[p * 3 + c];
        return equal;
      };
      if (!neighbours_agree) {
        // traced as usual: bit for bit the exact pixel
        REQUIRE(same(shade));
        REQUIRE(same(interpolate));
        continue;
      }
      ++assumed;
      // shade: an assumed pixel whose guess is right is the exact pixel (the
      // same root of the same primitive, the same shading)
      if (exact.hit[p] == exact.hit[p - 1]) REQUIRE(same(shade));
      // interpolate: the mean of the neighbours' canvas colours, their hit,
      // the lights both have blocked
      for (int c = 0; c < 3; ++c)
        REQUIRE(interpolate.rgb[p * 3 + c] ==
                (to_u8(exact.rgb[(p - 1) * 3 + c]) + to_u8(exact.rgb[(p + 1) * 3 + c])) / 2.0);
      REQUIRE(interpolate.hit[p] == exact.hit[p - 1]);
      REQUIRE(interpolate.shadowed[p] == (exact.shadowed[p - 1] & exact.shadowed[p + 1]));
      interpolated_changed += !same(interpolate);
    }
  // Nearly every odd column is assumed on the demo (large regions of one
  // sphere or of the sky), and interpolation changes some of those pixels.
  CHECK(assumed > size_t(kW / 2) * kH * 9 / 10);
  CHECK(interpolated_changed > 0);
}

TEST_CASE("subsampling loses a sphere narrower than two pixels, in both engines", "[reference][opencl][subsample]") {
  // The book's warning made a test: the neighbours of the sphere's one pixel
  // both see the background, so both modes assume the background there.
  const Scene s = thin_sphere();
  const size_t p = size_t(kThinRow) * kThinSize + kThinCol;
  const Image exact = render_reference(s, kThinSize, kThinSize, 0);
  REQUIRE(exact.hit[p] == 0);  // the exact render sees it ...
  REQUIRE(exact.hit[p - 1] == -1);
  REQUIRE(exact.hit[p + 1] == -1);
  for (const Sampling& mode : kModes) {
    INFO(subsample_name(mode.subsample));
    const Image ref = render_reference(s, kThinSize, kThinSize, 0, mode);
    const Image cl = render(KernelConfig{}, s, kThinSize, kThinSize, 0, mode);
    for (const Image* img : {&ref, &cl}) {  // ... subsampling does not
      CHECK(img->hit[p] == -1);
      CHECK(img->rgb[p * 3] == 0);
    }
    CHECK(render(KernelConfig{}, s, kThinSize, kThinSize, 0, {}).hit[p] == 0);
  }
}

TEST_CASE("with a single primitive, shade subsampling is exact", "[reference][opencl][subsample]") {
  // One sphere in the middle of the image: an assumed hit is never wrong
  // (there is nothing else to hit), and two background neighbours never
  // straddle the sphere (it is far wider than two pixels).
  const Scene s = parse_scene(R"({"spheres": [{"center": [0, 0, 3], "radius": 1, "color": [200, 50, 50],
      "specular": 50, "reflective": 0.3}], "lights": [{"type": "ambient", "intensity": 0.3},
      {"type": "point", "intensity": 0.7, "position": [2, 2, 0]}]})",
                              "one");
  const Image exact = render_reference(s, kW, kH, 3);
  clrt_test::require_identical(render_reference(s, kW, kH, 3, kShade), exact);
  // the kernel: no pixel differs from its own exact render
  CHECK(pixels_differing(render(KernelConfig{}, s, kW, kH, 3, kShade), render(KernelConfig{}, s, kW, kH, 3, {})) == 0);
}

TEST_CASE("OpenCL subsampling matches the reference's subsampled twin", "[opencl][subsample][slow]") {
  // The tolerance of `clrt stability` (within_tolerance(), eval/compare.hpp):
  // the engines' camera rays decide grazing hits differently, and a pixel
  // assumed or interpolated from such a neighbour may differ with it; an
  // interpolated pixel is a mean of 8-bit values the engines may round one
  // level apart, so it differs by at most one level where they agree.
  const DeviceInfo dev = clrt_test::test_device();
  struct Case {
    const char* name;
    Scene scene;
  };
  const Case cases[] = {{"demo", clrt_test::load("scenes/cgfs-demo.json")},
                        {"camera", clrt_test::load("scenes/cgfs-camera.json")},
                        {"glass", clrt_test::load("scenes/glass.json")},
                        {"flat", clrt_test::flat_scene()}};
  const auto builds = clrt_test::kernel_builds(dev);
  // Four factors: scene (4), mode (2), build (3 or 4) and hierarchy (2);
  // each cell is a program, a cold build of ~2.6 s on PoCL (all 64 cells took
  // 190 s of the slow tier). The cells run are a pairwise design: every
  // scene with every build, and mode = (scene + build) % 2, hierarchy =
  // (scene / 2 + build) % 2, so every pair of levels of any two factors meets
  // in at least one cell (scene x mode, scene x hierarchy, mode x build,
  // hierarchy x build and mode x hierarchy all take both values as the other
  // index runs). A fault that needs three factors at once to show is what
  // this leaves out; the next test runs every build and hierarchy on the
  // scene with every primitive kind. On the devices after the default one
  // (every_build() off: each program a cold build of 10-40 s) the demo and
  // the flat scene, both modes, the default build without the hierarchy.
  const bool every = clrt_test::every_build();
  for (size_t scene = 0; scene < std::size(cases); ++scene) {
    const Case& k = cases[scene];
    if (!every && std::string(k.name) != "demo" && std::string(k.name) != "flat") continue;
    for (size_t mode = 0; mode < std::size(kModes); ++mode) {
      const Image ref = render_reference(k.scene, kW, kH, 3, kModes[mode]);  // (once per scene and mode)
      for (size_t build = 0; build < builds.size(); ++build) {
        if (every && (scene + build) % 2 != mode) continue;
        const Accel accel = every && (scene / 2 + build) % 2 ? Accel::Bvh : Accel::None;
        const auto& [name, cfg] = builds[build];
        KernelConfig c = cfg;
        c.accel = accel;
        INFO(k.name << ", " << subsample_name(kModes[mode].subsample) << ", " << name << ", " << accel_name(accel));
        const Comparison cmp = compare_images(render(c, k.scene, kW, kH, 3, kModes[mode]), ref);
        INFO("off by > 1: " << cmp.off_by_gt1 << ", max " << cmp.max_abs_8bit << ", hit flips " << cmp.hit_flips);
        CHECK(within_tolerance(cmp));
        CHECK(cmp.nan_inf == 0);
      }
    }
  }
}

TEST_CASE("OpenCL shade subsampling: the even columns are the exact render, bit for bit", "[opencl][subsample][slow]") {
  // Pass 0 finds their hits with the full search; pass 1 tests the primitive
  // found again (the same arithmetic, the same root) and shades it as usual.
  const DeviceInfo dev = clrt_test::test_device();
  const Scene s = clrt_test::flat_scene();  // every primitive kind
  for (const auto& [name, cfg] : clrt_test::kernel_builds(dev))
    for (Accel accel : {Accel::None, Accel::Bvh}) {
      if (accel == Accel::Bvh && (cfg.precision == Precision::Naive || !clrt_test::every_build())) continue;
      KernelConfig c = cfg;
      c.accel = accel;
      INFO(name << ", " << accel_name(accel));
      const Image exact = render(c, s, kW, kH, 3, {}), shade = render(c, s, kW, kH, 3, kShade);
      for (int row = 0; row < kH; ++row)
        for (int col = 0; col < kW; col += 2) {
          const size_t p = size_t(row) * kW + col;
          INFO("row " << row << " col " << col);
          REQUIRE(shade.hit[p] == exact.hit[p]);
          REQUIRE(shade.shadowed[p] == exact.shadowed[p]);
          for (int k = 0; k < 3; ++k) REQUIRE(shade.rgb[p * 3 + k] == exact.rgb[p * 3 + k]);
        }
    }
}

TEST_CASE("interpolated pixels are the same from 8-bit and float frames", "[opencl][subsample][output]") {
  // The mean is taken of the neighbours' canvas colours in both, so an 8-bit
  // frame is the canvas rule applied to the float frame, bit for bit.
  const Scene s = clrt_test::load("scenes/cgfs-demo.json");
  KernelConfig rgba8;
  rgba8.output = {PixelFormat::Rgba8, false};
  const Image bytes = render(rgba8, s, kW, kH, 3, kInterpolate);
  const Image floats = render(KernelConfig{}, s, kW, kH, 3, kInterpolate);
  for (size_t p = 0; p < floats.pixels(); ++p)
    for (int c = 0; c < 3; ++c) {
      INFO("pixel " << p << " channel " << c);
      REQUIRE(bytes.rgba8[p * 4 + c] == to_u8(floats.rgb[p * 3 + c]));
    }
}

TEST_CASE("subsampling does not depend on the bands a frame is cut into", "[opencl][subsample]") {
  // Columns are the image's, and every band holds whole rows: one-row bands
  // give the frame of one band.
  const Scene s = clrt_test::load("scenes/cgfs-demo.json");
  TilePolicy one_row;
  one_row.band_rows = 1;
  for (const Sampling& mode : kModes) {
    INFO(subsample_name(mode.subsample));
    clrt_test::require_identical(render(KernelConfig{}, s, kW, kH, 3, mode, one_row),
                                 render(KernelConfig{}, s, kW, kH, 3, mode));
  }
}

TEST_CASE("what each subsampling mode saves: searches, or whole camera rays", "[opencl][subsample][rays][slow]") {
  const Scene s = clrt_test::load("scenes/cgfs-demo.json");
  KernelConfig cfg;
  cfg.count_rays = true;
  FrameStats exact, shade, interpolate;
  (void)render(cfg, s, kW, kH, 3, {}, {}, &exact);
  (void)render(cfg, s, kW, kH, 3, kShade, {}, &shade);
  (void)render(cfg, s, kW, kH, 3, kInterpolate, {}, &interpolate);
  const uint64_t pixels = uint64_t(kW) * kH;
  // shade: one camera ray per pixel, as without subsampling; an assumed
  // pixel tests 1 sphere (0 for assumed background) instead of 4, and about
  // half the pixels are assumed
  CHECK(shade.rays.primary == pixels);
  CHECK(exact.rays.sphere_tests - shade.rays.sphere_tests > pixels);
  // interpolate: the even columns and the odd pixels whose neighbours
  // disagree trace; on the demo nearly every odd pixel is interpolated
  CHECK(interpolate.rays.primary >= pixels / 2);
  CHECK(interpolate.rays.primary < pixels * 11 / 20);
  CHECK(interpolate.rays.total() < exact.rays.total() * 11 / 20);
}

TEST_CASE("subsampling is refused with supersampling and for unknown modes", "[subsample][cli]") {
  Renderer r = clrt_test::renderer(KernelConfig{});
  const Scene demo = clrt_test::load("scenes/cgfs-demo.json");
  CHECK_THROWS_AS(r.prepare(demo, 64, 64, 3, Sampling(2, -1, Subsample::Shade)), UserError);
  CHECK_THROWS_AS(render_reference(demo, 8, 8, 3, Sampling(2, -1, Subsample::Interpolate)), std::invalid_argument);
  const std::string scene = clrt_test::source_path("scenes/cgfs-demo.json");
  const auto both = clrt_test::run_clrt({"render", scene, "--spp", "2", "--subsample", "shade", "-o", "/dev/null"});
  CHECK(both.status == 2);
  CHECK(both.one_line_error());
  CHECK_THAT(both.err, Catch::Matchers::StartsWith("clrt: error: --subsample needs one sample per pixel"));
  const auto unknown = clrt_test::run_clrt({"render", scene, "--subsample", "half", "-o", "/dev/null"});
  CHECK(unknown.status == 2);
  CHECK(unknown.one_line_error());
}

}  // namespace test_subsampling
