// engine.cpp - dispatch to the reference renderer or the OpenCL renderer.
#include "engine.hpp"

#include <chrono>
#include <iostream>

#include "reference.hpp"

namespace clrt {

Image run_engine(const std::string& engine, const Scene& scene, const RenderOptions& o, int depth, EngineRun* run) {
  EngineRun r;
  r.engine = engine;
  Image img;
  if (engine == "reference") {
    auto t0 = std::chrono::steady_clock::now();
    img = render_reference(scene, o.width, o.height, depth);
    r.wall_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    r.device = "host (scalar double)";
  } else {
    ClRenderer cl(select_device(o.device), o.kernel_config());
    int lx, ly;
    parse_local_size(o.local_size, lx, ly);
    cl.set_local_size(lx, ly);
    cl.set_max_tile(o.max_tile);
    cl.prepare(scene, o.width, o.height, depth);
    img = cl.render();
    r.cl = cl.timings();
    r.wall_ms = r.cl.total_ms;
    r.device = cl.device().name;
    r.options = cl.options();
  }
  if (run) *run = r;
  return img;
}

}  // namespace clrt
