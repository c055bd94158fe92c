// test_specialize.cpp - the scene-specialized (float8-lane) kernel against the
// generic (scalar, per-pixel) kernel, the program cache, and the kernel's ray
// counters against counts derived by hand.
#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "cl/device.hpp"
#include "cl/program_cache.hpp"
#include "cli_run.hpp"
#include "render/renderer.hpp"
#include "scene/scene_json.hpp"
#include "test_util.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_specialize {

using namespace clrt;

namespace {

Image render_with(const DeviceInfo& dev, KernelConfig cfg, const Scene& s, int w, int h, int depth,
                  RayCounts* counts = nullptr, FrameStats* t = nullptr) {
  Renderer r({dev}, RenderSettings{cfg, {}, {}});
  r.prepare(s, w, h, depth);
  Image img = r.render();
  if (counts) *counts = r.stats().rays;
  if (t) *t = r.stats();
  return img;
}

// 157 x 118: the width is not a multiple of the 8 (or 16) pixels a
// specialized work-item shades, so partial packets are exercised.
constexpr int kW = 157, kH = 118;

}  // namespace

TEST_CASE("specialized and generic kernels give identical images on every scene", "[opencl][specialize]") {
  DeviceInfo dev = clrt_test::test_device();
  KernelConfig generic;
  generic.specialize = false;
  KernelConfig special;  // default: specialized, the device's default lanes (default_lanes())
  for (const auto& path : clrt_test::shipped_scenes()) {
    Scene s = load_scene(path);
    for (int depth : {0, 1, 3}) {
      INFO(path << " depth " << depth);
      clrt_test::require_identical(render_with(dev, special, s, kW, kH, depth),
                                   render_with(dev, generic, s, kW, kH, depth));
    }
  }
}

TEST_CASE("one specialized program serves every depth that reflects", "[opencl][specialize]") {
  // The depth is read at run time: preparing another depth rebuilds nothing
  // and renders what a fresh generic renderer at that depth renders.
  DeviceInfo dev = clrt_test::test_device();
  const Scene s = clrt_test::load("scenes/cgfs-demo.json");
  KernelConfig generic;
  generic.specialize = false;
  Renderer r({dev}, RenderSettings{KernelConfig{}, {}, {}});
  r.prepare(s, kW, kH, 1);
  const std::string options = r.options();
  for (int depth : {4, 2, 1, 7, 3}) {
    INFO("depth " << depth);
    r.prepare(s, kW, kH, depth);
    CHECK(r.options() == options);
    CHECK(r.stats().build_ms == 0);  // the program of the first prepare()
    clrt_test::require_identical(r.render(), render_with(dev, generic, s, kW, kH, depth));
  }
}

TEST_CASE("every precision and lane count gives the generic kernel's image", "[opencl][specialize][slow]") {
  DeviceInfo dev = clrt_test::test_device();
  Scene s = clrt_test::load("scenes/cgfs-demo.json");
  for (Precision p : {Precision::Naive, Precision::Stable, Precision::Robust, Precision::Fp64}) {
    if (p == Precision::Fp64 && !dev.fp64) continue;
    KernelConfig generic;
    generic.precision = p;
    generic.specialize = false;
    Image ref = render_with(dev, generic, s, kW, kH, 2);
    std::vector<int> lanes = p == Precision::Fp64 ? std::vector<int>{1} : std::vector<int>{1, 4, 8, 16};
    for (int l : lanes) {
      INFO(precision_name(p) << " lanes " << l);
      KernelConfig special = generic;
      special.specialize = true;
      special.lanes = l;
      clrt_test::require_identical(render_with(dev, special, s, kW, kH, 2), ref);
    }
  }
}

