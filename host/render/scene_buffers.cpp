// scene_buffers.cpp - Scene (double) -> device layouts (float hi/lo pairs).
#include "render/scene_buffers.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <iterator>
#include <map>
#include <stdexcept>

#include "render/conditioning.hpp"
#include "render/pack_triangles.hpp"
#include "scene/ray_tree.hpp"
#include "util/content_hash.hpp"

namespace clrt {

// The layout contract with the kernel: every member a 32-bit scalar, no
// padding surprises, and CLRT_LAYOUT_FIELDS naming every member in order (so
// that the layout test, which walks that list, covers every byte). A change
// to clrt_layout.h that breaks this fails here.
static_assert(sizeof(clrt_f32) == 4 && sizeof(clrt_i32) == 4, "32-bit scalars");
static_assert(sizeof(clrt_sphere) == 80, "clrt_sphere size");
static_assert(sizeof(clrt_light) == 48, "clrt_light size");
static_assert(sizeof(clrt_params) == 188, "clrt_params size");
static_assert(sizeof(clrt_material) == 32, "clrt_material size");
static_assert(sizeof(clrt_plane) == 64, "clrt_plane size");
static_assert(sizeof(clrt_triangle) == 48, "clrt_triangle size");
static_assert(sizeof(clrt_triangle_lo) == 48, "clrt_triangle_lo size");
static_assert(sizeof(clrt_ray_counts) == 20, "clrt_ray_counts size");
static_assert(sizeof(clrt_bvh_node) == 32, "clrt_bvh_node size");
static_assert(sizeof(clrt_wide_node) == 32 * CLRT_BVH_WIDTH, "clrt_wide_node size");
static_assert(sizeof(clrt_leaf_sphere) == 16, "clrt_leaf_sphere size");
static_assert(CLRT_BVH_WIDTH == 4 || CLRT_BVH_WIDTH == 8, "CLRT_BVH_WIDTH: 4 or 8");

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

}  // namespace

void split_hi_lo(double value, float& hi, float& lo) {
  hi = static_cast<float>(value);
  lo = static_cast<float>(value - static_cast<double>(hi));
}

