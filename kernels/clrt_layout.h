/* clrt_layout.h - data layouts and codes shared by the host (C++17) and the
 * kernel (OpenCL C 1.2). With clrt_kernel_args.h (the render kernel's
 * argument list) it is one of the two files compiled by both sides; it
 * holds plain data, no shading logic. Every member is a 32-bit scalar so that
 * the layout is identical on both sides without alignment pragmas; the host
 * static_asserts that CLRT_LAYOUT_FIELDS covers every byte of every struct
 * (host/render/scene_buffers.hpp) and the layout test compares the kernel
 * compiler's offsets with the host's (kernels/layout_probe.cl).
 *
 * Doubles from the scene are stored as a float "hi" part plus a float "lo"
 * remainder (hi + lo == value to ~48 bits), so float kernels use hi only,
 * compensated kernels use both and fp64 kernels rebuild a double. */
#ifndef CLRT_LAYOUT_H
#define CLRT_LAYOUT_H

#ifdef __OPENCL_VERSION__
typedef float clrt_f32;
typedef int clrt_i32;
#else
#include <cstdint>
typedef float clrt_f32;
typedef std::int32_t clrt_i32;
#endif

/* Precision variants: the value of -DCLRT_PRECISION, and the host's
 * Precision enum (host/render/precision.hpp) takes its values from here. */
#define CLRT_PRECISION_NAIVE 0
#define CLRT_PRECISION_STABLE 1
#define CLRT_PRECISION_ROBUST 2
#define CLRT_PRECISION_FAST 3
#define CLRT_PRECISION_FP64 4

/* clrt_light.type, and the entries of -DCLRT_LIGHT_TYPES. */
#define CLRT_LIGHT_AMBIENT 0
#define CLRT_LIGHT_POINT 1
#define CLRT_LIGHT_DIRECTIONAL 2

/* Bits of the device status word (the kernel's `status` argument, one int
 * per launch, zeroed by the host before it): what a work-item found wrong
 * with its own run. The host turns a set bit into an error and drops the
 * tile (host/render/device_renderer.cpp). */
#define CLRT_STATUS_LOOP_LIMIT 1 /* the driver ended the work-item's loops early (clrt_device_status.h) */

/* Largest recursion depth accepted anywhere (scene files, CLI, kernels).
 * The generic kernel's explicit stack has CLRT_MAX_DEPTH + 1 frames. */
#define CLRT_MAX_DEPTH 64

/* Largest supersampling rate accepted anywhere (--spp N: N x N samples per
 * pixel; clrt_params.spp). */
#define CLRT_MAX_SPP 16

typedef struct clrt_sphere {
  clrt_f32 center[3];    /* hi parts */
  clrt_f32 radius;       /* hi part */
  clrt_f32 center_lo[3]; /* center - (double)center_hi */
  clrt_f32 radius_lo;
  clrt_f32 color[3]; /* 0..255 */
  clrt_f32 specular; /* -1 = matte */
  clrt_f32 reflective;
  /* robust kernel: 1 = compensated arithmetic for this sphere, 0 = the
   * cheap path (the host's rule: host/render/conditioning.hpp) */
  clrt_i32 compensated;
  /* chapter 5: the share of unreflected light that passes through (0 = an
   * opaque sphere), the index inside, and the index of the medium around the
   * sphere (the smallest transparent sphere containing it, else 1; the
   * host's outside_medium(), host/render/scene_buffers.cpp) */
  clrt_f32 transparency;
  clrt_f32 refractive_index;
  clrt_f32 outside_index;
  clrt_f32 pad[3];
} clrt_sphere; /* 80 bytes */

