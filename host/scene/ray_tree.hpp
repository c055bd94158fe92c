// ray_tree.hpp - how many rays one camera ray can take, and the weight
// cut-off that bounds them. The book's TraceRay follows a reflected ray from
// every reflective hit and, with chapter 5's transparency, a refracted one
// too: where one surface does both, a camera ray is a binary tree of up to
// 2^(depth+1) - 1 rays (two transparent, reflective shells in a mirror reach
// it).
//
// The cut-off (docs/reference/limits.md derives it). Every ray carries a weight, the
// product of the shares (r, (1 - r) t, or r + (1 - r) t under total internal
// reflection) along its path; whatever its subtree adds to the pixel is that
// weight times a colour of at most C (max_colour below: every ray's colour
// is a blend, with shares that add up to at most 1, of local colours and the
// background). A child ray whose weight is below min_weight is not traced,
// in the kernel and in the reference alike. With alpha (exponent below) the
// smallest number in [0, 1] for which every surface's children have shares
// a, b with a^alpha + b^alpha <= 1, the weights w of any set of rays none of
// which descends from another have sum(w^alpha) <= 1 (by induction from the
// camera ray, weight 1), so the rays that are cut, each below min_weight,
// have weights that add up to less than min_weight^(1 - alpha). min_weight =
// (kRayCutLevels / C)^(1 / (1 - alpha)) thus changes no colour channel by
// kRayCutLevels or more before the 8-bit rounding: no 8-bit value by more
// than one level. The same count bounds the work: at most
// min_weight^-alpha rays of one level pass the cut.
#pragma once
#include <string>

#include "scene/scene.hpp"

namespace clrt {

// How far the rays that are cut may move a colour channel (in 8-bit levels,
// unclamped): under one level, so the cut moves no 8-bit value by more than
// one level; half a level, so that most pixels do not move at all.
constexpr double kRayCutLevels = 0.5;

struct RayCut {
  // alpha: 0 when no surface both reflects and refracts, 1 when one passes
  // all of its light on to two children (t = 1 and 0 < r < 1: no cut-off can
  // be honest there, the pixel is the blend of its deepest rays).
  double exponent = 0;
  // C: the largest colour channel a ray can return (unclamped).
  double max_colour = 0;
  // The cut-off: child rays of smaller weight are not traced. A float (the
  // kernel's clrt_params.min_weight; the reference uses the same value),
  // rounded down; 0 (no cut) where it would fall below float's normal range.
  float min_weight = 0;
};

// The scene's cut-off, computed once per frame on the host.
RayCut ray_cut(const Scene& scene);

// The most rays one camera ray of `scene` can take at recursion depth
// `depth` with the cut-off (cut = false: without it): 1 without reflective
// or transparent surfaces, at most depth + 1 when no surface both reflects
// and refracts (only spheres refract), else at most 2^(depth+1) - 1 (as a
// double: 2^65 does not fit in 64 bits); with the cut, at most
// min_weight^-alpha rays of each level, and none at levels where even the
// largest share's power is below min_weight.
double worst_rays_per_camera_ray(const Scene& scene, int depth, bool cut = true);

// The worst case of a whole frame: width x height x spp^2 camera rays.
double worst_rays_per_frame(const Scene& scene, int depth, int width, int height, int spp, bool cut = true);

// A frame whose worst case passes this many rays gets a warning before the
// work (about an hour at 3e7 rays per second, a CPU device's pace on the
// book's scenes); rendering goes on.
constexpr double kRayWarningThreshold = 1e11;

// The warning's text for that frame, or "" when its worst case is below
// the threshold.
std::string ray_tree_warning(const Scene& scene, int depth, int width, int height, int spp, bool cut = true);

// The ray budget: a frame whose worst case (with the cut-off) passes this
// many rays is refused before any work (--ray-budget changes it). The cut
// bounds every scene whose surfaces each keep some light, whatever the depth;
// it cannot bound one that passes all of its light on to two children
// (t = 1 and 0 < r < 1: 2^(depth+1) - 1 rays), nor one whose shares come so
// close to that that the cut falls below float's range. 1e18 rays is some
// 30 years at 1e9 rays per second: past it a frame is not work that ends,
// and the worst case of every shipped scene at every depth stays below it
// at 600x600 (glass.json: 3.3e15 at depth 64).
constexpr double kRayBudget = 1e18;

// The error's text for that frame when its worst case passes `budget`,
// else "".
std::string ray_budget_error(const Scene& scene, int depth, int width, int height, int spp, double budget,
                             bool cut = true);

}  // namespace clrt
