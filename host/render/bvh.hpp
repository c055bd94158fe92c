// bvh.hpp - the bounding volume hierarchy over a scene's spheres, built on
// the host and walked by the kernel (kernels/clrt_bvh.h) in place of testing
// every sphere: binned surface-area heuristic, at most kBvhLeafSize
// primitives per leaf where a split pays, never deeper than
// CLRT_BVH_MAX_DEPTH; the binary tree is then collapsed into the wide nodes
// the kernel walks (wide_bvh.hpp).
//
// The boxes are padded and rounded outward so that the hierarchy never
// changes which primitive a ray hits, at any precision variant
// (tests/render/test_bvh.cpp compares BVH and brute-force images). A float
// sphere or triangle test can report a hit only for a ray that passes within
// its error of the primitive, a few ulps of the distances it works with:
// |O - C| and r, at most max|C| + r + max|O| in a coordinate (C, r the
// centre and radius or the vertices, O the ray's origin, relative to the
// packing origin). So each box is padded by a factor of max|C| + r here, and
// the walk widens every box by the same factor of max|O| for each ray
// (kernels/clrt_bvh.h), the factor per variant (CLRT_BVH_PAD_*,
// clrt_layout.h):
//  - stable, robust (perpendicular-distance discriminant, watertight
//    triangles): 2^-17, 64 ulps of float, where the worst cases of the
//    tests add up to ~20 (the ulps of each step, with |g| <= sqrt(3) times
//    the coordinates' sum); fp64 2^-40;
//  - fast (native square root and division, whose accuracy the device
//    chooses): 2^-11;
//  - naive (the book's b^2 - 4ac): a few ulps of |O - C|^2 in c, so grazing
//    rays "hit" up to ~2^-22 E^2 / r away from a sphere of radius r (E the
//    scene's extent, camera included): padded by that too. Its boxes are
//    large; Accel::Auto keeps testing every sphere.
// Before, every box was padded by 2^-16 E (fast: 2^-12 E), E the scene's
// extent: a scene with the book's floor (radius 5 000) padded spheres of
// radius 0.01 near the camera by 0.08 (robust) or 1.2 (fast), and rays tested
// 1.4x (robust) and 22x (fast) the spheres (docs/results/wide-hierarchy.md).
// Since |C| + r and |O| are at most E, no box is padded more than then for
// any ray (robust; fast and fp64 at most 4x), and most by far less.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "clrt_layout.h"
#include "render/precision.hpp"
#include "scene/scene.hpp"

namespace clrt {

// Which spheres a ray tests: all of them, or those the hierarchy reaches.
enum class Accel { Auto, None, Bvh };
// "auto", "none", "bvh"; UserError naming --accel otherwise.
Accel parse_accel(const std::string& name);
std::string accel_name(Accel accel);

// Auto uses the hierarchy from this many spheres on: below it testing every
// sphere is faster (measured, docs/results/archive.md).
constexpr size_t kBvhMinSpheres = 32;
// (the count: spheres and triangles, the primitives the hierarchy holds;
// planes are unbounded and always tested, bvh_primitive_count())
bool uses_bvh(Accel accel, size_t primitive_count, Precision precision);
size_t bvh_primitive_count(const Scene& scene);

constexpr int kBvhLeafSize = 4;  // a leaf of more only where no split pays (or at the depth limit)
// The largest leaf, whatever the SAH says (coincident primitives are split by
// count); only the depth limit can make a larger one (2^47 leaves away).
constexpr int kBvhMaxLeafSize = 4 * kBvhLeafSize;
constexpr int kBvhBins = 16;  // SAH candidates per axis

struct Bvh {
  std::vector<clrt_bvh_node> nodes;  // the binary tree; nodes[0] is the root
  std::vector<clrt_wide_node> wide;  // the same tree collapsed (wide_bvh.hpp): what the kernel walks
  std::vector<clrt_i32> primitives;  // the leaves' entries (kind << shift | index; see below)
  // A triangle entry's index is its place in this list of the scene's
  // triangle indices, the order in which the leaves hold them: the device's
  // triangles are stored so (clrt_layout.h, clrt_triangle), and a walk reads
  // them in the order it tests them. A sphere entry's is the scene's index.
  std::vector<clrt_i32> triangle_order;
  int depth = 0;             // deepest leaf of the binary tree, the root being 0
  double padding_scale = 0;  // CLRT_BVH_PAD_*: a box is padded by this times max|C| + r (naive: more)
  // What the device holds: the wide nodes and the entries.
  size_t bytes() const { return wide.size() * sizeof(clrt_wide_node) + primitives.size() * sizeof(clrt_i32); }
};

// The factor of the boxes' padding for `precision`, in a hierarchy that
// holds spheres or not (CLRT_BVH_PAD).
double bvh_padding_scale(Precision precision, bool spheres);

// The hierarchy of `scene`'s spheres and triangles (empty scene: one empty
// leaf; planes are never in it), in
// coordinates relative to `origin`, as the kernel sees them
// (render/scene_buffers.hpp: packing_origin()). Large subtrees are built on
// up to `threads` threads (0: one per hardware thread); the result is the
// same for every thread count.
// The inverse of bvh.triangle_order: each scene triangle's place in it
// (the kernel's triangle_slots).
std::vector<clrt_i32> triangle_slots(const Bvh& bvh);

Bvh build_bvh(const Scene& scene, Precision precision, Vec3 origin = {}, int threads = 0);

}  // namespace clrt