TEST_CASE("program cache: a second build is a hit and renders the same image", "[opencl][cache]") {
  const clrt_test::StoringDriver storing;
  clrt_test::TempDir dir;
  std::string old = std::getenv("CLRT_CACHE_DIR") ? std::getenv("CLRT_CACHE_DIR") : "";
  ::setenv("CLRT_CACHE_DIR", dir.path().c_str(), 1);
  DeviceInfo dev = clrt_test::test_device();
  const Scene s = parse_scene(clrt_test::kOneSphereScene, "one");  // (five cold builds)
  KernelConfig cfg;
  FrameStats t1, t2, t3, t4;
  Image first = render_with(dev, cfg, s, 64, 48, 2, nullptr, &t1);
  CHECK_FALSE(t1.build_cached);
  REQUIRE(dir.entries().size() == 1);  // one entry, no temporary left behind
  Image second = render_with(dev, cfg, s, 64, 48, 2, nullptr, &t2);
  CHECK(t2.build_cached);
  clrt_test::require_identical(first, second);

  // A corrupted entry (flipped byte in the binary) is detected by its
  // checksum and rebuilt from source; then it is valid again.
  std::string entry = (dir.path() / dir.entries()[0]).string();
  std::string data = clrt_test::slurp(entry);
  data[data.size() - 20] ^= 0x5a;
  std::ofstream(entry, std::ios::binary | std::ios::trunc) << data;
  Image third = render_with(dev, cfg, s, 64, 48, 2, nullptr, &t3);
  CHECK_FALSE(t3.build_cached);
  clrt_test::require_identical(first, third);
  // A truncated entry as well.
  std::ofstream(entry, std::ios::binary | std::ios::trunc) << data.substr(0, 40);
  Image fourth = render_with(dev, cfg, s, 64, 48, 2, nullptr, &t4);
  CHECK_FALSE(t4.build_cached);
  clrt_test::require_identical(first, fourth);

  // --no-cache: neither reads nor writes.
  KernelConfig off = cfg;
  off.use_cache = false;
  FrameStats t5;
  std::filesystem::remove(entry);
  render_with(dev, off, s, 64, 48, 2, nullptr, &t5);
  CHECK_FALSE(t5.build_cached);
  CHECK(dir.entries().empty());
  ::setenv("CLRT_CACHE_DIR", old.c_str(), 1);
}

TEST_CASE("ray counters match counts derived by hand", "[opencl][rays][slow]") {
  DeviceInfo dev = clrt_test::test_device();
  const int W = 37, H = 11;  // 37: not a multiple of the lane count
  const uint64_t px = uint64_t(W) * H;
  auto counts = [&](const Scene& s, int depth, bool specialize) {
    KernelConfig cfg;
    cfg.count_rays = true;
    cfg.specialize = specialize;
    RayCounts c;
    render_with(dev, cfg, s, W, H, depth, &c);
    return c;
  };
  // One sphere behind the camera: no hit, so no shadow or reflection ray.
  Scene miss = parse_scene(R"({"spheres": [{"center": [0, 0, -10], "radius": 1, "color": [9, 9, 9], "reflective": 0.5}],
                               "lights": [{"type": "point", "intensity": 1, "position": [0, 5, 0]}]})",
                           "miss");
  // The camera sits at the centre of a sphere of radius 100, so every primary
  // ray hits it (t = 100/|D| > 1) and every reflection leaves the inner
  // surface towards the inside and hits it again: per pixel depth + 1 hits,
  // depth reflection rays, and one shadow ray per hit for each of the 2
  // non-ambient lights. A second sphere far away is never hit but still
  // tested: 2 tests per ray.
  Scene inside = clrt_test::camera_inside_sphere();
  const int depth = 3;
  for (bool specialize : {true, false}) {
    INFO("specialized " << specialize);
    RayCounts m = counts(miss, 3, specialize);
    CHECK(m.primary == px);
    CHECK(m.shadow == 0);
    CHECK(m.reflection == 0);
    CHECK(m.sphere_tests == px * 1);
    RayCounts c = counts(inside, depth, specialize);
    CHECK(c.primary == px);
    CHECK(c.reflection == px * depth);
    CHECK(c.shadow == px * (depth + 1) * 2);
    CHECK(c.sphere_tests == 2 * (c.primary + c.reflection + c.shadow));
  }
}

}  // namespace test_specialize
