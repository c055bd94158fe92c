// test_kernel_features.cpp - scene analysis (KernelFeatures), the -D list
// made from it, the unroll bound and the lane-count rules. Host only: no
// OpenCL device is needed.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "clrt_layout.h"
#include "render/build_options.hpp"
#include "render/kernel_features.hpp"
#include "render/lane_choice.hpp"
#include "render/precision_support.hpp"
#include "scene/scene_json.hpp"
#include "test_util.hpp"
#include "util/error.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_kernel_features {

using namespace clrt;
using Catch::Matchers::Contains;

namespace {

Sphere sphere(double specular, double reflective) {
  Sphere s;
  s.specular = specular;
  s.reflective = reflective;
  return s;
}

Light light(LightType type) {
  Light l;
  l.type = type;
  return l;
}

bool has(const std::vector<std::string>& options, const std::string& option) {
  for (const auto& o : options)
    if (o == option) return true;
  return false;
}

bool has_prefix(const std::vector<std::string>& options, const std::string& prefix) {
  for (const auto& o : options)
    if (o.compare(0, prefix.size(), prefix) == 0) return true;
  return false;
}

DeviceInfo device(const std::string& type, cl_uint native_float_width) {
  DeviceInfo d;
  d.type = type;
  d.native_float_width = native_float_width;
  return d;
}

}  // namespace

TEST_CASE("features of every shipped scene", "[features]") {
  for (const auto& path : clrt_test::shipped_scenes()) {
    INFO(path);
    const Scene s = load_scene(path);
    const KernelFeatures f = kernel_features(s, 3);
    // Every shipped scene of chapters 2-4 is the book's kind: 4 spheres, one
    // light of each type, everything shiny and reflective, nothing
    // transparent; the chapter 5 scene (glass.json) adds transparent spheres
    // and stands them on a plane instead of the book's floor sphere.
    const bool chapter5 = path.find("glass") != std::string::npos;
    CHECK(f.has_transparent == chapter5);
    CHECK(f.traces_refractions() == chapter5);
    CHECK(f.sphere_count == (chapter5 ? 6 : 4));
    CHECK(f.plane_count == (chapter5 ? 1 : 0));
    CHECK(f.light_count == 3);
    CHECK(f.light_types == std::vector<LightType>{LightType::Ambient, LightType::Point, LightType::Directional});
    CHECK(f.has_ambient);
    CHECK(f.has_point);
    CHECK(f.has_directional);
    CHECK(f.has_shadows());
    CHECK(f.has_specular);
    CHECK(f.has_reflective);
    CHECK(f.depth == 3);
    CHECK(f.traces_reflections());
    CHECK(f.unroll_counts);
    CHECK(kernel_features(s, 0).depth == 0);
    CHECK_FALSE(kernel_features(s, 0).traces_reflections());
  }
}

TEST_CASE("features follow the scene's lights and materials", "[features]") {
  Scene s;
  KernelFeatures empty = kernel_features(s, 5);
  CHECK(empty.sphere_count == 0);
  CHECK(empty.light_count == 0);
  CHECK(empty.light_types.empty());
  CHECK_FALSE(empty.has_ambient);
  CHECK_FALSE(empty.has_point);
  CHECK_FALSE(empty.has_directional);
  CHECK_FALSE(empty.has_shadows());
  CHECK_FALSE(empty.has_specular);
  CHECK_FALSE(empty.has_reflective);

  s.spheres = {sphere(-1, 0), sphere(10, 0)};  // -1 = matte
  s.lights = {light(LightType::Directional), light(LightType::Ambient)};
  KernelFeatures f = kernel_features(s, 5);
  CHECK(f.light_types == std::vector<LightType>{LightType::Directional, LightType::Ambient});
  CHECK(f.has_ambient);
  CHECK_FALSE(f.has_point);
  CHECK(f.has_directional);
  CHECK(f.has_shadows());
  CHECK(f.has_specular);
  CHECK_FALSE(f.has_reflective);

  // Only ambient light: no shadow rays.
  s.lights = {light(LightType::Ambient)};
  CHECK_FALSE(kernel_features(s, 5).has_shadows());
  // Only matte spheres: no specular term.
  s.spheres = {sphere(-1, 0)};
  CHECK_FALSE(kernel_features(s, 5).has_specular);
}

