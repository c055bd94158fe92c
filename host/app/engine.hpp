// engine.hpp - run either engine on a scene with the CLI's options.
#pragma once
#include <string>

#include "render/cl_renderer.hpp"
#include "render/multi_renderer.hpp"
#include "app/cli_common.hpp"
#include "image/image.hpp"
#include "scene/scene.hpp"

namespace clrt {

struct EngineRun {
  std::string engine;      // "opencl" or "reference"
  std::string device;      // device name(s) (opencl)
  std::string options;     // build options (opencl)
  double wall_ms = 0;      // reference: render time; opencl: render() wall time
  RenderTimings cl;        // opencl details (kernel_ms summed over devices)
  std::vector<DeviceShare> shares;  // opencl: per-device tiles and time
};

Image run_engine(const std::string& engine, const Scene& scene, const RenderOptions& o, int depth, EngineRun* run);

}  // namespace clrt
