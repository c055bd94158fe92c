// engine.cpp - dispatch to the reference renderer or the OpenCL renderer.
#include "app/engine.hpp"

#include "reference/reference.hpp"
#include "util/error.hpp"
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
    if (contents.layers)
      r.layers = render_reference_layers(scene, o.image.width, o.image.height, contents.layers, cancel);
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
    r.layers = renderer.layers();
    r.wall_ms = r.frame.wall_ms;
    r.device = renderer.device_names();
    r.options = renderer.options();
  }
  if (run) *run = r;
  return img;
}

void check_layers_fit(const Scene& scene, unsigned layers) {
  const size_t primitives = scene.spheres.size() + scene.planes.size() + scene.triangles.size();
  if ((layers & kLayerId) && primitives > size_t(kMaxLayerIds))
    throw UserError("--aov id: the scene has " + std::to_string(primitives) + " primitives; the id layer (float " +
                    "channel) holds ids exactly up to " + std::to_string(kMaxLayerIds));
}

CompareRun run_compare(const Scene& scene, const RenderOptions& o, int depth, const Thresholds& limits,
                       const Image* image, const std::string& image_path, const CancelFn& cancel,
                       const FrameLayers* image_layers) {
  CompareRun c;
  c.depth = depth;
  c.limits = limits;
  c.layers = o.layers();
  check_layers_fit(scene, c.layers | kLayerId);
  // With layers, both engines give the id too: the other layers are
  // compared where the ids agree.
  const uint8_t rendered_layers = uint8_t(c.layers ? c.layers | kLayerId : 0);
  c.ref = run_engine("reference", scene, o, depth, &c.reference, {}, cancel);
  if (c.layers) {
    const auto t0 = Clock::now();
    c.reference.layers =
        render_reference_layers(scene, o.image.width, o.image.height, rendered_layers, cancel, &c.incidence);
    c.reference.wall_ms += ms_since(t0);
  }
  if (!image) {
    c.test = run_engine("opencl", scene, o, depth, &c.opencl, FrameContents{PixelFormat::Float, true, rendered_layers},
                        cancel);
  } else {  // an image file has no hit/shadow data: the reference's
    c.image = image_path;
    c.test = *image;
    c.test.hit = c.ref.hit;
    c.test.shadowed = c.ref.shadowed;
    if (c.layers) {
      if (!image_layers || (image_layers->layers & c.layers) != c.layers)
        throw UserError(image_path + ": --aov " + layer_list(c.layers) + ": the image has the layers \"" +
                        (image_layers ? layer_list(image_layers->layers) : std::string()) +
                        "\" (clrt render --aov writes them into an EXR)");
      c.opencl.layers = *image_layers;  // (without an id layer, compared where the reference hits)
    }
  }
  c.comparison = compare_images(c.test, c.ref);
  c.verdict = judge(c.comparison, limits);
  if (c.layers) {
    c.layer_comparison = compare_layers(c.opencl.layers, c.reference.layers, &c.incidence);
    if (!c.layer_comparison.pass()) {
      c.verdict.pass = false;
      c.verdict.reason += (c.verdict.reason.empty() ? "" : "; ") + c.layer_comparison.failures();
    }
  }
  return c;
}

}  // namespace clrt