TEST_CASE("depth is folded to 0 when nothing reflects", "[features]") {
  Scene s;
  s.spheres = {sphere(10, 0)};
  s.lights = {light(LightType::Point)};
  // Nothing reflects: every depth gives the same features (one program).
  CHECK(kernel_features(s, 0) == kernel_features(s, 7));
  CHECK(kernel_features(s, 7).depth == 0);
  s.spheres.push_back(sphere(10, 0.5));
  CHECK(kernel_features(s, 7).depth == 7);
  CHECK(kernel_features(s, 0) != kernel_features(s, 7));
}

TEST_CASE("features compare as values", "[features]") {
  const Scene demo = clrt_test::load("scenes/cgfs-demo.json");
  CHECK(kernel_features(demo, 3) == kernel_features(demo, 3));
  CHECK_FALSE(kernel_features(demo, 3) != kernel_features(demo, 3));
  CHECK(kernel_features(demo, 2) != kernel_features(demo, 3));
  Scene reordered = demo;
  std::swap(reordered.lights[0], reordered.lights[2]);  // same light kinds, other order
  CHECK(kernel_features(reordered, 3) != kernel_features(demo, 3));
  Scene moved = demo;
  moved.spheres[0].center.x += 1;  // geometry is not a feature
  moved.camera.position.y += 1;
  CHECK(kernel_features(moved, 3) == kernel_features(demo, 3));
}

TEST_CASE("counts are unrolled up to the bound only", "[features][specialize]") {
  static_assert(counts_unrolled(kMaxUnrolledSpheres, kMaxUnrolledLights));
  static_assert(!counts_unrolled(kMaxUnrolledSpheres + 1, 0));
  static_assert(!counts_unrolled(0, kMaxUnrolledLights + 1));
  CHECK(counts_unrolled(0, 0));
  Scene s;
  s.spheres.resize(kMaxUnrolledSpheres);
  s.lights.resize(kMaxUnrolledLights);
  CHECK(kernel_features(s, 3).unroll_counts);
  s.spheres.resize(kMaxUnrolledSpheres + 1);
  CHECK_FALSE(kernel_features(s, 3).unroll_counts);
  s.spheres.resize(1);
  s.lights.resize(kMaxUnrolledLights + 1);
  CHECK_FALSE(kernel_features(s, 3).unroll_counts);
  // Features beyond the bound still hold every light's type.
  CHECK(kernel_features(s, 3).light_types.size() == kMaxUnrolledLights + 1);
}