typedef struct clrt_light {
  clrt_i32 type; /* CLRT_LIGHT_* */
  clrt_f32 intensity;
  clrt_f32 vec[3];    /* position (point) or direction (directional), hi */
  clrt_f32 vec_lo[3]; /* lo parts */
  /* Directional: the shadow ray's t_min is epsilon x this, a power of two
   * (Light::shadow_t_min: the book's range, in units of the direction the
   * scene gave); 1 for other lights. */
  clrt_f32 t_min_scale;
  clrt_f32 pad[3];
} clrt_light; /* 48 bytes */

typedef struct clrt_params {
  clrt_i32 width; /* full image size in pixels */
  clrt_i32 height;
  clrt_i32 depth; /* recursion depth (generic kernel) */
  clrt_i32 n_spheres;
  clrt_i32 n_lights;
  clrt_i32 spp; /* N: N x N samples per pixel, averaged (1 = one ray through the centre) */
  clrt_f32 viewport[2];
  clrt_f32 proj_d;
  clrt_f32 epsilon;
  clrt_f32 origin[3]; /* camera position, hi */
  clrt_f32 origin_lo[3];
  clrt_f32 rotation[9]; /* row-major 3x3 */
  clrt_f32 rotation_lo[9];
  clrt_f32 background[3];
  clrt_f32 proj_d_lo; /* lo parts of the camera scalars (fp64 builds) */
  clrt_f32 viewport_lo[2];
  clrt_f32 epsilon_lo;
  clrt_f32 camera_medium; /* refractive index around the camera (1 = air) */
  clrt_i32 n_planes;      /* chapter 5's other primitives */
  clrt_i32 n_triangles;
  clrt_i32 adaptive;            /* adaptive supersampling (scene/sampling.hpp): 1 = on */
  clrt_f32 adaptive_threshold;  /* its T, in 8-bit levels */
  /* The ray tree's weight cut-off (host/scene/ray_tree.hpp): a child ray
   * whose weight (the product of the shares along its path) is below it is
   * not traced; 0 = every ray down to the depth. */
  clrt_f32 min_weight;
} clrt_params; /* 188 bytes */

/* The material of a plane or triangle (spheres carry theirs inline). */
typedef struct clrt_material {
  clrt_f32 color[3]; /* 0..255 */
  clrt_f32 specular; /* -1 = matte */
  clrt_f32 reflective;
  clrt_f32 pad[3];
} clrt_material; /* 32 bytes */

/* An infinite plane through `point` with unit `normal` (hi and lo parts). */
typedef struct clrt_plane {
  clrt_f32 point[3];
  clrt_i32 material; /* index into the materials */
  clrt_f32 normal[3];
  clrt_f32 pad;
  clrt_f32 point_lo[3];
  clrt_f32 pad_lo;
  clrt_f32 normal_lo[3];
  clrt_f32 pad_lo2;
} clrt_plane; /* 64 bytes */

/* A triangle: its vertices (hi parts: the lo parts are clrt_triangle_lo's),
 * its material and its index in the scene's list (its id is TRIANGLE_ID0 +
 * index). Where the
 * kernel walks a hierarchy the buffer holds the triangles in the order of
 * its entries, which name their place in it (the host's
 * order_triangles()), and triangle_slots maps an index to that place: a
 * walk then reads them in the order it tests them, instead of a cache miss
 * away each (docs/results/wide-hierarchy.md). */
typedef struct clrt_triangle {
  clrt_f32 v0[3];
  clrt_i32 material; /* index into the materials */
  clrt_f32 v1[3];
  clrt_i32 index; /* in the scene's list of triangles */
  clrt_f32 v2[3];
  clrt_f32 pad;
} clrt_triangle; /* 48 bytes */

/* The lo parts of a triangle's vertices, in a buffer of their own beside
 * the triangles (same order): only fp64 builds read them, so float builds
 * get a one-element stand-in, and a float walk reads 48 bytes a triangle,
 * not 96 (the device holds 183 MiB less at 4 million triangles). */
