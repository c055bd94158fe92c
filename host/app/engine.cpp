// engine.cpp - dispatch to the reference renderer or the OpenCL renderer.
#include "app/engine.hpp"

#include "reference/reference.hpp"
#include "util/progress.hpp"
#include "util/timer.hpp"

namespace clrt {

Image run_engine(const std::string& engine, const Scene& scene, const RenderOptions& o, int depth, EngineRun* run,
                 FrameContents contents, const CancelFn& cancel) {
  EngineRun r;
  r.engine = engine;
  Image img;
  if (engine == "reference") {
    const auto t0 = Clock::now();
    img = render_reference(scene, o.image.width, o.image.height, depth, o.image.sampling(), cancel);
    r.wall_ms = ms_since(t0);
    r.device = "host (scalar double)";
  } else {
    RenderSettings settings = o.settings();
    settings.kernel.output = contents;
    settings.progress = stderr_progress();  // big frames: rows done, on a terminal
    settings.cancel = cancel;
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

CompareRun run_compare(const Scene& scene, const RenderOptions& o, int depth, const Thresholds& limits,
                       const Image* image, const std::string& image_path, const CancelFn& cancel) {
  CompareRun c;
  c.depth = depth;
  c.limits = limits;
  c.ref = run_engine("reference", scene, o, depth, &c.reference, {}, cancel);
  if (!image) {
    c.test = run_engine("opencl", scene, o, depth, &c.opencl, {}, cancel);
  } else {  // an image file has no hit/shadow data: the reference's
    c.image = image_path;
    c.test = *image;
    c.test.hit = c.ref.hit;
    c.test.shadowed = c.ref.shadowed;
  }
  c.comparison = compare_images(c.test, c.ref);
  c.verdict = judge(c.comparison, limits);
  return c;
}

}  // namespace clrt
