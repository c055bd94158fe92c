/* clrt_layout.h - data layouts shared by the host (C++17) and the kernel
 * (OpenCL C 1.2). This is the ONLY file compiled by both sides; it holds
 * plain data, no shading logic. Every member is a 32-bit scalar so that the
 * layout is identical on both sides without alignment pragmas; the host
 * static_asserts sizes and offsets (host/scene_buffers.cpp).
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

#define CLRT_LIGHT_AMBIENT 0
#define CLRT_LIGHT_POINT 1
#define CLRT_LIGHT_DIRECTIONAL 2

/* Largest recursion depth accepted anywhere (scene files, CLI, kernels).
 * The generic kernel's explicit stack has CLRT_MAX_DEPTH + 1 frames. */
#define CLRT_MAX_DEPTH 64

typedef struct clrt_sphere {
  clrt_f32 center[3];    /* hi parts */
  clrt_f32 radius;       /* hi part */
  clrt_f32 center_lo[3]; /* center - (double)center_hi */
  clrt_f32 radius_lo;
  clrt_f32 color[3]; /* 0..255 */
  clrt_f32 specular; /* -1 = matte */
  clrt_f32 reflective;
  clrt_f32 pad[3];
} clrt_sphere; /* 64 bytes */

typedef struct clrt_light {
  clrt_i32 type; /* CLRT_LIGHT_* */
  clrt_f32 intensity;
  clrt_f32 vec[3];    /* position (point) or direction (directional), hi */
  clrt_f32 vec_lo[3]; /* lo parts */
} clrt_light; /* 32 bytes */

typedef struct clrt_params {
  clrt_i32 width; /* full image size in pixels */
  clrt_i32 height;
  clrt_i32 depth; /* recursion depth (generic kernel) */
  clrt_i32 n_spheres;
  clrt_i32 n_lights;
  clrt_i32 pad0;
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
  clrt_f32 pad1;
} clrt_params; /* 168 bytes */

/* Per-pixel ray counters written when CLRT_COUNT_RAYS is defined. */
typedef struct clrt_ray_counts {
  clrt_i32 primary;
  clrt_i32 shadow;
  clrt_i32 reflection;
  clrt_i32 sphere_tests;
} clrt_ray_counts;

#endif /* CLRT_LAYOUT_H */
