// reference.hpp - the oracle: a scalar, recursive, double-precision, literal
// translation of the book's ray tracer (Computer Graphics from Scratch,
// chapters 2-5, and its web demo). Deliberately independent of the kernel.
#pragma once
#include "image/image.hpp"
#include "scene/scene.hpp"

namespace clrt {

// Renders width x height at the given recursion depth (the scene's own
// recursion_depth is ignored; callers pass it when they want it).
//
// Supersampling (spp = N, 1..CLRT_MAX_SPP): pixel (x, y) of the book's canvas
// (x = col - W/2, y = H/2 - 1 - row) is traced at the canvas points
// (x + o_i, y + o_j), o_k = (k + 0.5) / N - 0.5 for k = 0..N-1, sample
// s = j * N + i, and its colour is the mean of the N^2 colours (unclamped,
// before the canvas rule); its hit/shadow classification is sample 0's, at
// (x + o_0, y + o_0). N = 1 is the book's one ray through (x, y), bit for
// bit. The kernel states the same rule (kernels/trace.cl); the tests check
// that the two agree.
Image render_reference(const Scene& scene, int width, int height, int depth, int spp = 1);

}  // namespace clrt
