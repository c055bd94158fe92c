// engine.hpp - render a scene with the engine the command line picked: the
// OpenCL renderer (render/renderer.hpp) or the scalar double reference.
#pragma once
#include <string>
#include <vector>

#include "app/options.hpp"
#include "eval/compare.hpp"
#include "eval/layer_compare.hpp"
#include "image/image.hpp"
#include "render/renderer.hpp"
#include "scene/scene.hpp"
#include "util/progress.hpp"

namespace clrt {

struct EngineRun {
  std::string engine;   // "opencl" or "reference"
  std::string device;   // device name(s); the host for the reference
  std::string options;  // build options (opencl)
  double wall_ms = 0;   // reference: render time; opencl: render() wall time
  FrameStats frame;     // opencl: build, upload, kernel, per-device shares
  FrameLayers layers;   // the AOV layers asked for (FrameContents::layers); empty without
};

// UserError when `scene` has more primitives than the id layer holds
// exactly (kMaxLayerIds; only when `layers` has kLayerId).
void check_layers_fit(const Scene& scene, unsigned layers);

// `contents`: what the OpenCL frame must hold (render asks for what its
// output file needs); the reference always gives float colour and classes.
// Both engines give the layers of contents.layers in run->layers.
// `cancel` (optional): asked between bands (OpenCL) or columns (the
// reference); true: Cancelled (util/error.hpp).
Image run_engine(const std::string& engine, const Scene& scene, const RenderOptions& o, int depth, EngineRun* run,
                 FrameContents contents = {}, const CancelFn& cancel = {});

// What `clrt compare` measured: the reference, and OpenCL or an image file,
// and their comparison and verdict.
struct CompareRun {
  int depth = 0;
  EngineRun reference, opencl;  // opencl: empty where an image file was compared
  std::string image;            // that file's path; "": OpenCL
  Image test, ref;              // the images compared (--diff)
  Comparison comparison;
  // --aov: the layers asked for (kLayer* bits; 0: none), the test's (OpenCL,
  // or the image file's) and the reference's, each rendered with the id
  // added, and their comparison (which decides the verdict too).
  unsigned layers = 0;
  std::vector<float> incidence;  // the reference's, per pixel (render_reference_layers())
  LayerComparison layer_comparison;
  Thresholds limits;
  Verdict verdict;
  bool classified() const { return !opencl.engine.empty(); }  // hit/shadow classes known (OpenCL)
};
// Renders `scene` (fitted to o.image: ImageOptions::load_scene) with the
// reference and, unless `image` (read from `image_path`) is given, with
// OpenCL, and compares them against `limits`; with o.layers(), also their
// layers (an image file's: `image_layers`, which must have them).
CompareRun run_compare(const Scene& scene, const RenderOptions& o, int depth, const Thresholds& limits,
                       const Image* image = nullptr, const std::string& image_path = "",
                       const CancelFn& cancel = {}, const FrameLayers* image_layers = nullptr);

}  // namespace clrt
