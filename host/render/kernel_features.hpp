// kernel_features.hpp - what a scene asks of the kernel, as a value (the idea
// of Cycles' DeviceRequestedFeatures): computed once from (scene, depth),
// compared with ==, and turned into -D options by build_options.hpp (equal
// features, equal options).
#pragma once
#include <cstddef>
#include <vector>

#include "scene/scene.hpp"

namespace clrt {

// A specialized build makes the sphere and light counts (and each light's
// type) compile-time constants, and unrolls their loops, only up to these
// counts; past them it keeps the other specializations and loops over the
// scene's buffers, so build time stays bounded for any scene
// (docs/reference/kernel.md, "Specialization").
constexpr size_t kMaxUnrolledSpheres = 16, kMaxUnrolledLights = 16;

// The rule for the bound above.
constexpr bool counts_unrolled(size_t sphere_count, size_t light_count) {
  return sphere_count <= kMaxUnrolledSpheres && light_count <= kMaxUnrolledLights;
}

struct KernelFeatures {
  size_t sphere_count = 0;
  size_t light_count = 0;
  size_t plane_count = 0;              // chapter 5's flat primitives (their loops
  size_t triangle_count = 0;           // compile out when there are none)
  std::vector<LightType> light_types;  // each light's type, in scene order
  bool has_ambient = false;            // some light of each type
  bool has_point = false;
  bool has_directional = false;
  bool has_specular = false;     // some sphere with specular != -1
  bool has_reflective = false;   // some sphere with reflective > 0
  bool has_transparent = false;  // some sphere with transparency > 0
  // Each sphere's needs_compensation() (render/conditioning.hpp), in scene
  // order: whether the robust kernel tests it with compensated arithmetic.
  // A specialized robust build makes them constants (build_options.cpp).
  std::vector<bool> compensated;
  // The recursion depth the kernel is built for: the requested one, folded
  // to 0 when nothing reflects or refracts so that one program serves every depth.
  int depth = 0;
  // Whether the counts (and light types) are compile-time constants with
  // unrolled loops: counts_unrolled(sphere_count, light_count).
  bool unroll_counts = true;

  // How many spheres are compensated.
  size_t compensated_spheres() const;
  // Shadow rays are cast toward point and directional lights only.
  bool has_shadows() const { return has_point || has_directional; }
  // Whether the kernel tests planes or triangles at all.
  bool has_flat() const { return plane_count > 0 || triangle_count > 0; }
  // Reflection rays are traced only when something reflects and depth > 0.
  bool traces_reflections() const { return has_reflective && depth > 0; }
  // Refracted rays (and the pending children of the tree walk, clrt_ray_tree.h)
  // only when something is transparent and depth > 0.
  bool traces_refractions() const { return has_transparent && depth > 0; }

  bool operator==(const KernelFeatures& other) const;
  bool operator!=(const KernelFeatures& other) const { return !(*this == other); }
};

KernelFeatures kernel_features(const Scene& scene, int depth);

}  // namespace clrt
