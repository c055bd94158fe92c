// pack_triangles.hpp - the scene's triangles in the kernel's layout
// (clrt_triangle, clrt_triangle_lo: kernels/clrt_layout.h), on every core:
// millions of them, read in the hierarchy's order from all over the scene
// (pack_scene() in scene_buffers.hpp puts them where they go).
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <tuple>
#include <vector>

#include "clrt_layout.h"
#include "scene/scene.hpp"

namespace clrt {

// What the kernel reads of a material, as a key: materials with equal keys
// share one packed entry (clrt_material).
using MaterialKey = std::tuple<double, double, double, double, double>;
MaterialKey material_key(const Material& m);

// Each scene triangle's material entry: entry_of(m) for its material m,
// called once per material on the calling thread in the order of first use
// in the scene (a mesh's faces share one); equal materials (the fields the
// kernel reads) are one. A scene of millions reads each face once, on every
// core.
std::vector<clrt_i32> triangle_material_entries(const Scene& scene,
                                                const std::function<clrt_i32(const Material&)>& entry_of);

// Triangles are hashed in blocks of this many: the digest of a scene's
// packed triangles does not depend on how they were handed out.
constexpr size_t kTriangleHashBlock = 4096;

// Packs the triangles [first, first + count) of the packing order (`order`
// names scene indices; null: the scene's own) shifted by -shift into out[0,
// count) and out_lo (null: the lo parts are not kept), on every core; first
// a multiple of kTriangleHashBlock. Appends the ContentHash of each block of
// kTriangleHashBlock triangles (hi and lo parts), in order, to `hashes`.
void pack_triangles(const Scene& scene, const Vec3& shift, const std::vector<clrt_i32>* order,
                    const std::vector<clrt_i32>& material_entries, size_t first, size_t count, clrt_triangle* out,
                    clrt_triangle_lo* out_lo, std::vector<uint64_t>& hashes);

}  // namespace clrt
