// test_refraction.cpp - chapter 5's transparency and refraction in the kernel
// (the tree walk of kernels/clrt_ray_tree.h) against the reference (reference.hpp)
// and against images and counts derived by hand: Snell's law at the critical
// angle, the medium around the camera, index 1 as plain transparency, the
// media of nested spheres, the pending-ray slots, and the ray counters.
#include <catch2/catch.hpp>
#include <string>

#include "eval/compare.hpp"
#include "reference/reference.hpp"
#include "render/build_options.hpp"
#include "render/renderer.hpp"
#include "render/scene_buffers.hpp"
#include "scene/scene_json.hpp"
#include "test_util.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_refraction {

using namespace clrt;

namespace {

// 157 x 118: partial work-item blocks at the right and bottom edges.
constexpr int kW = 157, kH = 118;

Image render(const KernelConfig& cfg, const Scene& s, int w, int h, int depth, FrameStats* stats = nullptr) {
  Renderer r = clrt_test::renderer(cfg);
  r.prepare(s, w, h, depth);
  Image img = r.render();
  if (stats) *stats = r.stats();
  return img;
}

// A black, fully transparent sphere of index 1.5 and radius 10 around the
// origin; the camera inside it at (offset, 0, 0), looking along +z; a grey
// background and an ambient light only (so a hit's own colour is black and
// adds nothing). The ray of the pixel at the canvas centre, (0, 0), runs
// along z at distance `offset` from the centre and meets the surface at an
// angle of incidence with sin = offset / 10. Leaving glass (1.5) for air it
// is totally reflected when that exceeds 1 / 1.5, and then stays inside
// forever (a sphere keeps the angle): the pixel is black. Below the critical
// angle it leaves the sphere and the pixel is the background.
Scene glass_around_camera(double offset) {
  return parse_scene(R"({"camera": {"position": [)" + std::to_string(offset) + R"(, 0, 0]},
      "background": [100, 150, 200],
      "spheres": [{"center": [0, 0, 0], "radius": 10, "color": [0, 0, 0], "transparency": 1,
                   "refractive_index": 1.5}],
      "lights": [{"type": "ambient", "intensity": 1}]})",
                     "glass around the camera");
}

// The pixel at the canvas point (0, 0) of a 2 x 2 image: column 1, row 0.
constexpr size_t kCentre = 1;

}  // namespace

TEST_CASE("the reference totally reflects past the critical angle, from the camera's medium", "[reference]") {
  // sin(critical) = 1 / 1.5 = 0.6667: 0.66 leaves the glass, 0.67 does not.
  // Were the camera's medium air (the book's default) instead of the glass
  // around it, both rays would go straight on to the background.
  for (double offset : {6.0, 6.6}) {
    INFO("offset " << offset);
    const Image img = render_reference(glass_around_camera(offset), 2, 2, 5);
    CHECK(img.rgb[kCentre * 3 + 0] > 99);  // the background, seen through the glass (weight 1)
    CHECK(img.rgb[kCentre * 3 + 2] > 199);
  }
  for (double offset : {6.7, 8.0}) {
    INFO("offset " << offset);
    const Image img = render_reference(glass_around_camera(offset), 2, 2, 5);
    for (int c = 0; c < 3; ++c) CHECK(img.rgb[kCentre * 3 + c] == 0);
  }
}

TEST_CASE("the kernel totally reflects past the critical angle, from the camera's medium",
          "[opencl][refraction][slow]") {
  const DeviceInfo dev = clrt_test::test_device();
  for (const auto& [name, cfg] : clrt_test::kernel_builds(dev)) {
    for (double offset : {6.0, 6.6, 6.7, 8.0}) {
      INFO(name << ", offset " << offset);
      const Scene s = glass_around_camera(offset);
      const Image img = render(cfg, s, 2, 2, 5);
      const Image ref = render_reference(s, 2, 2, 5);
      for (int c = 0; c < 3; ++c) CHECK(to_u8(img.rgb[kCentre * 3 + c]) == to_u8(ref.rgb[kCentre * 3 + c]));
    }
  }
}

