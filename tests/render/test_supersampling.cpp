// test_supersampling.cpp - the kernel's supersampling (--spp N, N x N samples
// per pixel, kernels/clrt_samples.h) against the reference's (reference.hpp): the
// same sample rule, the same images within the compare tolerance, spp 1 the
// single-ray render, one program for every N, and rays counted per sample.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>

#include "clrt_layout.h"
#include "edge_scene.hpp"
#include "eval/compare.hpp"
#include "reference/reference.hpp"
#include "render/renderer.hpp"
#include "test_util.hpp"
#include "util/error.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_supersampling {

using namespace clrt;

namespace {

// 157 x 118: partial work-item blocks at the right and bottom edges.
constexpr int kW = 157, kH = 118;

Image render_spp(const KernelConfig& cfg, const Scene& s, int w, int h, int depth, int spp,
                 FrameStats* stats = nullptr) {
  Renderer r = clrt_test::renderer(cfg);
  r.prepare(s, w, h, depth, spp);
  Image img = r.render();
  if (stats) *stats = r.stats();
  return img;
}

// The two builds the tests cover: the default (robust, specialized, 16 lanes)
// and the generic kernel (scalar).
std::vector<std::pair<const char*, KernelConfig>> builds() {
  KernelConfig special;
  special.lanes = 16;
  KernelConfig generic;
  generic.specialize = false;
  return {{"specialized, 16 lanes", special}, {"generic", generic}};
}

}  // namespace

TEST_CASE("spp 1 renders the single-ray image, and one program serves every spp", "[opencl][spp]") {
  const Scene s = clrt_test::load("scenes/cgfs-demo.json");
  for (const auto& [name, cfg] : builds()) {
    INFO(name);
    const Image single = clrt_test::render_cl(s, kW, kH, 3, cfg);  // prepare() without spp
    Renderer r = clrt_test::renderer(cfg);
    r.prepare(s, kW, kH, 3, 3);
    const std::string options = r.options();
    const Image three = r.render();
    r.prepare(s, kW, kH, 3, 1);
    CHECK(r.options() == options);
    CHECK(r.stats().build_ms == 0);  // the spp 3 program, reused
    clrt_test::require_identical(r.render(), single);
    // and back: the same spp 3 image again
    r.prepare(s, kW, kH, 3, 3);
    clrt_test::require_identical(r.render(), three);
  }
}

TEST_CASE("OpenCL at spp 2, 3, 4 matches the reference at the same spp", "[opencl][spp]") {
  // The tolerance of `clrt stability` and `clrt devices --check`
  // (within_tolerance(), eval/compare.hpp): float32 decides grazing rays
  // at silhouettes differently from double; supersampling averages more
  // such rays per pixel but weighs each by 1/N^2.
  for (const char* path : {"scenes/cgfs-demo.json", "scenes/cgfs-camera.json"}) {
    const Scene s = clrt_test::load(path);
    for (int spp : {2, 3, 4}) {
      const Image ref = render_reference(s, kW, kH, s.recursion_depth, spp);
      for (const auto& [name, cfg] : builds()) {
        INFO(path << " spp " << spp << " " << name);
        const Comparison c = compare_images(render_spp(cfg, s, kW, kH, s.recursion_depth, spp), ref);
        INFO("off by > 1: " << c.off_by_gt1 << ", max " << c.max_abs_8bit << ", hit flips " << c.hit_flips);
        CHECK(within_tolerance(c));
        CHECK(c.nan_inf == 0);
        // The classification is sample 0's in both engines: it flips no more
        // often than a pixel's colour may.
        CHECK(100.0 * double(c.hit_flips) / double(c.pixels) <= kTolerancePercentOffByGt1);
      }
    }
  }
}

TEST_CASE("specialized and generic kernels agree at spp 3", "[opencl][spp][specialize]") {
  const Scene s = clrt_test::load("scenes/cgfs-camera.json");
  const auto b = builds();
  clrt_test::require_identical(render_spp(b[0].second, s, kW, kH, 3, 3), render_spp(b[1].second, s, kW, kH, 3, 3));
}

TEST_CASE("a pixel cut by a silhouette is the mean of its samples in the kernel too", "[opencl][spp]") {
  // The same pixel as the reference's test (edge_scene.hpp): the same k of
  // N^2 samples hit, so both engines place the samples by the same rule.
  // The kernel divides in float (within a few ulp in OpenCL C).
  using clrt_test::EdgeScene;
  const Scene s = EdgeScene::scene();
  const int row = EdgeScene::row();
  for (const auto& [name, cfg] : builds())
    for (int n = 1; n <= 5; ++n) {
      INFO(name << " spp " << n);
      REQUIRE(EdgeScene::hits(n) >= 0);
      const Image img = render_spp(cfg, s, EdgeScene::kWidth, EdgeScene::kHeight, 3, n);
      const size_t p = size_t(row) * img.width + EdgeScene::col(EdgeScene::kEdgeX);
      for (int c = 0; c < 3; ++c) {
        const double want = EdgeScene::expected(n, c);
        CHECK(std::fabs(img.rgb[p * 3 + c] - want) <= 1e-5 * std::max(1.0, want));
        CHECK(to_u8(img.rgb[p * 3 + c]) == to_u8(want));
      }
      CHECK(img.hit[p] == 0);
      if (n == 4) {  // the mirrored pixel: sample 0 misses, two columns hit
        const size_t q = size_t(row) * img.width + EdgeScene::col(-EdgeScene::kEdgeX);
        CHECK(img.hit[q] == -1);
        CHECK(img.rgb[q * 3] == Approx(100).epsilon(1e-6));
      }
    }
}

