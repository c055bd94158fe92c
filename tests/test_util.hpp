// test_util.hpp - shared helpers for the test suite.
#pragma once
#include <algorithm>
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

// A renderer on the test device.
inline clrt::Renderer renderer(const clrt::KernelConfig& kernel, clrt::TilePolicy tiles = {},
                               clrt::LocalSize local = {}) {
  return clrt::Renderer({test_device()}, clrt::RenderSettings{kernel, tiles, local});
}
// One frame on the test device.
inline clrt::Image render_cl(const clrt::Scene& s, int width, int height, int depth, const clrt::KernelConfig& kernel) {
  clrt::Renderer r = renderer(kernel);
  r.prepare(s, width, height, depth);
  return r.render();
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

}  // namespace clrt_test
