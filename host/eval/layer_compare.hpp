// layer_compare.hpp - the AOV layers of a frame (image/layers.hpp) against
// the reference's, each with its stated tolerance (`clrt compare --aov`).
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "image/layers.hpp"

namespace clrt {

// Tolerances, each stated for float32 kernels against the double reference
// (docs/guide/images.md, "Layers", has the measurements behind them).
//
// id: equal except at the reference's silhouettes. A pixel whose reference
// id differs from one of its 4 neighbours' lies on an edge between
// primitives (or a primitive and the background); there the centre ray
// passes within a fraction of a pixel of the edge and rounding may put it
// on either side. Anywhere else a different id is a wrong hit.
//
// The other layers are compared where both hit the same primitive. An error
// in where a surface lies, d along its normal, moves the hit along the ray
// by d / cos (cos: the cosine between the ray and the normal), and with it
// the normal of a curved surface: near grazing incidence every float32
// kernel's distance and normal grow by 1 / cos, though the surface is as
// close as anywhere. So the depth and normal errors are measured times cos,
// as the surface's offset along its normal (the reference's cos, 1 where
// none is given):
// depth   |Z - Z_ref| cos <= kDepthRelative Z_ref. Float32 holds 2^-24 (6e-8)
//         relative; the robust kernel's distances of the book's scenes,
//         radius-5000 floor included, stay within 2.2e-6 this way
//         (measured: docs/guide/images.md, "Layers"); 1e-4 leaves a factor
//         of 40 and still catches a wrong root (the far side of a sphere, a
//         shadow-acne offset) or a wrong camera ray (a pixel's offset, 1e-3
//         and more).
// normal  every component's error times cos <= kNormalAbsolute. A unit
//         normal's components are float32 values of at most 1 (6e-8
//         spacing); the hit point's float32 error over a sphere's radius,
//         and a triangle's float32 edges in its cross product, move them:
//         under 1e-6 on the book's scenes, 1.6e-5 on scenes/large (the
//         small spheres of random-10k, the mesh's small triangles); 1e-4 (a
//         direction within 0.006 degrees) leaves a factor of 6 there.
// albedo  equal at the 8-bit level: round(255 a) of the kernel's and the
//         reference's a (the primitive's own colour / 255 in float32 and
//         double, the same 8-bit colour).
// The stable, naive and fast kernels solve the floor's quadratic in plain
// float32 (docs/reference/precision.md) and exceed the depth tolerance on
// the book's scenes, as their colours exceed one level: compare reports it.
constexpr double kDepthRelative = 1e-4;
constexpr double kNormalAbsolute = 1e-4;

struct LayerComparison {
  unsigned layers = 0;  // those compared (kLayer* bits)
  size_t pixels = 0;
  size_t same_hit = 0;  // pixels whose ids agree and hit something (where depth, normal, albedo are compared)
  // The id's mismatches (counted whatever layers were asked for: the layers
  // are compared where the ids agree, so the id is always known), and of
  // those the ones off the reference's silhouettes (none allowed).
  size_t id_differ = 0, id_differ_silhouette = 0, id_differ_inside = 0;
  bool ids_compared = true;  // false: the test has no id layer (an EXR without one); the reference's ids decide
  size_t silhouette_pixels = 0;  // the reference's silhouette pixels (the denominator of their share)
  double depth_max_relative = 0;  // |Z - Z_ref| cos / Z_ref
  size_t depth_over = 0;           // pixels over kDepthRelative
  double normal_max_error = 0;     // the largest component error times cos
  size_t normal_over = 0;  // pixels with a component over kNormalAbsolute
  size_t albedo_differ = 0;  // pixels whose 8-bit albedo differs
  size_t non_finite = 0;     // NaN anywhere, or an infinite depth on a hit
  double percent(size_t count) const { return pixels ? 100.0 * double(count) / double(pixels) : 0.0; }
  // Whether every compared layer is within its tolerance.
  bool pass() const;
  // The layers over their tolerance, one clause each ("" when none).
  std::string failures() const;
};

// Compares `test` with `reference` (the same size; the test's layers with
// the reference's ids, which must be there: the reference is rendered with
// kLayerId added; a test without ids is compared where the reference's say
// the primitive is the same); `incidence`: the reference's cos per pixel
// (render_reference_layers()), null for 1. std::invalid_argument when they
// do not fit.
LayerComparison compare_layers(const FrameLayers& test, const FrameLayers& reference,
                               const std::vector<float>* incidence = nullptr);

}  // namespace clrt
