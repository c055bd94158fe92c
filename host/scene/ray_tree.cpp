// ray_tree.cpp - the largest ray tree a camera ray can grow (ray_tree.hpp).
#include "scene/ray_tree.hpp"

#include <cmath>
#include <cstdio>
#include <string>

namespace clrt {

double worst_rays_per_camera_ray(const Scene& scene, int depth) {
  bool reflects = false, branches = false;
  for (const Sphere& s : scene.spheres) {
    reflects |= s.reflective > 0 || s.transparency > 0;
    branches |= s.reflective > 0 && s.transparency > 0;
  }
  for (const Plane& p : scene.planes) reflects |= p.material.reflective > 0;
  for (const Triangle& t : scene.triangles) reflects |= t.material.reflective > 0;
  if (depth <= 0 || !reflects) return 1;
  return branches ? std::ldexp(1.0, depth + 1) - 1 : double(depth) + 1;
}

double worst_rays_per_frame(const Scene& scene, int depth, int width, int height, int spp) {
  return worst_rays_per_camera_ray(scene, depth) * double(width) * double(height) * double(spp) * double(spp);
}

std::string ray_tree_warning(const Scene& scene, int depth, int width, int height, int spp) {
  const double frame = worst_rays_per_frame(scene, depth, width, height, spp);
  if (frame < kRayWarningThreshold) return "";
  char text[320];
  std::snprintf(text, sizeof text,
                "a camera ray may branch into up to %.3g rays at depth %d (a surface both reflects and refracts): "
                "up to %.3g rays in this %dx%d frame, hours of work or more; a lower --depth bounds it",
                worst_rays_per_camera_ray(scene, depth), depth, frame, width, height);
  return text;
}

}  // namespace clrt