typedef struct clrt_triangle_lo {
  clrt_f32 v0_lo[3];
  clrt_f32 v1_lo[3];
  clrt_f32 v2_lo[3];
  clrt_f32 pad[3];
} clrt_triangle_lo; /* 48 bytes */
/* Whether the variant of CLRT_PRECISION_* code `precision` reads them: the
 * one rule, read by the host (which uploads them only then:
 * DeviceRenderer::prepare()) and the kernel (TRIANGLE_LO, clrt_scene.h). */
#define CLRT_READS_TRIANGLE_LO(precision) ((precision) == CLRT_PRECISION_FP64)

/* The AOV layers buffer (-DCLRT_OUT_LAYERS, kernels/clrt_layers.h): floats
 * per pixel, and where each layer starts among them: the distance along the
 * camera ray (0 on a miss: the host writes +inf), the unit normal (3), the
 * hit's colour / 255 (3), and the primitive id's int bits (-1: a miss). */
#define CLRT_LAYER_FLOATS 8
#define CLRT_LAYER_DISTANCE 0
#define CLRT_LAYER_NORMAL 1
#define CLRT_LAYER_ALBEDO 4
#define CLRT_LAYER_ID 7

/* Per-pixel ray counters written when CLRT_COUNT_RAYS is defined. */
typedef struct clrt_ray_counts {
  clrt_i32 primary;
  clrt_i32 shadow;
  clrt_i32 reflection;
  clrt_i32 sphere_tests;
  clrt_i32 refraction;
} clrt_ray_counts;

/* A node of the bounding volume hierarchy over the scene's primitives as
 * the host builds it (host/render/bvh.hpp; the kernel walks its wide form,
 * clrt_wide_node below). Its box is
 * padded and rounded outward on the host, so that no rounding of a kernel's
 * primitive or box test lets the hierarchy change which primitive a ray hits.
 * A leaf lists `count` (> 0) entries of the primitive list from `first`; an
 * inner node has its two children at `first` and `first + 1`, and `count` is
 * -(1 + the axis it was split on). */
typedef struct clrt_bvh_node {
  clrt_f32 lower[3];
  clrt_i32 first;
  clrt_f32 upper[3];
  clrt_i32 count;
} clrt_bvh_node; /* 32 bytes */

/* The boxes' padding per precision variant, as a fraction of the scale of
 * a test: a float primitive test errs by a few ulps of the distances it
 * works with, which are at most |C| + r + |O| in each coordinate (C, r a
 * primitive's centre or vertices and size, O the ray's origin, all relative
 * to the packing origin). The host pads each primitive's box by the factor
 * times max|C| + r; the walk widens every box by the factor times max|O| for
 * the ray at hand (kernels/clrt_bvh.h). Stable and robust: 2^-17, 64 ulps of
 * float (the tests' worst cases add up to ~20); fast, where the hierarchy
 * holds spheres: their tests take the native square root and division,
 * whose accuracy the device chooses, 2^-11; fast without spheres: 2^-17, as
 * the other float variants (its triangle tests use no native function, and
 * -cl-fast-relaxed-math's division errs by a few ulps: the [bvh] tests
 * check it); fp64 2^-40. (host/render/bvh.hpp) */
#define CLRT_BVH_PAD_FLOAT 0x1p-17
#define CLRT_BVH_PAD_FAST 0x1p-11
#define CLRT_BVH_PAD_FP64 0x1p-40
/* The factor of CLRT_PRECISION_* code `precision` for a hierarchy that
 * holds spheres (`spheres` nonzero) or not: the one mapping, read by the
 * host (bvh_padding_scale()) and the kernel (CLRT_RAY_PAD, whose
 * CLRT_BVH_SPHERES the host passes). */
#define CLRT_BVH_PAD(precision, spheres)                                       \
  ((precision) == CLRT_PRECISION_FP64                 ? CLRT_BVH_PAD_FP64 \
   : (precision) == CLRT_PRECISION_FAST && (spheres) ? CLRT_BVH_PAD_FAST \
                                                      : CLRT_BVH_PAD_FLOAT)

