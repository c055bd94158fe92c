// kernel_features.cpp - scene analysis for the specialized kernel.
#include "render/kernel_features.hpp"

#include <algorithm>
#include <tuple>

#include "render/conditioning.hpp"

namespace clrt {

bool KernelFeatures::operator==(const KernelFeatures& other) const {
  auto fields = [](const KernelFeatures& f) {
    return std::tie(f.sphere_count, f.light_count, f.plane_count, f.triangle_count, f.light_types, f.has_ambient,
                    f.has_point, f.has_directional, f.has_specular, f.has_reflective, f.has_transparent, f.compensated,
                    f.depth, f.unroll_counts);
  };
  return fields(*this) == fields(other);
}

size_t KernelFeatures::compensated_spheres() const {
  return size_t(std::count(compensated.begin(), compensated.end(), true));
}

KernelFeatures kernel_features(const Scene& scene, int depth) {
  KernelFeatures f;
  f.sphere_count = scene.spheres.size();
  f.light_count = scene.lights.size();
  for (const Light& light : scene.lights) {
    f.light_types.push_back(light.type);
    f.has_ambient |= light.type == LightType::Ambient;
    f.has_point |= light.type == LightType::Point;
    f.has_directional |= light.type == LightType::Directional;
  }
  f.plane_count = scene.planes.size();
  f.triangle_count = scene.triangles.size();
  // Flat primitives reflect (the transparent ones are spheres only).
  for (const Plane& plane : scene.planes) {
    f.has_specular |= plane.material.specular != -1;
    f.has_reflective |= plane.material.reflective > 0;
  }
  for (const Triangle& triangle : scene.triangles) {
    f.has_specular |= triangle.material.specular != -1;
    f.has_reflective |= triangle.material.reflective > 0;
  }
  for (const Sphere& sphere : scene.spheres) {
    f.has_specular |= sphere.specular != -1;
    f.has_reflective |= sphere.reflective > 0;
    f.has_transparent |= sphere.transparency > 0;
    f.compensated.push_back(needs_compensation(sphere, scene));
  }
  f.depth = f.has_reflective || f.has_transparent ? depth : 0;
  f.unroll_counts = counts_unrolled(f.sphere_count, f.light_count);
  return f;
}

}  // namespace clrt