TEST_CASE("features become one -D list, joined for the build and the cache key", "[features][options]") {
  const Scene demo = clrt_test::load("scenes/cgfs-demo.json");
  const KernelFeatures f = kernel_features(demo, 3);
  KernelConfig cfg;  // robust, specialized, lanes not yet resolved by a device: 8
  std::vector<std::string> expected = {"-cl-std=CL1.2",
                                       "-DCLRT_PRECISION=2",
                                       "-cl-denorms-are-zero",
                                       "-DCLRT_OUT_CLASSES",
                                       "-DCLRT_LANES=8",
                                       "-DCLRT_PACKET_ROWS=2",
                                       "-DCLRT_SPECIALIZED",
                                       "-DCLRT_HAS_AMBIENT=1",
                                       "-DCLRT_HAS_POINT=1",
                                       "-DCLRT_HAS_DIRECTIONAL=1",
                                       "-DCLRT_HAS_SPECULAR=1",
                                       "-DCLRT_HAS_REFLECTIVE=1",
                                       "-DCLRT_HAS_TRANSPARENT=0",
                                       "-DCLRT_HAS_PLANES=0",
                                       "-DCLRT_HAS_TRIANGLES=0",
                                       "-DCLRT_N_SPHERES=4",
                                       "-DCLRT_N_LIGHTS=3",
                                       "-DCLRT_LIGHT_TYPES=0,1,2"};
  expected.push_back("-DCLRT_COMPENSATED_FLAGS=0,0,0,1");  // only the floor is compensated (test_conditioning.cpp)
  CHECK(build_option_list(cfg, f, false) == expected);
  // The old entry point is the composition of the two steps.
  CHECK(build_options(cfg, demo, 3, false) == join_build_options(expected));
  CHECK(join_build_options(expected).find("-cl-std=CL1.2 -DCLRT_PRECISION=2 -cl-denorms-are-zero") == 0);
  CHECK(join_build_options({}).empty());

  SECTION("generic: no scene options, one lane") {
    KernelConfig generic;
    generic.specialize = false;
    CHECK(build_option_list(generic, f, false) == std::vector<std::string>{"-cl-std=CL1.2", "-DCLRT_PRECISION=2",
                                                                           "-cl-denorms-are-zero",
                                                                           "-DCLRT_OUT_CLASSES"});
  }
  SECTION("the frame's contents: 8-bit colour and classes only when asked for") {
    KernelConfig c;
    c.specialize = false;
    c.output = {PixelFormat::Rgba8, false};
    CHECK(build_option_list(c, f, false) ==
          std::vector<std::string>{"-cl-std=CL1.2", "-DCLRT_PRECISION=2", "-cl-denorms-are-zero", "-DCLRT_OUT_RGBA8"});
    c.output = {PixelFormat::Float, false};
    CHECK(build_option_list(c, f, false) ==
          std::vector<std::string>{"-cl-std=CL1.2", "-DCLRT_PRECISION=2", "-cl-denorms-are-zero"});
  }
  SECTION("configuration options, in order, extra options verbatim last") {
    KernelConfig c;
    c.precision = Precision::Fast;
    c.denorms_zero = false;
    c.count_rays = true;
    c.lanes = 16;
    c.specialize = false;
    c.extra_options = "-DCLRT_LIB_POW -DCLRT_SHADOW_ALL_SPHERES";
    CHECK(build_option_list(c, f, false) ==
          std::vector<std::string>{"-cl-std=CL1.2", "-DCLRT_PRECISION=3", "-cl-fast-relaxed-math", "-DCLRT_COUNT_RAYS",
                                   "-DCLRT_OUT_CLASSES", "-DCLRT_LANES=16", "-DCLRT_PACKET_ROWS=4",
                                   "-DCLRT_LIB_POW -DCLRT_SHADOW_ALL_SPHERES"});
  }
  SECTION("every precision passes its CLRT_PRECISION code") {
    static_assert(kernel_code(Precision::Naive) == CLRT_PRECISION_NAIVE);
    static_assert(kernel_code(Precision::Stable) == CLRT_PRECISION_STABLE);
    static_assert(kernel_code(Precision::Robust) == CLRT_PRECISION_ROBUST);
    static_assert(kernel_code(Precision::Fast) == CLRT_PRECISION_FAST);
    static_assert(kernel_code(Precision::Fp64) == CLRT_PRECISION_FP64);
    for (Precision p : all_precisions()) {
      KernelConfig c;
      c.precision = p;
      CHECK(has(build_option_list(c, f, true), "-DCLRT_PRECISION=" + std::to_string(kernel_code(p))));
    }
  }
  SECTION("nothing reflective: depth 0, no reflections") {
    Scene matte = demo;
    for (auto& s : matte.spheres) s.reflective = 0;
    const auto options = build_option_list(cfg, kernel_features(matte, 5), false);
    CHECK(has(options, "-DCLRT_HAS_REFLECTIVE=0"));
  }
  SECTION("depth 0: reflective spheres, but no reflection rays") {
    const auto options = build_option_list(cfg, kernel_features(demo, 0), false);
    CHECK(has(options, "-DCLRT_HAS_REFLECTIVE=0"));
  }
  SECTION("the depth is not compiled in: one program serves every depth that reflects") {
    const auto at1 = build_option_list(cfg, kernel_features(demo, 1), false);
    CHECK(at1 == build_option_list(cfg, kernel_features(demo, 3), false));
    CHECK(at1 == build_option_list(cfg, kernel_features(demo, CLRT_MAX_DEPTH), false));
    for (const auto& option : at1) CHECK(option.rfind("-DCLRT_DEPTH", 0) != 0);
  }
  SECTION("past the unroll bound: the other specializations stay") {
    Scene big = demo;
    big.spheres.resize(kMaxUnrolledSpheres + 1, demo.spheres[0]);
    const auto options = build_option_list(cfg, kernel_features(big, 3), false);
    CHECK(has(options, "-DCLRT_SPECIALIZED"));
    CHECK(has(options, "-DCLRT_HAS_SPECULAR=1"));
    CHECK_FALSE(has_prefix(options, "-DCLRT_N_SPHERES"));
    CHECK_FALSE(has_prefix(options, "-DCLRT_N_LIGHTS"));
    CHECK_FALSE(has_prefix(options, "-DCLRT_LIGHT_TYPES"));
  }
  SECTION("no lights: counts, but no light type list") {
    Scene dark = demo;
    dark.lights.clear();
    const auto options = build_option_list(cfg, kernel_features(dark, 3), false);
    CHECK(has(options, "-DCLRT_N_LIGHTS=0"));
    CHECK_FALSE(has_prefix(options, "-DCLRT_LIGHT_TYPES"));
  }
}

