// test_loop_limit.cpp - a driver that ends a work-item's loops early
// (Mesa's llvmpipe: 65 535 iterations in all, kernels/clrt_device_status.h)
// makes the frame an error, never a wrong image; where it does not happen,
// the check reports nothing and changes no pixel.
#include <catch2/catch.hpp>
#include <string>

#include "cl/device.hpp"
#include "eval/compare.hpp"
#include "reference/reference.hpp"
#include "render/renderer.hpp"
#include "scene/scene_json.hpp"
#include "cli_run.hpp"
#include "test_util.hpp"
#include "util/error.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_loop_limit {

using namespace clrt;
using clrt_test::RunResult;
using clrt_test::run_clrt;
using clrt_test::TempDir;

namespace {

// Two transparent, reflective shells between two mirrors (as in
// test_ray_cut.cpp): without the weight cut-off a pixel's tree at depth 22
// is ~10^5 rays, each a loop over the primitives and the lights: far past
// llvmpipe's 65 535 iterations. At depth 8 it is a few hundred rays (within
// it: measured, llvmpipe's image equals PoCL's there up to depth 12).
const char* kShells = R"({"camera": {"position": [0, 0, 0]}, "background": [30, 40, 70],
  "spheres": [
    {"center": [0, 0, 4], "radius": 1, "color": [200, 200, 255], "reflective": 0.3, "transparency": 0.5,
     "refractive_index": 1.5},
    {"center": [0, 0, 4], "radius": 2, "color": [200, 255, 200], "reflective": 0.3, "transparency": 0.5,
     "refractive_index": 1.3}],
  "planes": [
    {"point": [0, 0, 7], "normal": [0, 0, -1], "color": [255, 255, 255], "reflective": 0.9},
    {"point": [0, 0, -0.5], "normal": [0, 0, 1], "color": [255, 255, 255], "reflective": 0.9}],
  "lights": [{"type": "ambient", "intensity": 0.4}, {"type": "point", "intensity": 0.6, "position": [0, 1.5, 0.5]}]})";

Image render_on(const DeviceInfo& device, const Scene& s, int depth, bool probe) {
  KernelConfig config;
  config.probe_lanes = false;
  config.loop_limit_probe = probe;
  Renderer r({device}, RenderSettings{config, {}, {}});
  Sampling no_cut;
  no_cut.ray_cut = false;
  r.prepare(s, 8, 8, depth, no_cut);
  return r.render();
}

// The first device that ends long loops (llvmpipe where Mesa rusticl is
// installed and RUSTICL_ENABLE asks for it), or none.
const DeviceInfo* loop_limited_device(const std::vector<DeviceInfo>& devices) {
  for (const DeviceInfo& d : devices)
    if (ends_long_loops(d)) return &d;
  return nullptr;
}

}  // namespace

TEST_CASE("a driver that ends long loops early: an error, not a wrong image", "[opencl][loop-limit]") {
  const std::vector<DeviceInfo> devices = list_devices();
  const DeviceInfo* limited = loop_limited_device(devices);
  if (!limited) {
    WARN("no llvmpipe device (Mesa rusticl with RUSTICL_ENABLE=swrast): nothing to check here");
    return;
  }
  const Scene s = parse_scene(kShells, "shells in mirrors");
  // Within the allowance: the reference's image at the compare tolerance.
  Sampling no_cut;
  no_cut.ray_cut = false;
  const Comparison within = compare_images(render_on(*limited, s, 8, true), render_reference(s, 8, 8, 8, no_cut));
  CHECK(within_tolerance(within));
  // Past it: the error, naming the device and the limit.
  CHECK_THROWS_AS(render_on(*limited, s, 22, true), DeviceError);
  CHECK_THROWS_WITH(render_on(*limited, s, 22, true),
                    Catch::Contains("llvmpipe") && Catch::Contains("65 535 loop iterations"));
}

TEST_CASE("the loop-limit check reports nothing and changes no pixel where loops run to the end",
          "[opencl][loop-limit]") {
  const DeviceInfo device = clrt_test::test_device();
  if (ends_long_loops(device)) return;  // (the case above is that device's)
  const Scene s = parse_scene(kShells, "shells in mirrors");
  // Depth 22: ~10^5 rays per pixel, loops the probe must not mistake for
  // the limit; the image is the one without the check, bit for bit.
  const Image with = render_on(device, s, 22, true);
  const Image without = render_on(device, s, 22, false);
  CHECK(with.rgb == without.rgb);
}

TEST_CASE("clrt render on a driver that ends long loops early: one error line, exit 2, no image", "[opencl][cli]") {
  const std::vector<DeviceInfo> devices = list_devices();
  const DeviceInfo* limited = loop_limited_device(devices);
  if (!limited) {
    WARN("no llvmpipe device: nothing to check here");
    return;
  }
  TempDir dir;
  const RunResult run = run_clrt({"render", dir.write("shells.json", kShells), "-o", dir / "x.pfm", "--width", "8", "--height", "8",
                                  "--depth", "22", "--no-ray-cut", "--device", "llvmpipe"},
                                 "RUSTICL_ENABLE=swrast");
  CHECK(run.status == 2);
  CHECK(run.one_line_error());
  CHECK_THAT(run.err, Catch::Contains("ended the kernel's loops early"));
  CHECK(dir.entries() == std::vector<std::string>{"shells.json"});
}

}  // namespace test_loop_limit
