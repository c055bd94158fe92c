// test_ray_cut.cpp - the ray tree's weight cut-off (scene/ray_tree.hpp,
// docs/reference/limits.md): its value from the scene, the guarantee it states (rays
// it cuts move no colour channel by kRayCutLevels or more), checked on a
// tree enumerated by hand and on the reference's images with and without it,
// the kernel against the reference with it on, and the rays a frame traces
// at depth 64 against the bound, with the ray counters.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "eval/compare.hpp"
#include "reference/reference.hpp"
#include "render/renderer.hpp"
#include "scene/ray_tree.hpp"
#include "scene/scene_json.hpp"
#include "test_util.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_ray_cut {

using namespace clrt;

namespace {

// Two transparent, reflective shells between two mirrors: every hit on a
// shell both reflects (0.3) and refracts ((1 - 0.3) x 0.5 = 0.35), and the
// mirrors (0.9) send the rays that leave back. Light: 0.4 ambient, 0.6
// point, nothing shiny, so no colour passes 255 x 1.0. Without the cut the
// reference takes ~0.7 s at depth 22 on 8 x 8 pixels and doubles with every
// level (58 s at depth 30); with it 0.05 s, at any depth.
Scene shells_in_mirrors(double transparency = 0.5) {
  return parse_scene(R"({"camera": {"position": [0, 0, 0]},
      "background": [30, 40, 70],
      "spheres": [
        {"center": [0, 0, 4], "radius": 1, "color": [200, 200, 255], "reflective": 0.3,
         "transparency": )" + std::to_string(transparency) +
                         R"(, "refractive_index": 1.5},
        {"center": [0, 0, 4], "radius": 2, "color": [200, 255, 200], "reflective": 0.3,
         "transparency": )" + std::to_string(transparency) +
                         R"(, "refractive_index": 1.3}],
      "planes": [
        {"point": [0, 0, 7], "normal": [0, 0, -1], "color": [255, 255, 255], "reflective": 0.9},
        {"point": [0, 0, -0.5], "normal": [0, 0, 1], "color": [255, 255, 255], "reflective": 0.9}],
      "lights": [{"type": "ambient", "intensity": 0.4},
                 {"type": "point", "intensity": 0.6, "position": [0, 1.5, 0.5]}]})",
                     "shells in mirrors");
}

Sampling without_cut() {
  Sampling s;
  s.ray_cut = false;
  return s;
}

// The weights that the cut drops from the full binary tree in which every
// ray hits a surface with shares (a, b), down to `depth` levels: each child
// lighter than `cut` whose parent passed. Counted by level: a ray reached by
// i reflections and j refractions weighs a^i b^j, and C(i + j, i) rays do.
double cut_mass(double a, double b, double cut, int depth, double* traced) {
  double mass = 0;
  *traced = 0;
  for (int level = 0; level <= depth; ++level)
    for (int i = 0; i <= level; ++i) {
      const double w = std::pow(a, i) * std::pow(b, level - i);
      if (w < cut) continue;
      const double rays = std::round(std::exp(std::lgamma(level + 1) - std::lgamma(i + 1) - std::lgamma(level - i + 1)));
      *traced += rays;
      if (level == depth) continue;
      for (double share : {a, b})
        if (w * share < cut) mass += rays * w * share;
    }
  return mass;
}

}  // namespace

TEST_CASE("the weight cut-off follows from the scene's shares and light", "[ray-cut]") {
  const RayCut shells = ray_cut(shells_in_mirrors());
  // alpha solves 0.3^alpha + 0.35^alpha = 1
  CHECK(std::pow(0.3, shells.exponent) + std::pow(0.35, shells.exponent) == Approx(1).epsilon(1e-9));
  CHECK(shells.max_colour == 255);  // 255 x (0.4 + 0.6): nothing shiny
  CHECK(double(shells.min_weight) ==
        Approx(std::pow(kRayCutLevels / 255, 1 / (1 - shells.exponent))).epsilon(1e-6));
  CHECK(double(shells.min_weight) <= std::pow(kRayCutLevels / 255, 1 / (1 - shells.exponent)));  // rounded down

  // Reflection only: one ray per level, so what is cut is one ray lighter
  // than the cut-off: the cut-off is kRayCutLevels / C itself.
  const Scene demo = clrt_test::load("scenes/cgfs-demo.json");
  const RayCut book = ray_cut(demo);
  CHECK(book.exponent == 0);
  CHECK(double(book.min_weight) == Approx(kRayCutLevels / book.max_colour).epsilon(1e-6));
  // At the book's depths no ray is that light (the demo's largest
  // reflectivity, 0.5, to the power 5 is 0.03): its images do not change.
  CHECK(std::pow(0.5, 5) > book.min_weight);

  // A surface that passes all of its light on to two rays (t = 1, 0 < r < 1):
  // nothing can be cut with a guarantee; the tree is bounded by the depth.
  Scene lossless = shells_in_mirrors(1.0);
  const RayCut none = ray_cut(lossless);
  CHECK(none.exponent == 1);
  CHECK(none.min_weight == 0);
  CHECK(worst_rays_per_camera_ray(lossless, 30) == std::ldexp(1.0, 31) - 1);
}