TEST_CASE("fp64 needs cl_khr_fp64, decided in one place", "[features][options]") {
  const KernelFeatures f = kernel_features(clrt_test::load("scenes/cgfs-demo.json"), 3);
  KernelConfig cfg;
  cfg.precision = Precision::Fp64;
  CHECK_FALSE(precision_supported(Precision::Fp64, false));
  CHECK(precision_supported(Precision::Fp64, true));
  for (Precision p : all_precisions())
    if (p != Precision::Fp64) CHECK(precision_supported(p, false));
  CHECK_THROWS_WITH(build_option_list(cfg, f, false), Contains("cl_khr_fp64"));
  CHECK_THROWS_AS(build_options(cfg, Scene{}, 3, false), UserError);
  const auto options = build_option_list(cfg, f, true);
  CHECK(has(options, "-DCLRT_PRECISION=4"));
  CHECK_FALSE(has_prefix(options, "-DCLRT_LANES"));  // fp64 kernels are scalar
}

TEST_CASE("lane counts: explicit, unresolved and per device", "[features][lanes]") {
  KernelConfig cfg;
  SECTION("kernel_lanes") {
    CHECK(kernel_lanes(cfg) == 8);  // specialized float, no device has chosen yet
    for (int lanes : {1, 4, 8, 16}) {
      cfg.lanes = lanes;
      CHECK(kernel_lanes(cfg) == lanes);
    }
    cfg.lanes = 0;
    cfg.specialize = false;
    CHECK(kernel_lanes(cfg) == 1);
    cfg.specialize = true;
    cfg.precision = Precision::Fp64;
    CHECK(kernel_lanes(cfg) == 1);
    cfg.lanes = 1;
    CHECK(kernel_lanes(cfg) == 1);
  }
  SECTION("kernel_lanes rejects other counts, and vectors with fp64") {
    for (int lanes : {-1, 2, 3, 32}) {
      cfg.lanes = lanes;
      CHECK_THROWS_WITH(kernel_lanes(cfg), Contains("--lanes must be 1, 4, 8 or 16"));
      CHECK_THROWS_AS(build_option_list(cfg, KernelFeatures{}, true), UserError);
    }
    cfg.precision = Precision::Fp64;
    cfg.lanes = 4;
    CHECK_THROWS_WITH(kernel_lanes(cfg), Contains("fp64 kernels are scalar"));
  }
  SECTION("default_lanes") {
    CHECK(default_lanes(cfg, device("CPU", 16)) == 16);  // AVX-512
    CHECK(default_lanes(cfg, device("CPU", 8)) == 8);
    CHECK(default_lanes(cfg, device("CPU", 4)) == 8);
    CHECK(default_lanes(cfg, device("GPU", 16)) == 1);  // work-items are SIMD lanes already
    CHECK(default_lanes(cfg, device("ACCELERATOR", 16)) == 1);
    // Mesa's llvmpipe (rusticl) runs work-items as SIMD lanes on a CPU: 8
    // lanes of pixels per work-item compile 10x longer there and run no
    // faster (docs/results/archive.md).
    DeviceInfo llvmpipe = device("CPU", 8);
    llvmpipe.platform_name = "rusticl";
    llvmpipe.name = "llvmpipe (LLVM 15.0.6, 256 bits)";
    CHECK(default_lanes(cfg, llvmpipe) == 1);
    llvmpipe.platform_name = "Portable Computing Language";
    CHECK(default_lanes(cfg, llvmpipe) == 1);  // by its name alone
    KernelConfig generic;
    generic.specialize = false;
    CHECK(default_lanes(generic, device("CPU", 16)) == 1);
    KernelConfig fp64;
    fp64.precision = Precision::Fp64;
    CHECK(default_lanes(fp64, device("CPU", 16)) == 1);
  }
}

