// layer_compare.hpp - the AOV layers of a frame (image/layers.hpp) against
// the reference's, each with its stated tolerance (`clrt compare --aov`).
#pragma once
#include <cstddef>
#include <string>

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
// The other layers are compared where both hit the same primitive:
// depth   |Z - Z_ref| <= kDepthRelative Z_ref. Float32 holds 2^-24 (6e-8)
//         relative; the kernel's t and |D| each round a few times and the
//         robust kernel recovers t of even the radius-5000 floor to about
//         1e-6 (measured: docs/guide/images.md); 1e-4 leaves a factor of 100
//         and still catches a wrong root (the far side of a sphere, a
//         shadow-acne offset: relative errors of 1e-3 and more).
// normal  every component within kNormalAbsolute of the reference's. A unit
//         normal's components are float32 values of at most 1 (6e-8
//         spacing); the hit point's error over the radius moves them, about
//         1e-6 measured; 1e-4 is a direction within 0.006 degrees.
// albedo  equal at the 8-bit level: round(255 a) of the kernel's and the
//         reference's a (the primitive's own colour / 255 in float32 and
//         double, the same 8-bit colour).
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
  size_t silhouette_pixels = 0;  // the reference's silhouette pixels (the denominator of their share)
  double depth_max_relative = 0;
  size_t depth_over = 0;  // pixels over kDepthRelative
  double normal_max_error = 0;
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
// kLayerId added). std::invalid_argument when they do not fit.
LayerComparison compare_layers(const FrameLayers& test, const FrameLayers& reference);

}  // namespace clrt
