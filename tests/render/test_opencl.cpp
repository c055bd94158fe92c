// test_opencl.cpp - the OpenCL engine against the double reference on the
// default device (PoCL in CI), and the host/kernel layout agreement.
#include <catch2/catch.hpp>
#include <filesystem>
#include <iterator>

#include "cl/device.hpp"
#include "cl/kernel_source.hpp"
#include "cl/program.hpp"
#include "eval/compare.hpp"
#include "reference/reference.hpp"
#include "render/renderer.hpp"
#include "render/scene_buffers.hpp"
#include "scene/scene_json.hpp"
#include "test_util.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_opencl {

using namespace clrt;

using clrt_test::shipped_scenes;

TEST_CASE("kernel and host agree on the shared layouts", "[opencl][layout]") {
  // Both sides walk CLRT_LAYOUT_FIELDS: the kernel reports (offset, size,
  // struct size) per entry, the host has them in kLayoutFields.
  DeviceInfo dev = clrt_test::test_device();
  cl::Context ctx(dev.device);
  cl::CommandQueue q(ctx, dev.device);
  cl::Program prog = build_program(ctx, dev, load_kernel_source("layout_probe.cl"),
                                 "-cl-std=CL1.2 -DCLRT_BVH_WIDTH=" + std::to_string(CLRT_BVH_WIDTH));
  cl::Kernel k(prog, "layout_probe");
  const size_t n = std::size(kLayoutFields);
  cl::Buffer buf(ctx, CL_MEM_WRITE_ONLY, 3 * n * sizeof(cl_int));
  k.setArg(0, buf);
  q.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(1));
  std::vector<cl_int> got(3 * n);
  q.enqueueReadBuffer(buf, CL_TRUE, 0, got.size() * sizeof(cl_int), got.data());
  for (size_t i = 0; i < n; ++i) {
    const LayoutField& f = kLayoutFields[i];
    INFO(f.type << "." << f.member);
    CHECK(got[3 * i + 0] == f.offset);
    CHECK(got[3 * i + 1] == f.size);
    CHECK(got[3 * i + 2] == f.type_size);
  }
}

TEST_CASE("OpenCL (robust float32) matches the reference on every shipped scene", "[opencl]") {
  // Tolerance: at most 0.01% of pixels (36 of 360,000) may be off by more
  // than one 8-bit level. float32 cannot decide rays that graze a silhouette
  // (|discriminant| below float rounding) the way double does; those are the
  // only pixels allowed to differ by more than rounding. Pixels off by one
  // level come from float rounding of values near .5 and are not limited.
  KernelConfig cfg;  // robust, specialized
  Renderer cl = clrt_test::renderer(cfg);
  for (const auto& path : shipped_scenes()) {
    Scene s = load_scene(path);
    for (int depth : {0, 1, 3, 5}) {
      INFO(path << " depth " << depth);
      Image ref = render_reference(s, 600, 600, depth);
      cl.prepare(s, 600, 600, depth);
      Image img = cl.render();
      Comparison c = compare_images(img, ref);
      CHECK(c.off_by_gt1 <= 36);
      CHECK(c.nan_inf == 0);
      CHECK(c.shadow_flips <= 36);
      // Away from those few pixels the error is rounding: RMSE well below 1 level.
      CHECK(c.rmse_8bit < 0.5);
    }
  }
}

TEST_CASE("OpenCL fp64 reproduces the reference", "[opencl]") {
  DeviceInfo dev = clrt_test::test_device();
  if (!dev.fp64) {
    WARN("device has no cl_khr_fp64; skipped");
    return;
  }
  KernelConfig cfg;
  cfg.precision = Precision::Fp64;
  Renderer cl = clrt_test::renderer(cfg);
  Scene s = clrt_test::load("scenes/cgfs-demo.json");
  for (int depth : {0, 3}) {
    Image ref = render_reference(s, 600, 600, depth);
    cl.prepare(s, 600, 600, depth);
    Comparison c = compare_images(cl.render(), ref);
    // Same formulas in double; scene values pass through float hi/lo pairs
    // (48 significant bits), so only an exact .5 tie could round differently.
    CHECK(c.off_by_gt1 == 0);
    CHECK(c.differ <= 2);
    // Intensities, reflectivities and the output are stored as float: each
    // contributes a relative 2^-24 error, i.e. ~1.5e-5 on a 255 scale; allow
    // a few of them.
    CHECK(c.max_abs_float < 1e-4);
  }
}

TEST_CASE("naive float32 shows the floor acne the robust mode removes", "[opencl]") {
  // Documents the measured fact the robust mode exists for: the book's
  // formulas in float32 self-hit the radius-5000 floor on ~2% of pixels.
  Scene s = clrt_test::load("scenes/cgfs-demo.json");
  Image ref = render_reference(s, 600, 600, 3);
  KernelConfig naive;
  naive.precision = Precision::Naive;
  Comparison c = compare_images(clrt_test::render_cl(s, 600, 600, 3, naive), ref);
  CHECK(c.percent_off_by_gt1() > 0.5);
}

TEST_CASE("tiled rendering equals the single-launch image", "[opencl]") {
  Scene s = clrt_test::load("scenes/cgfs-camera.json");
  Image a = clrt_test::render_cl(s, 203, 157, 3, KernelConfig{});  // odd sizes on purpose
  // 13-row bands: 157 = 12*13 + 1
  Renderer tiled = clrt_test::renderer(KernelConfig{}, TilePolicy{0, 13}, LocalSize{8, 4});
  tiled.prepare(s, 203, 157, 3);
  Image b = tiled.render();
  CHECK(tiled.stats().launches == 13);
  CHECK(a.rgb == b.rgb);
  CHECK(a.hit == b.hit);
  CHECK(a.shadowed == b.shadowed);
}

}  // namespace test_opencl
