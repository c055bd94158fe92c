// scene_buffers.cpp - Scene (double) -> device layouts (float hi/lo pairs).
#include "render/scene_buffers.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <iterator>

#include "render/conditioning.hpp"

namespace clrt {

// The layout contract with the kernel: every member a 32-bit scalar, no
// padding surprises, and CLRT_LAYOUT_FIELDS naming every member in order (so
// that the layout test, which walks that list, covers every byte). A change
// to clrt_layout.h that breaks this fails here.
static_assert(sizeof(clrt_f32) == 4 && sizeof(clrt_i32) == 4, "32-bit scalars");
static_assert(sizeof(clrt_sphere) == 64, "clrt_sphere size");
static_assert(sizeof(clrt_light) == 32, "clrt_light size");
static_assert(sizeof(clrt_params) == 168, "clrt_params size");
static_assert(sizeof(clrt_ray_counts) == 16, "clrt_ray_counts size");
static_assert(sizeof(clrt_bvh_node) == 32, "clrt_bvh_node size");

namespace {

// Index of the first entry of kLayoutFields that breaks the contract above,
// -1 if none: each struct's entries must start at offset 0, each one where
// the previous one ends, the last one at the end of the struct, and every
// member must be whole 32-bit scalars.
constexpr int first_layout_gap() {
  constexpr int n = static_cast<int>(std::size(kLayoutFields));
  for (int i = 0; i < n; ++i) {
    const LayoutField& f = kLayoutFields[i];
    if (f.size % 4 != 0) return i;
    if (f.offset != 0) {  // not the first member of its struct
      if (i == 0) return i;
      const LayoutField& previous = kLayoutFields[i - 1];
      if (f.type_size != previous.type_size || f.offset != previous.offset + previous.size) return i;
    }
    const bool last_of_struct = i + 1 == n || kLayoutFields[i + 1].offset == 0;
    if (last_of_struct && f.offset + f.size != f.type_size) return i;
  }
  return -1;
}
static_assert(first_layout_gap() == -1,
              "CLRT_LAYOUT_FIELDS must name every member of the shared structs, in order, with no padding between");

void split3(Vec3 v, float* hi, float* lo) {
  split_hi_lo(v.x, hi[0], lo[0]);
  split_hi_lo(v.y, hi[1], lo[1]);
  split_hi_lo(v.z, hi[2], lo[2]);
}

}  // namespace

void split_hi_lo(double value, float& hi, float& lo) {
  hi = static_cast<float>(value);
  lo = static_cast<float>(value - static_cast<double>(hi));
}

int kernel_light_code(LightType type) {
  switch (type) {
    case LightType::Ambient:
      return CLRT_LIGHT_AMBIENT;
    case LightType::Point:
      return CLRT_LIGHT_POINT;
    case LightType::Directional:
      return CLRT_LIGHT_DIRECTIONAL;
  }
  return CLRT_LIGHT_AMBIENT;  // unreachable: every LightType is listed above
}

bool camera_relative(Precision p) {
  return p == Precision::Robust || p == Precision::Fast;
}

Vec3 packing_origin(const Scene& scene, Precision p) {
  return camera_relative(p) ? scene.camera.position : Vec3{};
}

SceneData pack_scene(const Scene& scene, Precision precision, int width, int height, int depth, int spp) {
  SceneData d;
  const Vec3 shift = packing_origin(scene, precision);
  clrt_params& p = d.params;
  p.width = width;
  p.height = height;
  p.depth = depth;
  p.spp = spp;
  p.n_spheres = static_cast<clrt_i32>(scene.spheres.size());
  p.n_lights = static_cast<clrt_i32>(scene.lights.size());
  split_hi_lo(scene.camera.viewport_w, p.viewport[0], p.viewport_lo[0]);
  split_hi_lo(scene.camera.viewport_h, p.viewport[1], p.viewport_lo[1]);
  split_hi_lo(scene.camera.projection_plane_d, p.proj_d, p.proj_d_lo);
  split_hi_lo(scene.epsilon, p.epsilon, p.epsilon_lo);
  split3(scene.camera.position - shift, p.origin, p.origin_lo);
  for (int k = 0; k < 9; ++k) split_hi_lo(scene.camera.rotation[k], p.rotation[k], p.rotation_lo[k]);
  p.background[0] = static_cast<float>(scene.background.x);
  p.background[1] = static_cast<float>(scene.background.y);
  p.background[2] = static_cast<float>(scene.background.z);

  for (const Sphere& s : scene.spheres) {
    clrt_sphere o{};
    split3(s.center - shift, o.center, o.center_lo);
    split_hi_lo(s.radius, o.radius, o.radius_lo);
    o.color[0] = static_cast<float>(s.color.x);
    o.color[1] = static_cast<float>(s.color.y);
    o.color[2] = static_cast<float>(s.color.z);
    o.specular = static_cast<float>(s.specular);
    o.reflective = static_cast<float>(s.reflective);
    o.compensated = needs_compensation(s, scene);  // read by robust kernels only
    d.spheres.push_back(o);
  }
  for (const Light& l : scene.lights) {
    clrt_light o{};
    o.type = kernel_light_code(l.type);
    o.intensity = static_cast<float>(l.intensity);
    // Positions move with the camera-relative shift; directions do not.
    if (l.type == LightType::Point) split3(l.vec - shift, o.vec, o.vec_lo);
    if (l.type == LightType::Directional) split3(l.vec, o.vec, o.vec_lo);
    d.lights.push_back(o);
  }
  return d;
}

}  // namespace clrt