/* Primitive list entries: the primitive's kind in the top bits, its index in
 * the scene's list of that kind below. Planes are never in the hierarchy
 * (unbounded). A hit is reported as one id over all primitives: spheres
 * 0..S-1, then planes S..S+P-1, then triangles S+P.. (the reference numbers
 * them the same way). */
#define CLRT_PRIMITIVE_SPHERE 0
#define CLRT_PRIMITIVE_TRIANGLE 1
#define CLRT_PRIMITIVE_KIND_SHIFT 28
#define CLRT_PRIMITIVE_INDEX_MASK 0x0fffffff
/* A sphere entry of the hierarchy's leaves, one per entry of the primitive
 * list and in its order (entries of other kinds leave theirs unused): the
 * centre and radius a float walk tests, read in the order the walk reads the
 * entries instead of from the scene's list, where 80-byte records in scene
 * order made the load of each tested sphere a cache miss (~35% of the kernel's
 * time on 100 000 spheres: docs/results/wide-hierarchy.md). The radius's sign
 * bit is the sphere's clrt_sphere.compensated flag. */
typedef struct clrt_leaf_sphere {
  clrt_f32 center[3]; /* hi parts, as clrt_sphere's */
  clrt_f32 radius;    /* negative: compensated */
} clrt_leaf_sphere; /* 16 bytes */

/* Deepest leaf the host builds (in the binary tree). */
#define CLRT_BVH_MAX_DEPTH 48

/* The hierarchy the kernel walks: the binary tree above collapsed into
 * nodes of up to CLRT_BVH_WIDTH children (host/render/wide_bvh.hpp), whose
 * boxes are stored axis by axis, one value per child (structure of arrays),
 * so that a ray is tested against all of a node's children in one SIMD step
 * (kernels/clrt_bvh.h). The host passes the width it was compiled with to
 * the kernel (-DCLRT_BVH_WIDTH, build_options.cpp): 4 or 8.
 * Child k: count[k] > 0 is a leaf listing count[k] entries of the primitive
 * list from child[k]; count[k] < 0 an inner node, nodes[child[k]]; 0 an
 * empty slot (or an empty leaf), never entered. Its box lower[a][k] ..
 * upper[a][k] on axis a is the binary node's, padded as described above. */
#ifndef CLRT_BVH_WIDTH /* 8: measured faster than 4 (docs/results/wide-hierarchy.md) */
#define CLRT_BVH_WIDTH 8
#endif
typedef struct clrt_wide_node {
  clrt_f32 lower[3][CLRT_BVH_WIDTH];
  clrt_f32 upper[3][CLRT_BVH_WIDTH];
  clrt_i32 child[CLRT_BVH_WIDTH];
  clrt_i32 count[CLRT_BVH_WIDTH];
} clrt_wide_node; /* 32 * CLRT_BVH_WIDTH bytes */
/* A wide node is at least one binary level below its parent, so inner
 * nodes are at most CLRT_BVH_MAX_DEPTH - 2 wide levels down; a walk's stack
 * holds the children it has yet to visit, at most CLRT_BVH_WIDTH - 1 per
 * level above the current node plus the current node's CLRT_BVH_WIDTH:
 * CLRT_BVH_STACK entries always suffice. */
#define CLRT_BVH_STACK (CLRT_BVH_MAX_DEPTH * (CLRT_BVH_WIDTH - 1))

/* Every member of every struct above, in declaration order, as
 * FIELD(struct, member): the one list that the host's static_asserts, the
 * kernel's layout probe and the layout test walk. A member added above but
 * not here leaves a gap that the host's static_asserts report. */
