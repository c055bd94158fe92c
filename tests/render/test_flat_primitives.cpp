// test_flat_primitives.cpp - chapter 5's planes and triangles (and OBJ
// meshes) in the kernel against the reference, through the hierarchy and
// without it, and the watertight triangle test: rays through shared edges
// and vertices of a mesh never pass between its faces.
#include <catch2/catch.hpp>
#include <string>

#include "eval/compare.hpp"
#include "flat_scene.hpp"
#include "reference/reference.hpp"
#include "render/build_options.hpp"
#include "render/renderer.hpp"
#include "scene/scene_json.hpp"
#include "test_util.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_flat_primitives {

using namespace clrt;

namespace {

// 157 x 118: partial work-item blocks at the right and bottom edges.
constexpr int kW = 157, kH = 118;

Image render(const KernelConfig& cfg, const Scene& s, int w, int h, int depth, Accel accel = Accel::Auto,
             FrameStats* stats = nullptr) {
  KernelConfig c = cfg;
  c.accel = accel;
  Renderer r = clrt_test::renderer(c);
  r.prepare(s, w, h, depth);
  Image img = r.render();
  if (stats) *stats = r.stats();
  return img;
}

// A wall of triangles at z = 5 in front of the camera (at the origin,
// viewport 1, d = 1) with its vertices and diagonals on the exact points
// where pixel rays meet the wall: a grid of squares `cell` pixels wide, each
// split along its diagonal. A W x H image at canvas point (x, y) hits the
// wall at 5 (x/W, y/H); cell corners are at multiples of `cell`, so the
// rays of every cell-th row and column run through edges, rays on the
// diagonals through the shared diagonal edges, and rays at the corners
// through vertices shared by six triangles. Nothing else is in the scene:
// a ray that slips between two triangles shows the background.
Scene edge_wall(int width, int height, int cell) {
  Scene s;
  s.background = {255, 0, 255};
  s.lights.push_back(Light{LightType::Ambient, 1.0, {}});
  const Material m{{100, 200, 100}, -1, 0};
  const int half_w = width / 2 + cell, half_h = height / 2 + cell;
  auto at = [&](int x, int y) { return Vec3{5.0 * x / width, 5.0 * y / height, 5.0}; };
  for (int x = -half_w; x < half_w; x += cell)
    for (int y = -half_h; y < half_h; y += cell) {
      const Vec3 a = at(x, y), b = at(x + cell, y), c = at(x + cell, y + cell), d = at(x, y + cell);
      s.triangles.push_back(Triangle{a, b, c, m});
      s.triangles.push_back(Triangle{a, c, d, m});
    }
  return s;
}

}  // namespace

TEST_CASE("OpenCL matches the reference on planes and triangles", "[opencl][flat][slow]") {
  // The tolerance of `clrt stability` (within_tolerance(), eval/compare.hpp):
  // float32 decides rays that graze a silhouette or edge differently from
  // double.
  const Scene s = clrt_test::flat_scene();
  const DeviceInfo dev = clrt_test::test_device();
  for (int depth : {0, 1, 3}) {
    const Image ref = render_reference(s, kW, kH, depth);
    for (const auto& [name, cfg] : clrt_test::kernel_builds(dev)) {
      for (Accel accel : {Accel::None, Accel::Bvh}) {
        if (accel == Accel::Bvh && cfg.precision == Precision::Naive) continue;
        INFO(name << ", depth " << depth << ", " << accel_name(accel));
        const Comparison c = compare_images(render(cfg, s, kW, kH, depth, accel), ref);
        INFO("off by > 1: " << c.off_by_gt1 << ", max " << c.max_abs_8bit << ", hit flips " << c.hit_flips);
        CHECK(within_tolerance(c));
        CHECK(c.nan_inf == 0);
        CHECK(c.nan_inf_reference == 0);
      }
    }
  }
}

TEST_CASE("the reference numbers hits over spheres, then planes, then triangles", "[reference][flat]") {
  const Scene s = clrt_test::flat_scene();
  const Image ref = render_reference(s, kW, kH, 0);
  std::vector<int> seen(5, 0);
  for (int32_t id : ref.hit) {
    REQUIRE(id >= -1);
    REQUIRE(id < 5);
    if (id >= 0) ++seen[size_t(id)];
  }
  for (int id = 0; id < 4; ++id) CHECK(seen[size_t(id)] > 0);  // the far plane is hidden here and there only
}