TEST_CASE("ray counters count every sample's rays", "[opencl][spp][rays]") {
  // As in "ray counters match counts derived by hand": the camera inside a
  // sphere of radius 100, so every ray hits; per sample depth + 1 hits,
  // depth reflections and 2 shadow rays per hit.
  const Scene inside = clrt_test::camera_inside_sphere();
  const int W = 37, H = 11, depth = 2, spp = 3;
  const uint64_t samples = uint64_t(W) * H * spp * spp;
  for (const auto& [name, base] : builds()) {
    INFO(name);
    KernelConfig cfg = base;
    cfg.count_rays = true;
    FrameStats stats;
    render_spp(cfg, inside, W, H, depth, spp, &stats);
    CHECK(stats.rays.primary == samples);
    CHECK(stats.rays.reflection == samples * depth);
    CHECK(stats.rays.shadow == samples * (depth + 1) * 2);
    CHECK(stats.rays.sphere_tests == 2 * stats.rays.total());
  }
}

TEST_CASE("the renderer refuses spp outside 1 to CLRT_MAX_SPP", "[opencl][spp]") {
  const Scene s = clrt_test::load("scenes/cgfs-demo.json");
  Renderer r = clrt_test::renderer(KernelConfig{});
  CHECK_THROWS_AS(r.prepare(s, 8, 8, 1, 0), UserError);
  CHECK_THROWS_AS(r.prepare(s, 8, 8, 1, CLRT_MAX_SPP + 1), UserError);
}

TEST_CASE("adaptive supersampling: OpenCL matches the reference's adaptive rule", "[opencl][spp]") {
  // The same tolerance as uniform supersampling: the corners' decision
  // (same primitive, span within T) is taken in float by the kernel and in
  // double by the reference, and may differ where a span is within rounding
  // of T; such a pixel is then the mean of 4 or of N^2 samples.
  for (const char* path : {"scenes/cgfs-demo.json", "scenes/glass.json"}) {
    const Scene s = clrt_test::load(path);
    for (double threshold : {0.0, 4.0, 1e6}) {
      const Sampling sampling(4, threshold);
      const Image ref = render_reference(s, kW, kH, 3, sampling);
      for (const auto& [name, cfg] : builds()) {
        INFO(path << " T " << threshold << " " << name);
        Renderer r = clrt_test::renderer(cfg);
        r.prepare(s, kW, kH, 3, sampling);
        const Comparison c = compare_images(r.render(), ref);
        INFO("off by > 1: " << c.off_by_gt1 << ", max " << c.max_abs_8bit);
        CHECK(within_tolerance(c));
        CHECK(c.nan_inf == 0);
      }
    }
  }
}

TEST_CASE("adaptive supersampling refines the edge pixel and nothing flat", "[opencl][spp]") {
  // The edge pixel of edge_scene.hpp: its corners straddle the sphere's
  // silhouette (different primitives), so it is refined to the N^2 mean at
  // any T; a pixel of the flat background keeps its 4 corners, all equal.
  using clrt_test::EdgeScene;
  const Scene s = EdgeScene::scene();
  const int row = EdgeScene::row();
  for (int n : {3, 4, 5}) {
    if (EdgeScene::hits(n) == 0 || EdgeScene::hits(n) == n * n) continue;  // corners on one side
    const Sampling sampling(n, 1e6);
    const Image ref = render_reference(s, EdgeScene::kWidth, EdgeScene::kHeight, 3, sampling);
    const size_t p = size_t(row) * EdgeScene::kWidth + EdgeScene::col(EdgeScene::kEdgeX);
    for (int c = 0; c < 3; ++c) CHECK(ref.rgb[p * 3 + c] == Approx(EdgeScene::expected(n, c)).epsilon(1e-12));
    for (const auto& [name, cfg] : builds()) {
      INFO(name << " spp " << n);
      Renderer r = clrt_test::renderer(cfg);
      r.prepare(s, EdgeScene::kWidth, EdgeScene::kHeight, 3, sampling);
      const Image img = r.render();
      for (int c = 0; c < 3; ++c) CHECK(to_u8(img.rgb[p * 3 + c]) == to_u8(EdgeScene::expected(n, c)));
      CHECK(img.rgb[2] == Approx(EdgeScene::kBackground[2]));  // a corner pixel: background
    }
  }
}

TEST_CASE("adaptive supersampling traces 4 rays where the corners agree", "[opencl][spp][rays]") {
  // The camera inside one sphere: every corner hits it. With T = 1e6 every
  // pixel keeps its 4 corners; with T = 0 a pixel refines unless its 4
  // corners have the same colour, and then traces N^2.
  const Scene inside = clrt_test::camera_inside_sphere();
  const int W = 37, H = 11, depth = 2, n = 4;
  const uint64_t pixels = uint64_t(W) * H;
  for (const auto& [name, base] : builds()) {
    INFO(name);
    KernelConfig cfg = base;
    cfg.count_rays = true;
    Renderer r = clrt_test::renderer(cfg);
    r.prepare(inside, W, H, depth, Sampling(n, 1e6));
    r.render();
    CHECK(r.stats().rays.primary == 4 * pixels);
    r.prepare(inside, W, H, depth, Sampling(n, 0));
    r.render();
    CHECK(r.stats().rays.primary > 4 * pixels);
    CHECK(r.stats().rays.primary <= uint64_t(n) * n * pixels);
    CHECK((r.stats().rays.primary - 4 * pixels) % (n * n - 4) == 0);  // whole pixels refined
  }
}

}  // namespace test_supersampling
