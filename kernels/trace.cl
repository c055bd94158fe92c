/* trace.cl - the render kernel: primary ray, shadow rays and bounded-depth
 * reflections with an explicit stack (no recursion), per pixel.
 *
 * A work-item shades a block of CLRT_LANES pixels, CLRT_PACKET_COLS wide and
 * CLRT_PACKET_ROWS high, one per SIMD lane (clrt_lanes.h; lanes beyond the
 * tile's edge are traced and not stored); every lane runs exactly the
 * per-pixel algorithm - its own ray, its own explicit stack (lane j of each
 * frame) - with branches turned into per-lane masks.
 *
 * The parts, each included once (host/cl/kernel_source.cpp expands them):
 *   clrt_layout.h     structs and codes shared with the host
 *   clrt_config.h     the -D options from the host, defaults, derived switches
 *   clrt_lanes.h      the precision's scalar, lane types and mask helpers
 *   clrt_math.h       3-vectors, hi/lo values, per-precision arithmetic
 *   clrt_intersect.h  ray-sphere roots, closest hit and any hit
 *   clrt_bvh.h        the same queries through the hierarchy (-DCLRT_BVH)
 *   clrt_shade.h      hit material, ComputeLighting, reflected rays
 * This file holds the camera rays (N x N per pixel with supersampling), the
 * bounce loop, the unwinding of the stack, the average and the stores. */
#include "clrt_config.h"
#include "clrt_intersect.h"
#include "clrt_lanes.h"
#include "clrt_layout.h"
#include "clrt_math.h"
#include "clrt_shade.h"

/* One camera ray per lane, through the viewport point (dx, dy) (before the
 * camera rotation m), and its bounded-depth reflections with an explicit
 * stack: the book's TraceRay without recursion. Returns its colour; where
 * `classify` is set (a pixel's first sample) its primary hit and blocked
 * lights go to *hit_id and *shadow_mask. */