void split3(const Vec3& v, float* hi, float* lo) {
  split_hi_lo(v.x, hi[0], lo[0]);
  split_hi_lo(v.y, hi[1], lo[1]);
  split_hi_lo(v.z, hi[2], lo[2]);
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

namespace {

// The smallest of the `candidates` (indices of transparent spheres) that
// contains sphere `index` whole; nullptr if none.
const Sphere* sphere_around(const Scene& scene, size_t index, const std::vector<size_t>& candidates) {
  const Sphere& sphere = scene.spheres[index];
  const Sphere* around = nullptr;
  for (size_t k : candidates) {
    const Sphere& o = scene.spheres[k];
    if (k == index) continue;
    if (length(o.center - sphere.center) + sphere.radius < o.radius && (!around || o.radius < around->radius))
      around = &o;
  }
  return around;
}

std::vector<size_t> transparent_spheres(const Scene& scene) {
  std::vector<size_t> indices;
  for (size_t i = 0; i < scene.spheres.size(); ++i)
    if (scene.spheres[i].transparency > 0) indices.push_back(i);
  return indices;
}

}  // namespace

// The medium around sphere `index`: the refractive index of the smallest
// transparent sphere that contains it whole (|C_o - C| + r < r_o; ties: the
// first), else 1. The reference states the same rule on its own
// (reference.cpp, MediumOutside).
double outside_medium(const Scene& scene, size_t index) {
  const Sphere* around = sphere_around(scene, index, transparent_spheres(scene));
  return around ? around->refractive_index : 1.0;
}

double camera_medium(const Scene& scene) {
  const Sphere* around = nullptr;
  for (const Sphere& o : scene.spheres) {
    if (o.transparency <= 0) continue;
    if (length(scene.camera.position - o.center) < o.radius && (!around || o.radius < around->radius)) around = &o;
  }
  return around ? around->refractive_index : 1.0;
}

namespace {

// Chapter 5's planes and triangles (shifted by `shift`) and their
// materials into `d`; the triangles where `output` says, in `order` if it
// is set (pack_scene()).
void pack_flat(const Scene& scene, const Vec3& shift, const TriangleOutput& output, const std::vector<clrt_i32>* order,
               SceneData& d) {
  // Planes and triangles name their material by index; equal materials (a
  // mesh's faces) share one entry.
  std::map<MaterialKey, clrt_i32> material_index;
  auto material = [&](const Material& m) {
    auto [at, added] = material_index.emplace(material_key(m), static_cast<clrt_i32>(d.materials.size()));
    if (added) {
      clrt_material o{};
      o.color[0] = static_cast<float>(m.color.x);
      o.color[1] = static_cast<float>(m.color.y);
      o.color[2] = static_cast<float>(m.color.z);
      o.specular = static_cast<float>(m.specular);
      o.reflective = static_cast<float>(m.reflective);
      d.materials.push_back(o);
    }
    return at->second;
  };
  for (const Plane& plane : scene.planes) {
    clrt_plane o{};
    split3(plane.point - shift, o.point, o.point_lo);
    split3(plane.normal, o.normal, o.normal_lo);
    o.material = material(plane.material);
    d.planes.push_back(o);
  }
  const size_t count = scene.triangles.size();
  const std::vector<clrt_i32> entries = triangle_material_entries(scene, material);
  std::vector<uint64_t> hashes;
  if (output.triangles) {
    pack_triangles(scene, shift, order, entries, 0, count, output.triangles, output.triangles_lo, hashes);
  } else if (output.sink) {
    // a chunk at a time, handed on and dropped
    std::vector<clrt_triangle> chunk(std::min(count, kTriangleChunk));
    std::vector<clrt_triangle_lo> chunk_lo(chunk.size());
    for (size_t first = 0; first < count; first += kTriangleChunk) {
      const size_t n = std::min(kTriangleChunk, count - first);
      pack_triangles(scene, shift, order, entries, first, n, chunk.data(), chunk_lo.data(), hashes);
      output.sink(chunk.data(), chunk_lo.data(), n);
    }
  } else {
    d.triangles.resize(count);
    d.triangles_lo.resize(count);
    pack_triangles(scene, shift, order, entries, 0, count, d.triangles.data(), d.triangles_lo.data(), hashes);
  }
  ContentHash digest;
  for (uint64_t hash : hashes) digest.add(&hash, sizeof hash);
  d.triangles_digest = digest.value;
}

}  // namespace

SceneData pack_scene(const Scene& scene, Precision precision, int width, int height, int depth, Sampling sampling,
                     const TriangleOutput& triangles, const std::vector<clrt_i32>* triangle_order) {
  SceneData d;
  const Vec3 shift = packing_origin(scene, precision);
  clrt_params& p = d.params;
  p.width = width;
  p.height = height;
  p.depth = depth;
  p.spp = sampling.spp;
  p.adaptive = sampling.adaptive() ? 1 : 0;
  p.adaptive_threshold = static_cast<float>(sampling.adaptive() ? sampling.adaptive_threshold : 0.0);
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
  p.camera_medium = static_cast<float>(camera_medium(scene));
  p.min_weight = sampling.ray_cut ? ray_cut(scene).min_weight : 0.0f;
  // Only transparent spheres can be another sphere's medium: the search
  // runs over them alone (none in the book's scenes).
  const std::vector<size_t> transparent = transparent_spheres(scene);

  for (size_t index = 0; index < scene.spheres.size(); ++index) {
    const Sphere& s = scene.spheres[index];
    clrt_sphere o{};
    split3(s.center - shift, o.center, o.center_lo);
    split_hi_lo(s.radius, o.radius, o.radius_lo);
    o.color[0] = static_cast<float>(s.color.x);
    o.color[1] = static_cast<float>(s.color.y);
    o.color[2] = static_cast<float>(s.color.z);
    o.specular = static_cast<float>(s.specular);
    o.reflective = static_cast<float>(s.reflective);
    o.compensated = needs_compensation(s, scene);  // read by robust kernels only
    o.transparency = static_cast<float>(s.transparency);
    o.refractive_index = static_cast<float>(s.refractive_index);
    const Sphere* around = sphere_around(scene, index, transparent);
    o.outside_index = static_cast<float>(around ? around->refractive_index : 1.0);
    d.spheres.push_back(o);
  }
  for (const Light& l : scene.lights) {
    clrt_light o{};
    o.type = kernel_light_code(l.type);
    o.intensity = static_cast<float>(l.intensity);
    // Positions move with the camera-relative shift; directions do not.
    if (l.type == LightType::Point) split3(l.vec - shift, o.vec, o.vec_lo);
    o.t_min_scale = 1;
    if (l.type == LightType::Directional) {
      split3(l.vec, o.vec, o.vec_lo);
      // 2^e within float's normal range (directions are within ±kMaxLength;
      // a tiny one's t_min is 0 in float as it is ~0 in double).
      o.t_min_scale = static_cast<float>(std::ldexp(1.0, std::max(-126, std::min(127, l.scale_exponent))));
    }
    d.lights.push_back(o);
  }
  p.n_planes = static_cast<clrt_i32>(scene.planes.size());
  p.n_triangles = static_cast<clrt_i32>(scene.triangles.size());
  pack_flat(scene, shift, triangles, triangle_order, d);
  return d;
}

std::vector<clrt_leaf_sphere> pack_leaf_spheres(const std::vector<clrt_i32>& primitives,
                                                const std::vector<clrt_sphere>& spheres) {
  const auto is_sphere = [](clrt_i32 entry) { return (entry >> CLRT_PRIMITIVE_KIND_SHIFT) == CLRT_PRIMITIVE_SPHERE; };
  if (std::none_of(primitives.begin(), primitives.end(), is_sphere)) return {};
  std::vector<clrt_leaf_sphere> leaves(primitives.size());
  for (size_t k = 0; k < primitives.size(); ++k) {
    if (!is_sphere(primitives[k])) continue;
    const clrt_sphere& s = spheres.at(size_t(primitives[k] & CLRT_PRIMITIVE_INDEX_MASK));
    std::copy(s.center, s.center + 3, leaves[k].center);
    leaves[k].radius = s.compensated ? -s.radius : s.radius;
  }
  return leaves;
}

}  // namespace clrt