TEST_CASE("lane_candidates: blocks of lanes and one ray per work-item where a hierarchy is walked", "[specialize]") {
  DeviceInfo cpu;
  cpu.type = "CPU";
  cpu.native_float_width = 16;
  KernelConfig cfg;  // specialized robust: 16 lanes on this CPU
  REQUIRE(default_lanes(cfg, cpu) == 16);
  CHECK(lane_candidates(cfg, cpu, true) == std::vector<int>{16, 8, 1});  // (4x4 and 4x2 blocks, one ray)
  CHECK(lane_candidates(cfg, cpu, false) == std::vector<int>{16});       // every sphere tested: blocks
  KernelConfig eight = cfg;
  eight.lanes = 8;  // --lanes wins: no probe
  CHECK(lane_candidates(eight, cpu, true) == std::vector<int>{8});
  DeviceInfo narrow = cpu;  // 8-wide floats: blocks of 8 or one ray
  narrow.native_float_width = 8;
  CHECK(lane_candidates(cfg, narrow, true) == std::vector<int>{8, 1});
  DeviceInfo gpu;
  gpu.type = "GPU";
  CHECK(lane_candidates(cfg, gpu, true) == std::vector<int>{1});
}

TEST_CASE("probe_bands: rows spread over the image, each row at most once", "[specialize]") {
  for (int height : {1, 3, 4, 7, 17, 64, 360, 1080, 4321}) {
    const std::vector<RowBand> bands = probe_bands(height);
    REQUIRE(!bands.empty());
    int rows = 0;
    for (size_t i = 0; i < bands.size(); ++i) {
      CHECK(bands[i].y0 >= 0);
      CHECK(bands[i].rows >= 1);
      CHECK(bands[i].y0 + bands[i].rows <= height);
      // whole blocks of lanes, unless clipped by the image's last row
      CHECK(bands[i].y0 % kProbeBlockRows == 0);
      if (bands[i].y0 + bands[i].rows < height) CHECK(bands[i].rows % kProbeBlockRows == 0);
      if (i > 0) CHECK(bands[i].y0 >= bands[i - 1].y0 + bands[i - 1].rows);
      rows += bands[i].rows;
    }
    // about a sixteenth of the rows, never fewer than one 4-row band's worth
    CHECK(rows >= std::min(height, 4));
    if (height >= kProbeBands * kProbeShare * 4) CHECK(rows <= height / kProbeShare + kProbeBands * kProbeBlockRows);
  }
  CHECK(probe_bands(0).empty());
}

TEST_CASE("lane choices are remembered per key", "[specialize]") {
  const std::string key = "test device\nno platform\n-DTEST_ONLY\n42";
  CHECK(recall_lanes(key) == 0);
  remember_lanes(key, 16);
  CHECK(recall_lanes(key) == 16);
  CHECK(recall_lanes(key + "3") == 0);
  remember_lanes(key, 1);
  CHECK(recall_lanes(key) == 1);
}

TEST_CASE("lane_choice_key: another scene, image size or device is another key", "[specialize]") {
  DeviceInfo cpu;
  cpu.name = "cpu";
  SceneData data;
  data.spheres.resize(3);
  const std::string key = lane_choice_key(cpu, "-DX", data, nullptr);
  CHECK(lane_choice_key(cpu, "-DX", data, nullptr) == key);
  CHECK(lane_choice_key(cpu, "-DY", data, nullptr) != key);
  SceneData moved = data;
  moved.spheres[2].radius = 1;
  CHECK(lane_choice_key(cpu, "-DX", moved, nullptr) != key);
  SceneData wider = data;
  wider.params.width = 640;
  CHECK(lane_choice_key(cpu, "-DX", wider, nullptr) != key);
  DeviceInfo other = cpu;
  other.name = "gpu";
  CHECK(lane_choice_key(other, "-DX", data, nullptr) != key);
}

}  // namespace test_kernel_features
