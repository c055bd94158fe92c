/* clrt_config.h - the kernel's build-time configuration: every -D option the
 * host passes (all made in one place, host/render/build_options.cpp, from the
 * config and the scene's KernelFeatures), their defaults, and the switches
 * derived from them.
 *
 *   CLRT_PRECISION       CLRT_PRECISION_* of clrt_layout.h (default robust)
 *   CLRT_SPECIALIZED     scene-specific build: the options below are constants
 *   CLRT_N_SPHERES, CLRT_N_LIGHTS  specialized, small scenes only: constant
 *                        loop bounds, loops unrolled (the host leaves them out
 *                        past a bound, kMaxUnrolled* in
 *                        host/render/kernel_features.hpp)
 *   CLRT_LIGHT_TYPES     with the counts: each light's CLRT_LIGHT_*, "0,1,2"
 *   CLRT_HAS_AMBIENT, CLRT_HAS_POINT, CLRT_HAS_DIRECTIONAL,
 *   CLRT_HAS_SPECULAR, CLRT_HAS_REFLECTIVE,
 *   CLRT_HAS_TRANSPARENT, CLRT_HAS_PLANES, CLRT_HAS_TRIANGLES
 *                        (0/1; generic build: all 1)
 *   CLRT_DEPTH_BOUND     the deepest recursion the program serves (the
 *                        pending rays of the tree walk take one slot per
 *                        level; default CLRT_MAX_DEPTH)
 *   CLRT_COMPENSATED_SPHERES  specialized robust builds: 0 when no sphere
 *                        needs compensated arithmetic, 1 when every one does
 *   CLRT_COMPENSATED_FLAGS  with the counts, when the spheres differ: each
 *                        sphere's clrt_sphere.compensated, "0,0,0,1"; with
 *                        neither, each sphere's flag decides at run time
 *                        (clrt_sphere.h)
 *   CLRT_BVH             walk the hierarchy (clrt_bvh.h) instead of testing
 *                        every sphere (the host's Accel, render/bvh.hpp)
 *   CLRT_BVH_SPHERES     with it: 0 when the hierarchy holds no sphere (its
 *                        boxes' padding, CLRT_BVH_PAD; default 1)
 *   CLRT_COUNT_RAYS      write per-pixel ray counters
 *   CLRT_OUT_RGBA8       store 8-bit RGBA (the canvas rule) instead of float
 *                        RGB (clrt_lanes.h: TO_CANVAS)
 *   CLRT_OUT_CLASSES     store each pixel's hit sphere and shadow mask
 *   CLRT_OUT_LAYERS      store each pixel's AOV layers (clrt_layers.h; an
 *                        extra kernel argument, the layers buffer:
 *                        clrt_kernel_args.h)
 *   CLRT_SUBSAMPLE       the book's subsampling (host/scene/sampling.hpp):
 *                        0 off (default), CLRT_SUBSAMPLE_SHADE or
 *                        CLRT_SUBSAMPLE_INTERPOLATE; a frame is two launches
 *                        per tile (trace.cl, clrt_subsample.h)
 *   CLRT_LANES           pixels per work-item: 1 (when absent), 4, 8 or 16;
 *                        the host picks it (default_lanes(), build_options.hpp)
 *   CLRT_PACKET_ROWS     rows of the work-item's block of pixels (1 when
 *                        absent; packet_rows(), build_options.hpp)
 *
 * Measurement knobs, never set by the host (--cl-options, see
 * docs/developer/benchmarking.md): CLRT_SHADOW_ALL_SPHERES, CLRT_LIB_POW, and
 * CLRT_DEPTH (with CLRT_SPECIALIZED: the recursion depth as a constant;
 * the host passes it at run time, which measured the same). */
#ifndef CLRT_CONFIG_H
#define CLRT_CONFIG_H

#include "clrt_layout.h"

#ifndef CLRT_PRECISION
#define CLRT_PRECISION CLRT_PRECISION_ROBUST
#endif

/* Robust and fast modes know which sphere a secondary ray starts on: for it
 * |f|^2 - r^2 is exactly 0, so its roots are exactly 0 and 2b/a. Computing
 * them from a rounded hit point instead is what lets float32 rays hit their
 * own sphere (shadow acne on the radius-5000 floor). */