TEST_CASE("the rays the cut drops weigh less than the guarantee allows", "[ray-cut]") {
  // The full tree of a surface that every ray hits, enumerated: the weight
  // dropped is below kRayCutLevels / C, and the rays traced stay within
  // min_weight^-alpha per level. Shares of the scenes above and of the
  // hardening test's shells (0.3 and 0.7 x 0.7 = 0.49).
  for (double t : {0.5, 0.7}) {
    Scene s = shells_in_mirrors(t);
    const RayCut cut = ray_cut(s);
    const double a = 0.3, b = 0.7 * t;
    double traced = 0;
    const double mass = cut_mass(a, b, cut.min_weight, 200, &traced);
    INFO("t " << t << ": alpha " << cut.exponent << ", cut-off " << cut.min_weight << ", dropped " << mass
              << ", traced " << traced);
    CHECK(mass > 0);
    CHECK(mass * cut.max_colour < kRayCutLevels);
    // the whole tree at this depth would be 2^201 - 1 rays
    CHECK(traced <= 201 * std::floor(std::pow(double(cut.min_weight), -cut.exponent)));
  }
}

TEST_CASE("the reference with the cut-off moves no pixel by a level", "[reference][ray-cut]") {
  // Depth 22: the cut drops rays (0.35^15 is below the cut-off of ~9e-8)
  // and the tree without it is still quick. The guarantee is on the
  // unrounded colours: each channel moves by less than kRayCutLevels, down
  // (what is dropped is never negative); so no 8-bit value moves by more
  // than one level.
  const Scene s = shells_in_mirrors();
  const int W = 8, H = 8, depth = 22;
  const Image cut = render_reference(s, W, H, depth);
  const Image full = render_reference(s, W, H, depth, without_cut());
  double largest = 0;
  for (size_t k = 0; k < cut.rgb.size(); ++k) {
    const double moved = full.rgb[k] - cut.rgb[k];
    CHECK(moved >= -1e-9);
    largest = std::max(largest, moved);
  }
  INFO("largest move " << largest << " levels");
  CHECK(largest > 0);  // the cut did drop rays
  CHECK(largest < kRayCutLevels);
  const Comparison c = compare_images(cut, full);
  CHECK(c.max_abs_8bit <= 1);
  CHECK(c.hit_flips == 0);
}

TEST_CASE("the kernel cuts the reference's rays: images agree, the rays stay within the bound",
          "[opencl][ray-cut][rays]") {
  const Scene s = shells_in_mirrors();
  const int W = 8, H = 8;
  const uint64_t pixels = uint64_t(W) * H;
  KernelConfig counting;
  counting.count_rays = true;
  const auto render = [&](int depth, Sampling sampling, FrameStats* stats) {
    Renderer r = clrt_test::renderer(counting);
    r.prepare(s, W, H, depth, sampling);
    Image img = r.render();
    *stats = r.stats();
    return img;
  };
  // Against the reference, with the cut on in both, at the compare
  // tolerance (the cut is decided in float here and in double there: a ray
  // at the edge may be cut in one of them, which moves the pixel by less
  // than kRayCutLevels).
  FrameStats cut22, full22;
  if (ends_long_loops(clrt_test::test_device())) {
    // llvmpipe ends a work-item's loops after 65 535 iterations in all; a
    // pixel's tree here takes more (kernels/clrt_device_status.h): the
    // frame is an error, never a wrong image (test_loop_limit.cpp).
    CHECK_THROWS_WITH(render(22, Sampling{}, &cut22), Catch::Contains("ended the kernel's loops early"));
    return;
  }
  const Image cl = render(22, Sampling{}, &cut22);
  const Comparison c = compare_images(cl, render_reference(s, W, H, 22));
  INFO("off by > 1: " << c.off_by_gt1 << ", max " << c.max_abs_8bit);
  CHECK(within_tolerance(c));
  // The kernel with and without its cut: at most one level apart, and the
  // cut traces fewer rays (measured, shadow rays included: 5.6e5 against
  // 1.2e7).
  const Image cl_full = render(22, without_cut(), &full22);
  CHECK(compare_images(cl, cl_full).max_abs_8bit <= 1);
  INFO("rays traced at depth 22: " << cut22.rays.total() << " with the cut, " << full22.rays.total() << " without");
  CHECK(cut22.rays.total() * 10 < full22.rays.total());

  // Depth 64: 2^65 - 1 rays per camera ray without the cut (no frame would
  // end); with it the frame ends, within the bound of ray_tree.hpp.
  FrameStats deep;
  render(CLRT_MAX_DEPTH, Sampling{}, &deep);
  const uint64_t traced = deep.rays.primary + deep.rays.reflection + deep.rays.refraction;
  const double bound = worst_rays_per_camera_ray(s, CLRT_MAX_DEPTH) * double(pixels);
  INFO("rays traced at depth 64: " << traced << ", bound " << bound);
  CHECK(deep.rays.primary == pixels);
  CHECK(double(traced) <= bound);
  CHECK(bound < 1e-12 * std::ldexp(1.0, CLRT_MAX_DEPTH + 1) * double(pixels));
}

}  // namespace test_ray_cut
