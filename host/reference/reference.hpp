// reference.hpp - the oracle: a scalar, recursive, double-precision, literal
// translation of the book's ray tracer (Computer Graphics from Scratch,
// chapters 2-5, and its web demo). Deliberately independent of the kernel.
#pragma once
#include "image/image.hpp"
#include "image/layers.hpp"
#include "scene/sampling.hpp"
#include "scene/scene.hpp"
#include "util/progress.hpp"

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
// bit. The kernel states the same rule (kernels/clrt_samples.h); the tests check
// that the two agree.
//
// Transparency and refraction (chapter 5; Sphere::transparency,
// Sphere::refractive_index): a hit blends its local colour, the reflected
// colour and the refracted one as
//   (1 - r) ((1 - t) local + t refracted) + r reflected,
// both children traced with depth - 1 (the book's recursion, now a binary
// tree); the ray's medium, Snell's law, total internal reflection and the
// medium around nested spheres are stated in reference.cpp (RefractRay,
// MediumOutside, CameraMedium). Shadow rays are the book's: transparent
// spheres block light like opaque ones.
//
// Adaptive supersampling (sampling.adaptive(), scene/sampling.hpp): the
// four corner samples of the grid first (s = 0, N - 1, N (N - 1), N^2 - 1);
// the pixel is their mean when they hit the same primitive (or all miss)
// and each channel's largest minus smallest value among them is at most T;
// otherwise the mean of all N^2 samples.
//
// Subsampling (sampling.subsample, spp 1; scene/sampling.hpp): the even
// columns are traced first; then an odd column's pixel whose left and right
// neighbours hit the same primitive is, with Shade, traced against that
// primitive alone (the full search where it misses it; background where both
// missed) and shaded as usual, with Interpolate the mean of their canvas
// colours. Other pixels are traced as usual.
//
// `cancel` (optional) is asked once per column of the canvas; true: Cancelled
// (util/error.hpp) is thrown.
Image render_reference(const Scene& scene, int width, int height, int depth, Sampling sampling = {},
                       const CancelFn& cancel = {});

// The AOV layers `layers` (image/layers.hpp: kLayer* bits) of a width x
// height frame of `scene`: for each pixel the first hit of the camera ray
// through the canvas point (x, y) - the book's ClosestIntersection from the
// camera, t in (1, inf) - its distance t |D|, the unit normal that shading
// uses there, the primitive's colour / 255 and its id (as the hit classes
// number them); +inf, zeros and -1 on a miss. Written apart from the
// kernel's (kernels/clrt_layers.h), like the rest of this file.
// `incidence` (optional): each pixel's |cos| of the angle between that ray
// and the normal (1 on a miss), which scales the layers' tolerances
// (eval/layer_compare.hpp).
FrameLayers render_reference_layers(const Scene& scene, int width, int height, unsigned layers,
                                    const CancelFn& cancel = {}, std::vector<float>* incidence = nullptr);

}  // namespace clrt