#if CLRT_PRECISION == CLRT_PRECISION_ROBUST || CLRT_PRECISION == CLRT_PRECISION_FAST
#define CLRT_SELF_ROOTS 1
#else
#define CLRT_SELF_ROOTS 0
#endif

/* Scene counts and recursion depth: constants in a specialized build (counts
 * only for small scenes), else read from the clrt_params at run time. */
#if defined(CLRT_SPECIALIZED) && defined(CLRT_N_SPHERES)
#define CLRT_SPHERE_COUNT(params) CLRT_N_SPHERES
#define CLRT_LIGHT_COUNT(params) CLRT_N_LIGHTS
#else
#define CLRT_SPHERE_COUNT(params) ((params)->n_spheres)
#define CLRT_LIGHT_COUNT(params) ((params)->n_lights)
#endif
/* The recursion depth is a constant where the host compiles it in
 * (CLRT_DEPTH); otherwise it is read at run time, bounded by the slots of
 * the pending rays (clrt_ray_tree.h): CLRT_DEPTH_BOUND where the host gives one
 * (one program then serves every depth up to it), else CLRT_MAX_DEPTH. */
#if defined(CLRT_SPECIALIZED) && defined(CLRT_DEPTH)
#define CLRT_RECURSION_DEPTH(params) CLRT_DEPTH
#define CLRT_STACK_FRAMES (CLRT_DEPTH + 1)
#else
#ifndef CLRT_DEPTH_BOUND
#define CLRT_DEPTH_BOUND CLRT_MAX_DEPTH
#endif
#define CLRT_RECURSION_DEPTH(params) (min((params)->depth, CLRT_DEPTH_BOUND))
#define CLRT_STACK_FRAMES (CLRT_DEPTH_BOUND + 1)
#endif

/* Supersampling: N x N samples per pixel (clrt_params.spp), always read at
 * run time, so one program serves every N; clamped to [1, CLRT_MAX_SPP]
 * (the host validates it). */
#define CLRT_SAMPLES_PER_AXIS(params) (clamp((params)->spp, 1, CLRT_MAX_SPP))

/* The generic build has every feature; a specialized one gets each from the
 * host (0 or 1). */
#ifndef CLRT_SPECIALIZED
#ifndef CLRT_HAS_AMBIENT
#define CLRT_HAS_AMBIENT 1
#endif
#ifndef CLRT_HAS_POINT
#define CLRT_HAS_POINT 1
#endif
#ifndef CLRT_HAS_DIRECTIONAL
#define CLRT_HAS_DIRECTIONAL 1
#endif
#ifndef CLRT_HAS_SPECULAR
#define CLRT_HAS_SPECULAR 1
#endif
#ifndef CLRT_HAS_REFLECTIVE
#define CLRT_HAS_REFLECTIVE 1
#endif
#ifndef CLRT_HAS_TRANSPARENT
#define CLRT_HAS_TRANSPARENT 1
#endif
#ifndef CLRT_HAS_PLANES
#define CLRT_HAS_PLANES 1
#endif
#ifndef CLRT_HAS_TRIANGLES
#define CLRT_HAS_TRIANGLES 1
#endif
#endif

#ifndef CLRT_BVH_SPHERES
#define CLRT_BVH_SPHERES 1
#endif

#ifndef CLRT_SUBSAMPLE
#define CLRT_SUBSAMPLE 0
#endif
#define CLRT_SUBSAMPLE_SHADE 1
#define CLRT_SUBSAMPLE_INTERPOLATE 2

#ifndef CLRT_LANES
#define CLRT_LANES 1
#endif
#ifndef CLRT_PACKET_ROWS
#define CLRT_PACKET_ROWS 1
#endif
#define CLRT_PACKET_COLS (CLRT_LANES / CLRT_PACKET_ROWS)
#if CLRT_PACKET_COLS * CLRT_PACKET_ROWS != CLRT_LANES
#error "CLRT_PACKET_ROWS must divide CLRT_LANES"
#endif

/* Helpers are forced inline (PoCL otherwise keeps intersect() out of line,
 * a call per ray-sphere test), and specialized builds of small scenes unroll
 * the loops whose bounds are constants there. */
#define CLRT_INLINE inline __attribute__((always_inline))
#if defined(CLRT_SPECIALIZED) && defined(CLRT_N_SPHERES)
#define CLRT_UNROLL _Pragma("unroll")
#else
#define CLRT_UNROLL
#endif

#endif /* CLRT_CONFIG_H */