TEST_CASE("specialized and generic kernels agree on planes and triangles", "[opencl][flat][specialize][slow]") {
  const Scene s = clrt_test::flat_scene();
  KernelConfig generic;
  generic.specialize = false;
  for (int lanes : clrt_test::every_build() ? std::vector<int>{1, 4, 8, 16} : std::vector<int>{0}) {
    INFO(lanes << " lanes");
    KernelConfig special;
    special.lanes = lanes;
    clrt_test::require_identical(render(special, s, kW, kH, 3), render(generic, s, kW, kH, 3));
  }
}

TEST_CASE("scenes without planes or triangles compile neither", "[flat][specialize]") {
  const Scene demo = clrt_test::load("scenes/cgfs-demo.json");
  KernelConfig cfg;
  const std::string demo_options = build_options(cfg, demo, 3, false);
  CHECK(demo_options.find("-DCLRT_HAS_PLANES=0") != std::string::npos);
  CHECK(demo_options.find("-DCLRT_HAS_TRIANGLES=0") != std::string::npos);
  const std::string flat_options = build_options(cfg, clrt_test::flat_scene(), 3, false);
  CHECK(flat_options.find("-DCLRT_HAS_PLANES=1") != std::string::npos);
  CHECK(flat_options.find("-DCLRT_HAS_TRIANGLES=1") != std::string::npos);
}

TEST_CASE("no ray passes between the triangles of a mesh, at its edges and vertices",
          "[opencl][flat][reference][slow]") {
  // Every pixel of the wall must show the wall, in the reference and in
  // every kernel build, through the hierarchy and without: a background
  // pixel is a ray that leaked through a shared edge or vertex.
  const int W = 64, H = 64;  // powers of two: the rays meet the wall exactly at 5 x / 64
  for (int cell : {1, 2, 4}) {
    const Scene wall = edge_wall(W, H, cell);
    INFO("cell " << cell << " px, " << wall.triangles.size() << " triangles");
    const Image ref = render_reference(wall, W, H, 0);
    size_t leaks = 0;
    for (int32_t id : ref.hit) leaks += id < 0;
    CHECK(leaks == 0);
    const DeviceInfo dev = clrt_test::test_device();
    for (const auto& [name, cfg] : clrt_test::kernel_builds(dev)) {
      for (Accel accel : {Accel::None, Accel::Bvh}) {
        INFO(name << ", " << accel_name(accel));
        const Image img = render(cfg, wall, W, H, 0, accel);
        size_t kernel_leaks = 0;
        for (int32_t id : img.hit) kernel_leaks += id < 0;
        CHECK(kernel_leaks == 0);
        CHECK(img.rgb[0] == 100);  // the wall's colour, ambient 1
      }
    }
  }
}

TEST_CASE("an OBJ mesh through the hierarchy: the brute-force image and the reference",
          "[opencl][flat][bvh][full-build]") {
  // The shipped mesh scene (two icospheres of 5 120 faces, a plane, a glass
  // sphere): through the hierarchy the image is the brute-force image bit
  // for bit, and both match the reference (small, for the reference's sake:
  // it tests every triangle).
  const Scene s = clrt_test::load("scenes/large/mesh.json");
  REQUIRE(s.triangles.size() == 2 * 5120);
  const DeviceInfo device = clrt_test::test_device();
  if (device.platform_name.find("rusticl") != std::string::npos) {
    // as for the large sphere scenes (test_bvh.cpp): 10 240 triangles tested
    // by every ray take minutes on llvmpipe
    WARN("skipped on " << device.platform_name);
    return;
  }
  KernelConfig cfg;
  FrameStats stats;
  const Image walked = render(cfg, s, 96, 72, 3, Accel::Auto, &stats);
  CHECK(stats.bvh);
  clrt_test::require_identical(walked, render(cfg, s, 96, 72, 3, Accel::None));
  const Comparison c = compare_images(walked, render_reference(s, 96, 72, 3));
  INFO("off by > 1: " << c.off_by_gt1 << ", hit flips " << c.hit_flips);
  CHECK(within_tolerance(c));
}

}  // namespace test_flat_primitives