TEST_CASE("a transparent sphere of index 1 is the book's plain transparency", "[reference][slow]") {
  // Ambient light only (no shadows, no position-dependent shading): a clear
  // sphere of index 1 (transparency 1, reflectivity 0) in front of the others
  // passes each ray on unbent (T = d exactly) with weight 1, so the image is
  // the one without it wherever the rays behind it hit the same sphere: all
  // but the pixels whose ray grazes a silhouette, where the re-started ray's
  // rounding may decide the other way (at most 0.05%, the compare tolerance).
  const std::string opaque = R"({"center": [0, -1, 3], "radius": 1, "color": [255, 0, 0]},
      {"center": [-2, 0, 4], "radius": 1, "color": [0, 255, 0]},
      {"center": [2, 0, 4], "radius": 1, "color": [0, 0, 255]},
      {"center": [0, -5001, 0], "radius": 5000, "color": [255, 255, 0]})";
  const std::string lights = R"("lights": [{"type": "ambient", "intensity": 0.8}])";
  const Scene without = parse_scene(R"({"spheres": [)" + opaque + "], " + lights + "}", "without");
  const Scene with = parse_scene(R"({"spheres": [{"center": [0.3, 0, 2], "radius": 0.7, "color": [9, 9, 9],
      "transparency": 1}, )" + opaque +
                                     "], " + lights + "}",
                                 "with");
  // Through the sphere a ray takes two more levels (in and out).
  const Comparison c = compare_images(render_reference(with, kW, kH, 2), render_reference(without, kW, kH, 0));
  INFO("pixels differ " << c.differ << ", off by > 1 " << c.off_by_gt1);
  CHECK(within_tolerance(c));
  // ... and the kernel gives the same image.
  const DeviceInfo dev = clrt_test::test_device();
  for (const auto& [name, cfg] : clrt_test::kernel_builds(dev)) {
    INFO(name);
    const Comparison k = compare_images(render(cfg, with, kW, kH, 2), render_reference(without, kW, kH, 0));
    CHECK(within_tolerance(k));
  }
}

TEST_CASE("the medium around a sphere is the smallest transparent sphere containing it", "[refraction]") {
  const Scene s = parse_scene(R"({"camera": {"position": [0, 0, 0]}, "spheres": [
      {"center": [0, 0, 10], "radius": 5, "color": [9, 9, 9], "transparency": 0.5, "refractive_index": 1.5},
      {"center": [0, 0, 10], "radius": 3, "color": [9, 9, 9], "transparency": 1, "refractive_index": 1.33},
      {"center": [0, 0, 10], "radius": 1, "color": [9, 9, 9], "refractive_index": 2},
      {"center": [4, 0, 10], "radius": 2, "color": [9, 9, 9], "transparency": 1, "refractive_index": 1.2},
      {"center": [0, 0, 0], "radius": 2, "color": [9, 9, 9], "transparency": 1, "refractive_index": 1.7},
      {"center": [0, 0, 0], "radius": 50, "color": [9, 9, 9], "refractive_index": 3}]})",
                              "nested");
  CHECK(outside_medium(s, 0) == 1.0);   // nothing transparent around it (sphere 5 is opaque)
  CHECK(outside_medium(s, 1) == 1.5);   // inside sphere 0
  CHECK(outside_medium(s, 2) == 1.33);  // the smallest of 0 and 1
  CHECK(outside_medium(s, 3) == 1.0);   // overlaps sphere 0's surface: not nested
  CHECK(outside_medium(s, 5) == 1.0);
  CHECK(camera_medium(s) == 1.7);  // the camera sits in sphere 4
  const SceneData packed = pack_scene(s, Precision::Robust, 8, 8, 3);
  CHECK(packed.spheres[2].outside_index == 1.33f);
  CHECK(packed.spheres[2].refractive_index == 2.0f);
  CHECK(packed.spheres[1].transparency == 1.0f);
  CHECK(packed.params.camera_medium == 1.7f);
}

TEST_CASE("OpenCL matches the reference on the refraction scene", "[opencl][refraction][slow]") {
  // The tolerance of `clrt stability` and `clrt devices --check`
  // (within_tolerance(), eval/compare.hpp): float32 decides grazing rays at
  // silhouettes differently from double; refracted rays bend those
  // differences but do not add new ones (measured on the scene's plane
  // floor: robust 2 of 90 000 pixels differ, by one level, at 300 x 300).
  const Scene s = clrt_test::load("scenes/glass.json");
  const DeviceInfo dev = clrt_test::test_device();
  for (int depth : {1, 2, 6}) {
    const Image ref = render_reference(s, kW, kH, depth);
    for (const auto& [name, cfg] : clrt_test::kernel_builds(dev)) {
      INFO(name << ", depth " << depth);
      const Comparison c = compare_images(render(cfg, s, kW, kH, depth), ref);
      INFO("off by > 1: " << c.off_by_gt1 << ", max " << c.max_abs_8bit << ", hit flips " << c.hit_flips);
      CHECK(within_tolerance(c));
      CHECK(c.nan_inf == 0);
      CHECK(c.nan_inf_reference == 0);
    }
  }
}

