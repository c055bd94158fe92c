// ray_tree.hpp - how many rays one camera ray can take. The book's TraceRay
// follows a reflected ray from every reflective hit and, with chapter 5's
// transparency, a refracted one too: where one surface does both, a camera
// ray is a binary tree of up to 2^(depth+1) - 1 rays (two transparent,
// reflective shells in a mirror reach it). Work that large is announced
// before it starts (a warning), never silently begun.
#pragma once
#include <string>

#include "scene/scene.hpp"

namespace clrt {

// The most rays one camera ray of `scene` can take at recursion depth
// `depth`: 1 without reflective or transparent surfaces, depth + 1 when no
// surface both reflects and refracts (only spheres refract), else
// 2^(depth+1) - 1 (as a double: 2^65 does not fit in 64 bits).
double worst_rays_per_camera_ray(const Scene& scene, int depth);

// The worst case of a whole frame: width x height x spp^2 camera rays.
double worst_rays_per_frame(const Scene& scene, int depth, int width, int height, int spp);

// A frame whose worst case passes this many rays gets a warning before the
// work (about an hour at 3e7 rays per second, a CPU device's pace on the
// book's scenes); rendering goes on.
constexpr double kRayWarningThreshold = 1e11;

// The warning's text for that frame, or "" when its worst case is below
// the threshold.
std::string ray_tree_warning(const Scene& scene, int depth, int width, int height, int spp);

}  // namespace clrt
