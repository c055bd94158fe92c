// sampling.hpp - how a pixel is sampled: N x N supersampling (--spp) and the
// book's adaptive variant (--adaptive T). A render setting, like the image
// size: the scene format has no field for it. The rule, stated in both
// engines (reference/reference.hpp, kernels/trace.cl), is in the README
// ("Anti-aliasing").
#pragma once

namespace clrt {

struct Sampling {
  int spp = 1;  // N: N x N stratified samples per pixel (1..CLRT_MAX_SPP)
  // Adaptive supersampling: with a threshold T >= 0 (in 8-bit levels of the
  // unclamped colour) a pixel first traces the 4 corner samples of its
  // N x N grid; when they hit the same primitive (or all miss) and no
  // channel spans more than T among them, the pixel is their mean, else all
  // N^2 samples are traced. Negative: off (every pixel traces N^2).
  double adaptive_threshold = -1;

  Sampling() = default;
  Sampling(int samples_per_axis, double threshold = -1) : spp(samples_per_axis), adaptive_threshold(threshold) {}
  // Adaptive sampling needs a grid with corners to refine from: N >= 3 (at
  // N = 2 the corners are every sample).
  bool adaptive() const { return adaptive_threshold >= 0 && spp >= 3; }
};

}  // namespace clrt