TEST_CASE("every lane count walks the same tree", "[opencl][refraction][specialize][slow]") {
  // The walk is in lock step across lanes (masked where a lane has no ray at
  // a tree position): any lane count must give the scalar kernel's image,
  // bit for bit.
  const Scene s = clrt_test::load("scenes/glass.json");
  KernelConfig one;
  one.lanes = 1;
  const Image scalar = render(one, s, kW, kH, 6);
  for (int lanes : clrt_test::every_build() ? std::vector<int>{4, 8, 16} : std::vector<int>{8}) {
    INFO(lanes << " lanes");
    KernelConfig cfg;
    cfg.lanes = lanes;
    clrt_test::require_identical(render(cfg, s, kW, kH, 6), scalar);
  }
}

TEST_CASE("the pending rays get as many slots as the depth needs", "[refraction][specialize]") {
  CHECK(pending_depth_bound(0) == 4);
  CHECK(pending_depth_bound(4) == 4);
  CHECK(pending_depth_bound(5) == 8);
  CHECK(pending_depth_bound(16) == 16);
  CHECK(pending_depth_bound(17) == 32);
  CHECK(pending_depth_bound(CLRT_MAX_DEPTH) == CLRT_MAX_DEPTH);
  const Scene glass = clrt_test::load("scenes/glass.json");
  const Scene demo = clrt_test::load("scenes/cgfs-demo.json");
  KernelConfig cfg;
  auto has = [](const std::string& options, const std::string& option) {
    return options.find(option) != std::string::npos;
  };
  CHECK(has(build_options(cfg, glass, 6, false), "-DCLRT_DEPTH_BOUND=8"));
  CHECK(has(build_options(cfg, glass, 6, false), "-DCLRT_HAS_TRANSPARENT=1"));
  CHECK(has(build_options(cfg, glass, 3, false), "-DCLRT_DEPTH_BOUND=4"));
  // Opaque scenes have no pending rays: no slots, no transparency code.
  CHECK_FALSE(has(build_options(cfg, demo, 6, false), "CLRT_DEPTH_BOUND"));
  CHECK(has(build_options(cfg, demo, 6, false), "-DCLRT_HAS_TRANSPARENT=0"));
  CHECK(has(build_options(cfg, glass, 0, false), "-DCLRT_HAS_TRANSPARENT=0"));  // depth 0 never refracts
}

TEST_CASE("depth deeper than the slot class renders what the reference renders", "[opencl][refraction]") {
  // Depth 9 takes the 16-slot program; the tree is 2^10 rays deep in places.
  const Scene s = clrt_test::load("scenes/glass.json");
  const Comparison c = compare_images(render(KernelConfig{}, s, 61, 47, 9), render_reference(s, 61, 47, 9));
  CHECK(within_tolerance(c));
}

TEST_CASE("ray counters count refracted rays", "[opencl][refraction][rays][slow]") {
  // The camera inside a sphere of radius 100 (test_util.hpp), now half
  // reflective and half transparent with index 1: every hit spawns a
  // reflected ray, which hits the sphere again, and a refracted one, which
  // leaves unbent and misses. Per camera ray: depth + 1 hits (2 shadow rays
  // each), depth reflected and depth refracted rays. The camera sits at the
  // centre, so every ray runs along +-D of its camera ray (z != 0): the far
  // sphere moves off the z axis to (0, 1000, 0), where none of them goes.
  Scene inside = clrt_test::camera_inside_sphere();
  inside.spheres[0].transparency = 0.5;
  inside.spheres[0].reflective = 0.5;
  inside.spheres[1].center = Vec3{0, 1000, 0};
  const int W = 37, H = 11, depth = 3;
  const uint64_t pixels = uint64_t(W) * H;
  const DeviceInfo dev = clrt_test::test_device();
  for (const auto& [name, base] : clrt_test::kernel_builds(dev)) {
    INFO(name);
    KernelConfig cfg = base;
    cfg.count_rays = true;
    FrameStats stats;
    render(cfg, inside, W, H, depth, &stats);
    CHECK(stats.rays.primary == pixels);
    CHECK(stats.rays.reflection == pixels * depth);
    CHECK(stats.rays.refraction == pixels * depth);
    CHECK(stats.rays.shadow == pixels * (depth + 1) * 2);
    CHECK(stats.rays.sphere_tests == 2 * stats.rays.total());
  }
}

}  // namespace test_refraction
