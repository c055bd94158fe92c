// engine.cpp - dispatch to the reference renderer or the OpenCL renderer.
#include "app/engine.hpp"

#include <chrono>
#include <iostream>

#include "reference/reference.hpp"
#include "util/timer.hpp"

namespace clrt {

Image run_engine(const std::string& engine, const Scene& scene, const RenderOptions& o, int depth, EngineRun* run) {
  EngineRun r;
  r.engine = engine;
  Image img;
  if (engine == "reference") {
    auto t0 = std::chrono::steady_clock::now();
    img = render_reference(scene, o.width, o.height, depth);
    r.wall_ms = ms_since(t0);
    r.device = "host (scalar double)";
  } else {
    MultiRenderer cl(select_devices(o.device), o.kernel_config());
    int lx, ly;
    parse_local_size(o.local_size, lx, ly);
    cl.set_local_size(lx, ly);
    cl.set_tile_policy(o.tile_policy());
    cl.prepare(scene, o.width, o.height, depth);
    img = cl.render();
    r.cl = cl.renderer(0).timings();
    r.cl.kernel_ms = cl.kernel_ms();
    r.cl.launches = cl.launches();
    r.cl.host_timed_launches = cl.host_timed_launches();
    r.cl.build_ms = cl.build_ms();
    r.cl.upload_ms = cl.upload_ms();
    r.cl.total_ms = r.wall_ms = cl.wall_ms();
    r.shares = cl.shares();
    for (size_t i = 0; i < cl.size(); ++i) r.device += (i ? " + " : "") + cl.renderer(i).device().name;
    r.options = cl.renderer(0).options();
  }
  if (run) *run = r;
  return img;
}

}  // namespace clrt