CLRT_INLINE vec3 trace_camera_ray(const lreal dx, const lreal dy, const real* m, const real dz, const vec3 camera,
                                  const real epsilon, const vec3 background, const int depth, const int classify,
                                  __global const clrt_params* params, __global const clrt_sphere* spheres,
                                  __global const clrt_light* lights, __global const clrt_bvh_node* nodes,
                                  __global const int* primitives, lint* hit_id, lint* shadow_mask,
                                  lane_ray_counts* counts) {
  vec3 D = v3(m[0] * dx + m[1] * dy + m[2] * dz, m[3] * dx + m[4] * dy + m[5] * dz, m[6] * dx + m[7] * dy + m[8] * dz);
  vec3 O = camera;
  COUNT_IN_LANES(counts->primary, MASK_TRUE, 1); /* one primary ray per lane and sample */

  /* Explicit stack: one frame (local colour, reflectivity) per bounce that
   * continues; unwound below as (1 - r) * local + r * reflected. A frame is
   * pushed only by a bounce that continues, so frame k always belongs to
   * bounce k and sp (per lane) is the number of frames. */
  vec3 stack_local[CLRT_STACK_FRAMES];
  lreal stack_r[CLRT_STACK_FRAMES];
  lint sp = 0;
  vec3 result = background;
  real tmin = 1;          /* the same for all lanes: 1 for primary rays, epsilon after */
  lint self = -1;         /* sphere the lane's current ray starts on */
  lint alive = MASK_TRUE; /* lanes whose ray of this bounce exists */

  for (int bounce = 0; bounce <= depth; ++bounce) {
    lreal t;
    lint tests = 0;
    const lint hit =
        closest_intersection(&O, &D, tmin, REAL_INFINITY, self, params, spheres, nodes, primitives, &t, &tests);
    COUNT_IN_LANES(counts->sphere_tests, alive, tests);
    const lint miss = alive & (hit < 0);
    result = vsel(miss, background, result);
    alive &= !miss;
    if (!ANY(alive)) break;

    vec3 C, color;
    lreal specular, reflective;
    hit_material(hit, params, spheres, &C, &color, &specular, &reflective);
    const vec3 Pt = vadd(O, vscale(t, D));
    vec3 N = vsub(Pt, C);
    N = vscale(1 / vlen(N), N);
    const vec3 V = vneg(D);
    const int primary_classified = classify && bounce == 0;
    if (primary_classified) *hit_id = alive ? hit : *hit_id;

    const lreal intensity = compute_lighting(&Pt, &N, &V, specular, hit, alive, epsilon, primary_classified, params,
                                             spheres, lights, nodes, primitives, shadow_mask, counts);
    const vec3 local_color = vscale(intensity, color);
#if CLRT_HAS_REFLECTIVE
    const lint stop = bounce >= depth ? alive : alive & (reflective <= 0);
#else
    const lint stop = alive;
#endif
    result = vsel(stop, local_color, result);
    alive &= !stop;
    if (!ANY(alive)) break;
    stack_local[bounce] = local_color;
    stack_r[bounce] = reflective;
    sp = alive ? (lint)(bounce + 1) : sp;
    const vec3 reflected = reflect_ray(V, N);
    O = vsel(alive, Pt, O);
    D = vsel(alive, reflected, D);
    self = alive ? hit : self;
    tmin = epsilon;
    COUNT_IN_LANES(counts->reflection, alive, 1);
  }
  /* Unwind: frames [sp, top) were never pushed in a lane and are skipped. */
#if CLRT_LANES == 1
  for (int k = sp - 1; k >= 0; --k) {
#else
  for (int k = min(depth, CLRT_STACK_FRAMES) - 1; k >= 0; --k) {
#endif
    const vec3 blended = vadd(vscale(1 - stack_r[k], stack_local[k]), vscale(stack_r[k], result));
    result = vsel(k < sp, blended, result);
  }
  return result;
}

__kernel void render(__global const clrt_params* params, __global const clrt_sphere* spheres,
                     __global const clrt_light* lights, __global CANVAS_T* out, __global int* aux,
                     __global clrt_ray_counts* ray_counts, const int x0, const int y0, const int tile_w,
                     const int tile_h, __global const clrt_bvh_node* nodes, __global const int* primitives) {
  const int gx = (int)get_global_id(0), gy = (int)get_global_id(1);
  /* first pixel of this work-item in the tile: its lanes are a block of
   * CLRT_PACKET_COLS x CLRT_PACKET_ROWS pixels, row by row */
  const int px = gx * CLRT_PACKET_COLS, py = gy * CLRT_PACKET_ROWS;
  if (px >= tile_w || py >= tile_h) return;
  const int W = params->width, H = params->height;
  const lint col = x0 + px + LANE_IOTA % CLRT_PACKET_COLS;
  const lint row = y0 + py + LANE_IOTA / CLRT_PACKET_COLS;
  const lint x = col - W / 2;
  const lint y = H / 2 - 1 - row;
  lane_ray_counts counts = {(lint)0, (lint)0, (lint)0, (lint)0};

  /* The camera: CanvasToViewport, then the rotation (per sample below). */
  const real viewport_w = REAL_FROM_HI_LO(params->viewport[0], params->viewport_lo[0]);
  const real viewport_h = REAL_FROM_HI_LO(params->viewport[1], params->viewport_lo[1]);
  const real dz = REAL_FROM_HI_LO(params->proj_d, params->proj_d_lo);
  real m[9];
  for (int k = 0; k < 9; ++k) m[k] = REAL_FROM_HI_LO(params->rotation[k], params->rotation_lo[k]);
  const vec3 camera = VEC3_FROM_HI_LO(params->origin, params->origin_lo);
  const real epsilon = REAL_FROM_HI_LO(params->epsilon, params->epsilon_lo);
  const vec3 background = v3(params->background[0], params->background[1], params->background[2]);
  const int depth = CLRT_RECURSION_DEPTH(params);

  /* Supersampling (--spp N, clrt_params.spp): pixel (x, y) is sampled at
   * the canvas points (x + o_i, y + o_j), o_k = (k + 0.5) / N - 0.5 for
   * k = 0..N-1, sample s = j * N + i; N = 1 is the one ray through (x, y).
   * The samples' colours are summed unclamped and divided by N^2 before the
   * store; the pixel's classification (hit sphere, shadow mask) is that of
   * sample 0, at (x + o_0, y + o_0). The reference states the same rule
   * (host/reference/reference.cpp; tests/render/test_supersampling.cpp
   * checks that they agree). */
  const int spp = CLRT_SAMPLES_PER_AXIS(params);
  lint hit_id = -1, shadow_mask = 0;
  vec3 result;
  if (spp == 1) {
    /* The one ray through (x, y), apart from the sample loop below: the
     * loop around it cost the single-ray render 5% of the demo's kernel
     * time (docs/performance.md, "Supersampling"). */
    const lreal dx = TO_LREAL(x) * viewport_w / (real)W;
    const lreal dy = TO_LREAL(y) * viewport_h / (real)H;
    result = trace_camera_ray(dx, dy, m, dz, camera, epsilon, background, depth, 1, params, spheres, lights, nodes,
                              primitives, &hit_id, &shadow_mask, &counts);
  } else {
    vec3 sum;
    for (int s = 0; s < spp * spp; ++s) {
      const real ox = ((real)(s % spp) + (real)0.5) / (real)spp - (real)0.5;
      const real oy = ((real)(s / spp) + (real)0.5) / (real)spp - (real)0.5;
      const lreal dx = (TO_LREAL(x) + ox) * viewport_w / (real)W;
      const lreal dy = (TO_LREAL(y) + oy) * viewport_h / (real)H;
      const vec3 color = trace_camera_ray(dx, dy, m, dz, camera, epsilon, background, depth, s == 0, params, spheres,
                                          lights, nodes, primitives, &hit_id, &shadow_mask, &counts);
      if (s == 0)
        sum = color;
      else
        sum = vadd(sum, color);
    }
    /* The mean of the samples (summed unclamped). */
    const real samples = (real)(spp * spp);
    result = v3(sum.x / samples, sum.y / samples, sum.z / samples);
  }

  /* One pixel per lane; lanes past the tile's edge are dropped. Only what
   * the host asked for is stored (CLRT_OUT_*, clrt_config.h). */
#if CLRT_LANES == 1
  CANVAS_T red[1] = {TO_CANVAS(result.x)}, green[1] = {TO_CANVAS(result.y)}, blue[1] = {TO_CANVAS(result.z)};
  int hit_ids[1] = {hit_id}, shadow_masks[1] = {shadow_mask};
#ifdef CLRT_COUNT_RAYS
  int primary[1] = {counts.primary}, shadow[1] = {counts.shadow}, reflection[1] = {counts.reflection},
      sphere_tests[1] = {counts.sphere_tests};
#endif
#else
  CANVAS_T red[CLRT_LANES], green[CLRT_LANES], blue[CLRT_LANES];
  STORE_LANES(red, TO_CANVAS(result.x));
  STORE_LANES(green, TO_CANVAS(result.y));
  STORE_LANES(blue, TO_CANVAS(result.z));
#ifdef CLRT_OUT_CLASSES
  int hit_ids[CLRT_LANES], shadow_masks[CLRT_LANES];
  STORE_LANES(hit_ids, hit_id);
  STORE_LANES(shadow_masks, shadow_mask);
#endif
#ifdef CLRT_COUNT_RAYS
  int primary[CLRT_LANES], shadow[CLRT_LANES], reflection[CLRT_LANES], sphere_tests[CLRT_LANES];
  STORE_LANES(primary, counts.primary);
  STORE_LANES(shadow, counts.shadow);
  STORE_LANES(reflection, counts.reflection);
  STORE_LANES(sphere_tests, counts.sphere_tests);
#endif
#endif
  for (int j = 0; j < CLRT_LANES; ++j) {
    const int jx = px + j % CLRT_PACKET_COLS, jy = py + j / CLRT_PACKET_COLS;
    if (jx >= tile_w || jy >= tile_h) continue;
    const int idx = jy * tile_w + jx;
#ifdef CLRT_OUT_RGBA8
    vstore4((uchar4)(red[j], green[j], blue[j], 255), idx, out);
#else
    out[idx * 3 + 0] = red[j];
    out[idx * 3 + 1] = green[j];
    out[idx * 3 + 2] = blue[j];
#endif
#ifdef CLRT_OUT_CLASSES
    aux[idx * 2 + 0] = hit_ids[j];
    aux[idx * 2 + 1] = shadow_masks[j];
#endif
#ifdef CLRT_COUNT_RAYS
    ray_counts[idx].primary = primary[j];
    ray_counts[idx].shadow = shadow[j];
    ray_counts[idx].reflection = reflection[j];
    ray_counts[idx].sphere_tests = sphere_tests[j];
#endif
  }
}