#define CLRT_LAYOUT_FIELDS(FIELD)      \
  FIELD(clrt_sphere, center)           \
  FIELD(clrt_sphere, radius)           \
  FIELD(clrt_sphere, center_lo)        \
  FIELD(clrt_sphere, radius_lo)        \
  FIELD(clrt_sphere, color)            \
  FIELD(clrt_sphere, specular)         \
  FIELD(clrt_sphere, reflective)       \
  FIELD(clrt_sphere, compensated)      \
  FIELD(clrt_sphere, transparency)     \
  FIELD(clrt_sphere, refractive_index) \
  FIELD(clrt_sphere, outside_index)    \
  FIELD(clrt_sphere, pad)              \
  FIELD(clrt_light, type)              \
  FIELD(clrt_light, intensity)         \
  FIELD(clrt_light, vec)               \
  FIELD(clrt_light, vec_lo)            \
  FIELD(clrt_light, t_min_scale)       \
  FIELD(clrt_light, pad)               \
  FIELD(clrt_params, width)            \
  FIELD(clrt_params, height)           \
  FIELD(clrt_params, depth)            \
  FIELD(clrt_params, n_spheres)        \
  FIELD(clrt_params, n_lights)         \
  FIELD(clrt_params, spp)              \
  FIELD(clrt_params, viewport)         \
  FIELD(clrt_params, proj_d)           \
  FIELD(clrt_params, epsilon)          \
  FIELD(clrt_params, origin)           \
  FIELD(clrt_params, origin_lo)        \
  FIELD(clrt_params, rotation)         \
  FIELD(clrt_params, rotation_lo)      \
  FIELD(clrt_params, background)       \
  FIELD(clrt_params, proj_d_lo)        \
  FIELD(clrt_params, viewport_lo)      \
  FIELD(clrt_params, epsilon_lo)       \
  FIELD(clrt_params, camera_medium)    \
  FIELD(clrt_params, n_planes)         \
  FIELD(clrt_params, n_triangles)      \
  FIELD(clrt_params, adaptive)         \
  FIELD(clrt_params, adaptive_threshold) \
  FIELD(clrt_params, min_weight)       \
  FIELD(clrt_material, color)          \
  FIELD(clrt_material, specular)       \
  FIELD(clrt_material, reflective)     \
  FIELD(clrt_material, pad)            \
  FIELD(clrt_plane, point)             \
  FIELD(clrt_plane, material)          \
  FIELD(clrt_plane, normal)            \
  FIELD(clrt_plane, pad)               \
  FIELD(clrt_plane, point_lo)          \
  FIELD(clrt_plane, pad_lo)            \
  FIELD(clrt_plane, normal_lo)         \
  FIELD(clrt_plane, pad_lo2)           \
  FIELD(clrt_triangle, v0)             \
  FIELD(clrt_triangle, material)       \
  FIELD(clrt_triangle, v1)             \
  FIELD(clrt_triangle, index)          \
  FIELD(clrt_triangle, v2)             \
  FIELD(clrt_triangle, pad)            \
  FIELD(clrt_triangle_lo, v0_lo)       \
  FIELD(clrt_triangle_lo, v1_lo)       \
  FIELD(clrt_triangle_lo, v2_lo)       \
  FIELD(clrt_triangle_lo, pad)         \
  FIELD(clrt_ray_counts, primary)      \
  FIELD(clrt_ray_counts, shadow)       \
  FIELD(clrt_ray_counts, reflection)   \
  FIELD(clrt_ray_counts, sphere_tests) \
  FIELD(clrt_ray_counts, refraction)   \
  FIELD(clrt_bvh_node, lower)          \
  FIELD(clrt_bvh_node, first)          \
  FIELD(clrt_bvh_node, upper)          \
  FIELD(clrt_bvh_node, count)          \
  FIELD(clrt_wide_node, lower)         \
  FIELD(clrt_wide_node, upper)         \
  FIELD(clrt_wide_node, child)         \
  FIELD(clrt_wide_node, count)        \
  FIELD(clrt_leaf_sphere, center)      \
  FIELD(clrt_leaf_sphere, radius)

#endif /* CLRT_LAYOUT_H */
