// test_util.hpp - shared helpers for the test suite.
#pragma once
#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "cl/device.hpp"
#include "render/renderer.hpp"
#include "scene/scene_json.hpp"

namespace clrt_test {

inline std::string source_path(const std::string& rel) {
  return std::string(CLRT_SOURCE_DIR) + "/" + rel;
}
inline clrt::Scene load(const std::string& rel) {
  return clrt::load_scene(source_path(rel));
}

// The smallest scene a kernel is specialized for: one diffuse sphere under
// an ambient light. The tests of the program cache build programs cold, with
// PoCL's own cache off (StoringDriver below), several times each: this
// scene's program builds and runs in 1.9 s against the demo's 3.2 s and the
// glass scene's 3.7 s (`POCL_KERNEL_CACHE=0 clrt render ... --width 64
// --height 48`, whole process, PoCL on the 2-core Intel guest).
inline const char* kOneSphereScene =
    R"({"spheres": [{"center": [0, 0, 3], "radius": 1, "color": [200, 50, 50]}],
        "lights": [{"type": "ambient", "intensity": 1}]})";

// The device the OpenCL tests run on: $CLRT_TEST_DEVICE (a --device spec,
// e.g. an index or "rusticl"; tests/every_device.sh sets it to run them on
// every device `clrt devices` lists), else the default device.
inline std::string test_device_spec() {
  const char* spec = std::getenv("CLRT_TEST_DEVICE");
  return spec ? spec : "";
}
inline clrt::DeviceInfo test_device() {
  return clrt::select_device(test_device_spec());
}

// The environment under which clrt stores programs in its own cache on PoCL:
// with PoCL's kernel cache off (clrt stores none where the driver keeps its
// own: cl/program.hpp, driver_caches_programs()). Tests of clrt's cache run
// with it, so that they check its store and load on the default device.
inline const char* kStoringDriverEnv = "POCL_KERNEL_CACHE=0";
// Sets an environment variable for a scope, then restores it.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old, had_ = true;
    ::setenv(name, value, 1);
  }
  ~ScopedEnv() {
    if (had_)
      ::setenv(name_.c_str(), old_.c_str(), 1);
    else
      ::unsetenv(name_.c_str());
  }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  std::string name_, old_;
  bool had_ = false;
};

// kStoringDriverEnv set in this process while it lives (clrt reads it at
// each build).
struct StoringDriver : ScopedEnv {
  StoringDriver() : ScopedEnv("POCL_KERNEL_CACHE", "0") {}
};

// A renderer on the test device. Without a forced lane count it renders with
// the device's default, without the timed probe of lane counts (one program
// per configuration, the same every run; the image does not depend on the
// lanes, and the probe has tests of its own in test_kernel_features.cpp).
inline clrt::Renderer renderer(clrt::KernelConfig kernel, clrt::TilePolicy tiles = {}, clrt::LocalSize local = {}) {
  kernel.probe_lanes = false;
  return clrt::Renderer({test_device()}, clrt::RenderSettings{kernel, tiles, local});
}
// One frame on the test device.
inline clrt::Image render_cl(const clrt::Scene& s, int width, int height, int depth, const clrt::KernelConfig& kernel) {
  clrt::Renderer r = renderer(kernel);
  r.prepare(s, width, height, depth);
  return r.render();
}

// Whether a test runs every build of its matrix (precisions, lane counts,
// generic) or only the default one: tests/every_device.sh sets
// CLRT_TEST_BUILDS=default for the devices after the default one, where each
// program costs a cold build (rusticl's llvmpipe: 10-40 s per program; the
// default device runs every build).
inline bool every_build() {
  const char* builds = std::getenv("CLRT_TEST_BUILDS");
  return !(builds && std::string(builds) == "default");
}

// The kernel builds a test sweeps, by name: the default (robust,
// specialized) at 16 and at 1 lane, the generic kernel, and fp64 where `dev`
// has it; only the default where every_build() is off.
inline std::vector<std::pair<std::string, clrt::KernelConfig>> kernel_builds(const clrt::DeviceInfo& dev) {
  if (!every_build()) return {{"default", clrt::KernelConfig{}}};
  clrt::KernelConfig special16;
  special16.lanes = 16;
  clrt::KernelConfig special1;
  special1.lanes = 1;
  clrt::KernelConfig generic;
  generic.specialize = false;
  std::vector<std::pair<std::string, clrt::KernelConfig>> builds = {
      {"specialized, 16 lanes", special16}, {"specialized, 1 lane", special1}, {"generic", generic}};
  if (dev.fp64) {
    clrt::KernelConfig fp64;
    fp64.precision = clrt::Precision::Fp64;
    builds.push_back({"fp64", fp64});
  }
  return builds;
}

// Every scenes/*.json of the source tree, sorted (`folder` "scenes/large":
// the scenes too large for the suites that render with the reference).
inline std::vector<std::string> shipped_scenes(const std::string& folder = "scenes") {
  std::vector<std::string> out;
  for (auto& e : std::filesystem::directory_iterator(source_path(folder)))
    if (e.path().extension() == ".json") out.push_back(e.path().string());
  std::sort(out.begin(), out.end());
  return out;
}

// The camera inside a reflective sphere of radius 100, so every ray hits it
// (depth + 1 hits per camera ray); a second sphere far away is never hit
// but always tested; an ambient, a point and a directional light (2 shadow
// rays per hit). The ray-counter tests derive their counts from it.
inline clrt::Scene camera_inside_sphere() {
  return clrt::parse_scene(
      R"({"spheres": [{"center": [0, 0, 0], "radius": 100, "color": [9, 9, 9], "reflective": 0.5, "specular": 10},
                      {"center": [0, 0, 1000], "radius": 1, "color": [9, 9, 9]}],
          "lights": [{"type": "ambient", "intensity": 0.2},
                     {"type": "point", "intensity": 0.5, "position": [0, 0, 0]},
                     {"type": "directional", "intensity": 0.3, "direction": [1, 1, 1]}]})",
      "inside");
}

// Byte-identical frames: the same float (exactly representable in the double
// Image), the same hit sphere and the same shadow bits in every pixel.
inline void require_identical(const clrt::Image& a, const clrt::Image& b) {
  REQUIRE(a.width == b.width);
  REQUIRE(a.height == b.height);
  REQUIRE(a.rgb.size() == b.rgb.size());
  REQUIRE(a.hit.size() == b.hit.size());
  size_t rgb_diff = 0, hit_diff = 0, shadow_diff = 0;
  for (size_t i = 0; i < a.rgb.size(); ++i) rgb_diff += a.rgb[i] != b.rgb[i];
  for (size_t i = 0; i < a.hit.size(); ++i) {
    hit_diff += a.hit[i] != b.hit[i];
    shadow_diff += a.shadowed[i] != b.shadowed[i];
  }
  CHECK(rgb_diff == 0);
  CHECK(hit_diff == 0);
  CHECK(shadow_diff == 0);
}

}  // namespace clrt_test
