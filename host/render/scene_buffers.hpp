// scene_buffers.hpp - packs a Scene into the layouts of kernels/clrt_layout.h.
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "clrt_layout.h"
#include "render/precision.hpp"
#include "scene/sampling.hpp"
#include "scene/scene.hpp"

namespace clrt {

struct SceneData {
  clrt_params params{};
  std::vector<clrt_sphere> spheres;
  std::vector<clrt_light> lights;
  std::vector<clrt_material> materials;  // of the planes and triangles
  std::vector<clrt_plane> planes;
  std::vector<clrt_triangle> triangles;        // empty where pack_scene() gave them to a sink
  std::vector<clrt_triangle_lo> triangles_lo;  // their lo parts, likewise
  uint64_t triangles_digest = 0;               // of the packed triangles (ContentHash), kept or not
};

// Where pack_scene() puts the packed triangles: SceneData::triangles when
// this is empty; else straight into arrays of every triangle (a mapped
// device buffer, filled on every core), or a chunk at a time to a sink, so
// that a caller can write them to a device without holding them all (the
// upload of 4 million held them twice: docs/results/meshes.md).
using TriangleSink =
    std::function<void(const clrt_triangle* triangles, const clrt_triangle_lo* triangles_lo, size_t count)>;
constexpr size_t kTriangleChunk = size_t(1) << 16;
struct TriangleOutput {
  TriangleSink sink;                         // kTriangleChunk at most a call, in order; or
  clrt_triangle* triangles = nullptr;        // one per scene triangle, and
  clrt_triangle_lo* triangles_lo = nullptr;  // their lo parts (null: not kept)
};

// Robust and fast modes are camera-relative: the host subtracts the camera
// position in double before rounding to float, so geometry near the camera
// keeps full float precision wherever the scene sits in world space.
bool camera_relative(Precision p);
// The point the packed coordinates are relative to: the camera position for
// camera-relative variants, else the world origin.
Vec3 packing_origin(const Scene& scene, Precision p);

// The kernel's code (CLRT_LIGHT_*) of a light type: clrt_light.type and the
// entries of -DCLRT_LIGHT_TYPES.
int kernel_light_code(LightType type);

// A double as a float `hi` (the nearest float) plus a float `lo` (what hi
// misses, rounded): hi + lo carries ~48 bits, and lo is 0 for a float.
void split_hi_lo(double value, float& hi, float& lo);
// The same for each coordinate: hi[0..2], lo[0..2].
void split3(const Vec3& v, float* hi, float* lo);

// Chapter 5's media (refraction): the refractive index around sphere
// `index` (that of the smallest transparent sphere containing it whole, else
// 1) and around the camera (the smallest transparent sphere containing its
// position, else 1): clrt_sphere.outside_index and clrt_params.camera_medium.
double outside_medium(const Scene& scene, size_t index);
double camera_medium(const Scene& scene);

// spp: N for N x N samples per pixel (clrt_params.spp, read at run time).
// `triangle_order` (a Bvh's): the triangles packed in that order of their
// scene indices, which must name each once (default: the scene's order).
SceneData pack_scene(const Scene& scene, Precision precision, int width, int height, int depth, Sampling sampling = {},
                     const TriangleOutput& triangles = {}, const std::vector<clrt_i32>* triangle_order = nullptr);

// The hierarchy's copies of the packed spheres for its leaves
// (clrt_leaf_sphere): one per entry of `primitives` (a Bvh's), in its order,
// the radius negated for a compensated sphere; empty when no entry is a sphere.
std::vector<clrt_leaf_sphere> pack_leaf_spheres(const std::vector<clrt_i32>& primitives,
                                                const std::vector<clrt_sphere>& spheres);

// One entry of CLRT_LAYOUT_FIELDS as this (host) compiler lays it out; the
// layout test compares it with the kernel compiler's view.
struct LayoutField {
  const char* type;    // e.g. "clrt_sphere"
  const char* member;  // e.g. "radius"
  int offset;          // of the member in its struct
  int size;            // of the member
  int type_size;       // of its struct
};

// offsetof is exact on the host (the structs are standard-layout); only the
// kernel side needs the two-address form, see kernels/layout_probe.cl.
#define CLRT_HOST_LAYOUT_FIELD(type, member) \
  LayoutField{#type, #member, int(offsetof(type, member)), int(sizeof(type::member)), int(sizeof(type))},
inline constexpr LayoutField kLayoutFields[] = {CLRT_LAYOUT_FIELDS(CLRT_HOST_LAYOUT_FIELD)};
#undef CLRT_HOST_LAYOUT_FIELD

}  // namespace clrt
