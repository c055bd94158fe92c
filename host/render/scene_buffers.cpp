// scene_buffers.cpp - Scene (double) -> device layouts (float hi/lo pairs).
#include "render/scene_buffers.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace clrt {

// The layout contract with the kernel: every member a 32-bit scalar, no
// padding surprises. A change to clrt_layout.h that breaks this fails here.
static_assert(sizeof(clrt_f32) == 4 && sizeof(clrt_i32) == 4, "32-bit scalars");
static_assert(sizeof(clrt_sphere) == 64, "clrt_sphere size");
static_assert(offsetof(clrt_sphere, radius) == 12, "clrt_sphere.radius");
static_assert(offsetof(clrt_sphere, center_lo) == 16, "clrt_sphere.center_lo");
static_assert(offsetof(clrt_sphere, color) == 32, "clrt_sphere.color");
static_assert(offsetof(clrt_sphere, specular) == 44, "clrt_sphere.specular");
static_assert(offsetof(clrt_sphere, reflective) == 48, "clrt_sphere.reflective");
static_assert(sizeof(clrt_light) == 32, "clrt_light size");
static_assert(offsetof(clrt_light, intensity) == 4, "clrt_light.intensity");
static_assert(offsetof(clrt_light, vec) == 8, "clrt_light.vec");
static_assert(offsetof(clrt_light, vec_lo) == 20, "clrt_light.vec_lo");
static_assert(sizeof(clrt_params) == 168, "clrt_params size");
static_assert(offsetof(clrt_params, viewport) == 24, "clrt_params.viewport");
static_assert(offsetof(clrt_params, proj_d) == 32, "clrt_params.proj_d");
static_assert(offsetof(clrt_params, epsilon) == 36, "clrt_params.epsilon");
static_assert(offsetof(clrt_params, origin) == 40, "clrt_params.origin");
static_assert(offsetof(clrt_params, origin_lo) == 52, "clrt_params.origin_lo");
static_assert(offsetof(clrt_params, rotation) == 64, "clrt_params.rotation");
static_assert(offsetof(clrt_params, rotation_lo) == 100, "clrt_params.rotation_lo");
static_assert(offsetof(clrt_params, background) == 136, "clrt_params.background");
static_assert(offsetof(clrt_params, proj_d_lo) == 148, "clrt_params.proj_d_lo");
static_assert(offsetof(clrt_params, viewport_lo) == 152, "clrt_params.viewport_lo");
static_assert(offsetof(clrt_params, epsilon_lo) == 160, "clrt_params.epsilon_lo");
static_assert(sizeof(clrt_ray_counts) == 16, "clrt_ray_counts size");

namespace {

void split(double v, float& hi, float& lo) {
  hi = static_cast<float>(v);
  lo = static_cast<float>(v - static_cast<double>(hi));
}

void split3(Vec3 v, float* hi, float* lo) {
  split(v.x, hi[0], lo[0]);
  split(v.y, hi[1], lo[1]);
  split(v.z, hi[2], lo[2]);
}

}  // namespace

bool camera_relative(Precision p) { return p == Precision::Robust || p == Precision::Fast; }

SceneData pack_scene(const Scene& scene, Precision precision, int width, int height, int depth) {
  SceneData d;
  const Vec3 shift = camera_relative(precision) ? scene.camera.position : Vec3{};
  clrt_params& p = d.params;
  p.width = width;
  p.height = height;
  p.depth = depth;
  p.n_spheres = static_cast<clrt_i32>(scene.spheres.size());
  p.n_lights = static_cast<clrt_i32>(scene.lights.size());
  split(scene.camera.viewport_w, p.viewport[0], p.viewport_lo[0]);
  split(scene.camera.viewport_h, p.viewport[1], p.viewport_lo[1]);
  split(scene.camera.projection_plane_d, p.proj_d, p.proj_d_lo);
  split(scene.epsilon, p.epsilon, p.epsilon_lo);
  split3(scene.camera.position - shift, p.origin, p.origin_lo);
  for (int k = 0; k < 9; ++k) split(scene.camera.rotation[k], p.rotation[k], p.rotation_lo[k]);
  p.background[0] = static_cast<float>(scene.background.x);
  p.background[1] = static_cast<float>(scene.background.y);
  p.background[2] = static_cast<float>(scene.background.z);

  for (const Sphere& s : scene.spheres) {
    clrt_sphere o{};
    split3(s.center - shift, o.center, o.center_lo);
    split(s.radius, o.radius, o.radius_lo);
    o.color[0] = static_cast<float>(s.color.x);
    o.color[1] = static_cast<float>(s.color.y);
    o.color[2] = static_cast<float>(s.color.z);
    o.specular = static_cast<float>(s.specular);
    o.reflective = static_cast<float>(s.reflective);
    d.spheres.push_back(o);
  }
  for (const Light& l : scene.lights) {
    clrt_light o{};
    o.intensity = static_cast<float>(l.intensity);
    switch (l.type) {
      case LightType::Ambient: o.type = CLRT_LIGHT_AMBIENT; break;
      case LightType::Point:
        o.type = CLRT_LIGHT_POINT;
        split3(l.vec - shift, o.vec, o.vec_lo);
        break;
      case LightType::Directional:
        o.type = CLRT_LIGHT_DIRECTIONAL;
        split3(l.vec, o.vec, o.vec_lo);
        break;
    }
    d.lights.push_back(o);
  }
  return d;
}

}  // namespace clrt
