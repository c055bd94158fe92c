// engine.cpp - dispatch to the reference renderer or the OpenCL renderer.
#include "app/engine.hpp"

#include "reference/reference.hpp"
#include "util/progress.hpp"
#include "util/timer.hpp"

namespace clrt {

Image run_engine(const std::string& engine, const Scene& scene, const RenderOptions& o, int depth, EngineRun* run,
                 FrameContents contents) {
  EngineRun r;
  r.engine = engine;
  Image img;
  if (engine == "reference") {
    const auto t0 = Clock::now();
    img = render_reference(scene, o.image.width, o.image.height, depth, o.image.sampling());
    r.wall_ms = ms_since(t0);
    r.device = "host (scalar double)";
  } else {
    RenderSettings settings = o.settings();
    settings.kernel.output = contents;
    settings.progress = stderr_progress();  // big frames: rows done, on a terminal
    Renderer renderer(o.device.devices(), settings);
    renderer.prepare(scene, o.image.width, o.image.height, depth, o.image.sampling());
    img = renderer.render();
    r.frame = renderer.stats();
    r.wall_ms = r.frame.wall_ms;
    r.device = renderer.device_names();
    r.options = renderer.options();
  }
  if (run) *run = r;
  return img;
}

}  // namespace clrt
