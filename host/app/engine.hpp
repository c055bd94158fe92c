// engine.hpp - render a scene with the engine the command line picked: the
// OpenCL renderer (render/renderer.hpp) or the scalar double reference.
#pragma once
#include <string>

#include "app/options.hpp"
#include "image/image.hpp"
#include "render/renderer.hpp"
#include "scene/scene.hpp"

namespace clrt {

struct EngineRun {
  std::string engine;   // "opencl" or "reference"
  std::string device;   // device name(s); the host for the reference
  std::string options;  // build options (opencl)
  double wall_ms = 0;   // reference: render time; opencl: render() wall time
  FrameStats frame;     // opencl: build, upload, kernel, per-device shares
};

// `contents`: what the OpenCL frame must hold (render asks for what its
// output file needs); the reference always gives float colour and classes.
Image run_engine(const std::string& engine, const Scene& scene, const RenderOptions& o, int depth, EngineRun* run,
                 FrameContents contents = {});

}  // namespace clrt
