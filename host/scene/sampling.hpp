// sampling.hpp - how a pixel is sampled: N x N supersampling (--spp), the
// book's adaptive variant (--adaptive T) and its subsampling (--subsample).
// A render setting, like the image size: the scene format has no field for
// it. The rules, stated in both engines (reference/reference.hpp;
// kernels/clrt_samples.h, clrt_subsample.h), are in docs/reference/semantics.md.
#pragma once
#include <string>

namespace clrt {

// The book's subsampling (chapter 5), an "impure" speed-up: the pixels of
// even columns are traced as usual; a pixel of an odd column whose left and
// right neighbours' camera rays hit the same primitive (or both missed) is
// not searched for:
//   Shade: it is assumed to hit that primitive (its ray is tested against
//     that primitive alone, with the full search only where it misses it;
//     two missing neighbours make it background), and everything after the
//     hit - lighting, shadows, reflection, refraction - is computed as
//     usual. Wrong only where something narrower than two pixels hides
//     between the neighbours.
//   Interpolate: no ray at all; its colour is the mean of its neighbours'
//     8-bit colours (after the canvas rule), its hit theirs, its shadow
//     mask the lights both neighbours have blocked. Wrong wherever shading
//     is not linear across three pixels (highlights, shadow edges,
//     reflections).
// Other pixels of odd columns, and the image's last column when it is odd,
// are traced as usual. Columns are counted over the whole image, so the rule
// does not depend on how a frame is cut into bands. One sample per pixel.
enum class Subsample { Off, Shade, Interpolate };

inline std::string subsample_name(Subsample mode) {
  return mode == Subsample::Shade ? "shade" : mode == Subsample::Interpolate ? "interpolate" : "off";
}

struct Sampling {
  int spp = 1;  // N: N x N stratified samples per pixel (1..CLRT_MAX_SPP)
  // Adaptive supersampling: with a threshold T >= 0 (in 8-bit levels of the
  // unclamped colour) a pixel first traces the 4 corner samples of its
  // N x N grid; when they hit the same primitive (or all miss) and no
  // channel spans more than T among them, the pixel is their mean, else all
  // N^2 samples are traced. Negative: off (every pixel traces N^2).
  double adaptive_threshold = -1;

  Subsample subsample = Subsample::Off;  // (above; spp 1 only)

  // The weight cut-off of the ray tree (scene/ray_tree.hpp): child rays too
  // light to move a pixel by a level are not traced. false: every ray down
  // to the depth is (--no-ray-cut; the tests' image without the cut).
  bool ray_cut = true;

  Sampling() = default;
  Sampling(int samples_per_axis, double threshold = -1, Subsample subsampling = Subsample::Off)
      : spp(samples_per_axis), adaptive_threshold(threshold), subsample(subsampling) {}
  // Adaptive sampling needs a grid with corners to refine from: N >= 3 (at
  // N = 2 the corners are every sample).
  bool adaptive() const { return adaptive_threshold >= 0 && spp >= 3; }
};

}  // namespace clrt
