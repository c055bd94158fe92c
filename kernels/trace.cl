/* trace.cl - the render kernel: primary ray, shadow rays and bounded-depth
 * reflections and refractions as an explicit, bounded tree walk (no
 * recursion), per pixel.
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
 *   clrt_flat.h       planes and triangles (watertight), the scene's buffers
 *   clrt_intersect.h  ray-sphere roots, closest hit and any hit
 *   clrt_bvh.h        the same queries through the hierarchy (-DCLRT_BVH)
 *   clrt_shade.h      hit material, ComputeLighting, reflected rays
 *   clrt_layers.h     the AOV layers' first hit (-DCLRT_OUT_LAYERS)
 *   clrt_device_status.h  checks of a work-item's own run (the status word)
 * This file holds the camera rays (N x N per pixel with supersampling), the
 * walk over the rays they spawn, the average and the stores. */
#include "clrt_config.h"
#include "clrt_device_status.h"
#include "clrt_flat.h"
#include "clrt_intersect.h"
#include "clrt_lanes.h"
#include "clrt_layers.h"
#include "clrt_layout.h"
#include "clrt_math.h"
#include "clrt_shade.h"

/* The direction of the camera ray through the viewport point (dx, dy, dz),
 * rotated by the camera's m. */
CLRT_INLINE vec3 camera_direction(const lreal dx, const lreal dy, const real* m, const real dz) {
  return v3(m[0] * dx + m[1] * dy + m[2] * dz, m[3] * dx + m[4] * dy + m[5] * dz, m[6] * dx + m[7] * dy + m[8] * dz);
}

/* One camera ray per lane, through the viewport point (dx, dy) (before the
 * camera rotation m), and the rays it spawns: the book's TraceRay without
 * recursion, in the lanes of `active`. Returns its colour; `classify` 1 (a
 * pixel's first sample) stores its primary hit and blocked lights in *hit_id
 * and *shadow_mask, 2 its primary hit only, 0 neither. `assumed` is the
 * primary hit subsampling assumes per lane (assumed_intersection(),
 * clrt_intersect.h; used by CLRT_SUBSAMPLE_SHADE only).
 *
 * TraceRay's colour is linear in its children's colours, so the walk carries
 * each ray's weight (the product of the shares along its path) and adds
 * weight x local colour at every hit, front to back: a hit with reflectivity
 * r and transparency t keeps (1 - r)(1 - t) of its local colour and passes
 * r to its reflected child and (1 - r) t to its refracted one (all of it to
 * the reflected child under total internal reflection); a ray that ends
 * (depth reached, or neither share) adds its whole local colour, a miss the
 * background. A child whose weight is below clrt_params.min_weight is not
 * traced (the host's cut-off, host/scene/ray_tree.hpp: what it could add
 * cannot move the pixel by a level). With reflection only, every ray has at
 * most one child and no stack is needed. With transparency (CLRT_HAS_TRANSPARENT) a hit can have
 * two children: the reflected one continues and the refracted one waits in
 * the slot of its level, a bounded tree walk in depth-first order. All
 * lanes walk the same tree positions (lanes without a ray there are masked),
 * so every slot index is uniform; a slot holds at most one ray per lane
 * because a level's slot is written only after every deeper one was
 * emptied. The slots take CLRT_DEPTH_BOUND + 1 entries of (origin,
 * direction, weight, medium, start sphere, mask) per lane: 40 bytes per lane
 * and level in float builds (docs/developer/kernel.md). */
CLRT_INLINE vec3 trace_camera_ray(const lreal dx, const lreal dy, const real* m, const real dz, const vec3 camera,
                                  const real epsilon, const vec3 background, const int depth, const int classify,
                                  const lint active, const lint assumed, const scene_data* scene, lint* hit_id,
                                  lint* shadow_mask, lane_ray_counts* counts) {
  vec3 D = camera_direction(dx, dy, m, dz);
  vec3 O = camera;
  COUNT_IN_LANES(counts->primary, active, 1); /* one primary ray per lane and sample */

  vec3 result = v3(0, 0, 0);
  lreal weight = 1;       /* of the lane's current ray */
  real tmin = 1;          /* the same for all lanes: 1 for primary rays, epsilon after */
  lint self = -1;         /* sphere the lane's current ray starts on */
  lint alive = active;    /* lanes whose current ray exists */
  int level = 0;          /* of the current rays (0: camera rays), the same for all lanes */
#if CLRT_HAS_REFLECTIVE || CLRT_HAS_TRANSPARENT
  const real min_weight = scene->params->min_weight; /* children lighter than this are not traced */
#endif
#if CLRT_HAS_TRANSPARENT
  lreal medium = scene->params->camera_medium; /* refractive index the current ray travels in */
  vec3 pending_origin[CLRT_STACK_FRAMES], pending_direction[CLRT_STACK_FRAMES];
  lreal pending_weight[CLRT_STACK_FRAMES], pending_medium[CLRT_STACK_FRAMES];
  lint pending_self[CLRT_STACK_FRAMES], pending[CLRT_STACK_FRAMES];
#endif

  for (;;) {
    lreal t;
    lint tests = 0;
#if CLRT_SUBSAMPLE == CLRT_SUBSAMPLE_SHADE
    /* camera rays: the assumed primitive first; the search where it cannot say */
    lint hit = level == 0 ? assumed_intersection(&O, &D, tmin, assumed, alive, scene, &t, &tests)
                          : (lint)ASSUME_NOTHING;
    const lint search = alive & (hit == (lint)ASSUME_NOTHING);
    if (ANY(search)) {
      lreal searched_t;
      lint searched_tests = 0;
      const lint searched = closest_intersection(&O, &D, tmin, REAL_INFINITY, self, scene, &searched_t, &searched_tests);
      hit = search ? searched : hit;
      t = search ? searched_t : t;
      tests += search ? searched_tests : (lint)0;
    }
#else
    const lint hit = closest_intersection(&O, &D, tmin, REAL_INFINITY, self, scene, &t, &tests);
#endif
    COUNT_IN_LANES(counts->sphere_tests, alive, tests);
    const lint miss = alive & (hit < 0);
    result = vsel(miss, vadd(result, vscale(weight, background)), result);
    alive &= !miss;
    if (ANY(alive)) {
      const hit_surface surface = hit_material(hit, scene);
      const vec3 Pt = vadd(O, vscale(t, D));
      const vec3 N = surface_normal(&surface, &Pt, &D);
      const vec3 V = vneg(D);
      const int primary_classified = classify == 1 && level == 0;
      if (classify && level == 0) *hit_id = alive ? hit : *hit_id;

      const lreal intensity = compute_lighting(&Pt, &N, &V, surface.specular, hit, alive, epsilon, primary_classified,
                                               scene, shadow_mask, counts);
      const vec3 local_color = vscale(intensity, surface.color);
#if CLRT_HAS_REFLECTIVE || CLRT_HAS_TRANSPARENT
      /* the shares of the local colour and of the children */
      lreal reflected_share = surface.reflective;
#if CLRT_HAS_TRANSPARENT
      lreal refracted_share = (1 - surface.reflective) * surface.transparency;
      const lreal local_share = (1 - surface.reflective) * (1 - surface.transparency);
      lreal n2;
      lint tir;
      const vec3 T = refract_ray(D, N, medium, &surface, &n2, &tir);
      reflected_share = tir ? reflected_share + refracted_share : reflected_share;
      refracted_share = tir ? (lreal)0 : refracted_share;
      const lint stop = level >= depth ? alive : alive & (reflected_share <= 0) & (refracted_share <= 0);
#else
      const lreal local_share = 1 - surface.reflective;
      const lint stop = level >= depth ? alive : alive & (reflected_share <= 0);
#endif
      result = vsel(alive, vadd(result, vscale(stop ? weight : weight * local_share, local_color)), result);
      alive &= !stop;
      /* The weight cut-off (clrt_params.min_weight): a child lighter than it
       * is not traced; a ray whose children are all cut ends here, having
       * added only its local share (the reference does the same). */
#if CLRT_HAS_TRANSPARENT
      const lint reflects = alive & (reflected_share > 0) & (weight * reflected_share >= min_weight);
      const lint refracts = alive & (refracted_share > 0) & (weight * refracted_share >= min_weight);
      alive = reflects | refracts;
#else
      alive &= weight * reflected_share >= min_weight;
#endif
      if (ANY(alive)) {
        const vec3 R = reflect_ray(V, N);
#if CLRT_HAS_TRANSPARENT
        /* Where both exist the refracted child waits; slot level + 1 is
         * empty in every lane (see above). */
        pending[level + 1] = reflects & refracts;
        pending_origin[level + 1] = Pt;
        pending_direction[level + 1] = T;
        pending_weight[level + 1] = weight * refracted_share;
        pending_medium[level + 1] = n2;
        pending_self[level + 1] = hit;
        COUNT_IN_LANES(counts->reflection, reflects, 1);
        COUNT_IN_LANES(counts->refraction, refracts, 1);
        /* The ray that goes on: the reflected one where it exists, else the
         * refracted one (into its new medium). */
        D = vsel(alive, vsel(reflects, R, T), D);
        weight = alive ? weight * (reflects ? reflected_share : refracted_share) : weight;
        medium = (alive & !reflects) ? n2 : medium;
#else
        COUNT_IN_LANES(counts->reflection, alive, 1);
        D = vsel(alive, R, D);
        weight = alive ? weight * reflected_share : weight;
#endif
        O = vsel(alive, Pt, O);
        self = alive ? hit : self;
        tmin = epsilon;
        ++level;
        continue;
      }
#else
      result = vsel(alive, vadd(result, vscale(weight, local_color)), result);
#endif
    }
#if CLRT_HAS_TRANSPARENT
    /* Every lane's path ended: resume the deepest waiting rays. */
    int k = level;
    while (k > 0 && !ANY(pending[k])) --k;
    if (k == 0) break;
    alive = pending[k];
    pending[k] = 0;
    O = pending_origin[k];
    D = pending_direction[k];
    weight = pending_weight[k];
    medium = pending_medium[k];
    self = pending_self[k];
    tmin = epsilon;
    level = k;
#else
    break;
#endif
  }
  return result;
}

__kernel void render(__global const clrt_params* params, __global const clrt_sphere* spheres,
                     __global const clrt_light* lights, __global CANVAS_T* out, __global int* aux,
                     __global clrt_ray_counts* ray_counts, const int x0, const int y0, const int tile_w,
                     const int tile_h, __global const clrt_wide_node* nodes, __global const int* primitives,
                     __global const clrt_plane* planes, __global const clrt_triangle* triangles,
                     __global const clrt_material* materials, const int pass, __global int* status
#ifdef CLRT_OUT_LAYERS
                     , __global float* layers /* CLRT_LAYER_FLOATS per pixel (clrt_layers.h) */
#endif
) {
  const int gx = (int)get_global_id(0), gy = (int)get_global_id(1);
  /* first pixel of this work-item in the tile: its lanes are a block of
   * CLRT_PACKET_COLS x CLRT_PACKET_ROWS pixels, row by row */
  const int px = gx * CLRT_PACKET_COLS, py = gy * CLRT_PACKET_ROWS;
#if CLRT_SUBSAMPLE
  /* Subsampling (host/scene/sampling.hpp), two launches, `pass` 0 then 1:
   *   shade:       pass 0 finds the camera hits of the image's even columns
   *                (no shading); pass 1 shades every pixel, even ones on
   *                their own hit, odd ones on their neighbours' where they
   *                agree (assumed_intersection()); a block searches only
   *                when one of its lanes has no hit to go on;
   *   interpolate: pass 0 traces the even columns; pass 1 the odd ones,
   *                interpolating where the neighbours agree.
   * A strided launch's block spans every other column of the tile: tile
   * column first_col + 2 (px + lane column). */
  const int strided = CLRT_SUBSAMPLE == CLRT_SUBSAMPLE_INTERPOLATE || pass == 0;
  const int first_col = strided ? (pass - x0) & 1 : 0; /* global columns of parity `pass` */
  const int col_step = strided ? 2 : 1;
  const int pass_w = strided ? (tile_w - first_col + 1) / 2 : tile_w;
  if (px >= pass_w || py >= tile_h) return;
  /* the tile column of lane j (an int, or LANE_IOTA for all lanes) */
#define LANE_TILE_X(j) (first_col + col_step * (px + (j) % CLRT_PACKET_COLS))
  const lint tile_col = LANE_TILE_X(LANE_IOTA);
#else
  if (px >= tile_w || py >= tile_h) return;
  const lint tile_col = px + LANE_IOTA % CLRT_PACKET_COLS;
#endif
  const int W = params->width, H = params->height;
  const lint col = x0 + tile_col;
  const lint row = y0 + py + LANE_IOTA / CLRT_PACKET_COLS;
  const lint x = col - W / 2;
  const lint y = H / 2 - 1 - row;
  lane_ray_counts counts = {(lint)0, (lint)0, (lint)0, (lint)0, (lint)0};
  const scene_data scene = {params, spheres, lights, nodes, primitives, planes, triangles, materials};

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
  lint assumed = ASSUME_NOTHING;
  lint traced = MASK_TRUE; /* lanes that trace their camera ray */
#if CLRT_SUBSAMPLE == CLRT_SUBSAMPLE_SHADE
  if (pass == 0) {
    /* The even columns' camera hits, for pass 1 (the one ray through (x, y),
     * as trace_camera_ray() casts it) */
    const lreal dx = TO_LREAL(x) * viewport_w / (real)W;
    const lreal dy = TO_LREAL(y) * viewport_h / (real)H;
    const vec3 D = camera_direction(dx, dy, m, dz);
    lreal t;
    lint tests = 0;
    const lint hit = closest_intersection(&camera, &D, 1, REAL_INFINITY, (lint)-1, &scene, &t, &tests);
#if CLRT_LANES == 1
    int hits[1] = {hit}, searched[1] = {tests};
#else
    int hits[CLRT_LANES], searched[CLRT_LANES];
    STORE_LANES(hits, hit);
    STORE_LANES(searched, tests);
#endif
    for (int j = 0; j < CLRT_LANES; ++j) {
      const int jx = LANE_TILE_X(j), jy = py + j / CLRT_PACKET_COLS;
      if (jx >= tile_w || jy >= tile_h) continue;
      aux[(jy * tile_w + jx) * 2] = hits[j];
#ifdef CLRT_COUNT_RAYS
      ray_counts[jy * tile_w + jx].sphere_tests = searched[j]; /* pass 1 adds its own */
#endif
    }
    CHECK_LOOP_LIMIT(params, status);
    return;
  }
#endif
#if CLRT_SUBSAMPLE
#if CLRT_SUBSAMPLE == CLRT_SUBSAMPLE_INTERPOLATE
  vec3 interpolated = v3(0, 0, 0);
  lint interpolated_shadow = 0;
#endif
  if (pass == 1) {
    /* The primitive both neighbours of an odd column hit (pass 0 stored
     * their hit ids in aux, and with interpolation their colours in out),
     * where both exist in the tile (the host gives whole rows, so only the
     * image's last column lacks one); with shade, an even column's own hit.
     * Lanes past the tile's edge assume a miss: no work, never stored. */
    int neighbours[CLRT_LANES];
#if CLRT_SUBSAMPLE == CLRT_SUBSAMPLE_INTERPOLATE
    float mean_red[CLRT_LANES], mean_green[CLRT_LANES], mean_blue[CLRT_LANES];
    int shadow_both[CLRT_LANES];
#endif
    for (int j = 0; j < CLRT_LANES; ++j) {
      const int jx = LANE_TILE_X(j), jy = py + j / CLRT_PACKET_COLS;
      neighbours[j] = -1;
#if CLRT_SUBSAMPLE == CLRT_SUBSAMPLE_INTERPOLATE
      mean_red[j] = mean_green[j] = mean_blue[j] = 0;
      shadow_both[j] = 0;
#endif
      if (jx >= tile_w || jy >= tile_h) continue;
#if CLRT_SUBSAMPLE == CLRT_SUBSAMPLE_SHADE
      if (((x0 + jx) & 1) == 0) {
        neighbours[j] = aux[(jy * tile_w + jx) * 2]; /* found by pass 0's search */
        continue;
      }
#endif
      neighbours[j] = ASSUME_NOTHING;
      if (jx < 1 || jx + 1 >= tile_w) continue;
      const int left = jy * tile_w + jx - 1, right = left + 2;
      if (aux[left * 2] != aux[right * 2]) continue;
      neighbours[j] = aux[left * 2];
#if CLRT_SUBSAMPLE == CLRT_SUBSAMPLE_INTERPOLATE
      /* the mean of the neighbours' canvas colours (exact in float) */
#ifdef CLRT_OUT_RGBA8
      const float4 l = convert_float4(vload4(left, out)), r = convert_float4(vload4(right, out));
#else
      const float4 l = convert_float4(convert_uchar4_sat_rte(
                       (float4)(out[left * 3], out[left * 3 + 1], out[left * 3 + 2], 0))),
                   r = convert_float4(convert_uchar4_sat_rte(
                       (float4)(out[right * 3], out[right * 3 + 1], out[right * 3 + 2], 0)));
#endif
      mean_red[j] = (l.x + r.x) * 0.5f;
      mean_green[j] = (l.y + r.y) * 0.5f;
      mean_blue[j] = (l.z + r.z) * 0.5f;
      shadow_both[j] = aux[left * 2 + 1] & aux[right * 2 + 1];
#endif
    }
    assumed = LOAD_LANES(neighbours);
#if CLRT_SUBSAMPLE == CLRT_SUBSAMPLE_INTERPOLATE
    interpolated = v3(LOAD_LANES(mean_red), LOAD_LANES(mean_green), LOAD_LANES(mean_blue));
    interpolated_shadow = LOAD_LANES(shadow_both);
    traced = assumed == (lint)ASSUME_NOTHING;
#endif
  }
#endif
  if (spp == 1) {
    /* The one ray through (x, y), apart from the sample loop below: the
     * loop around it cost the single-ray render 5% of the demo's kernel
     * time (docs/results/archive.md). */
    const lreal dx = TO_LREAL(x) * viewport_w / (real)W;
    const lreal dy = TO_LREAL(y) * viewport_h / (real)H;
#if CLRT_SUBSAMPLE == CLRT_SUBSAMPLE_INTERPOLATE
    result = v3(0, 0, 0);
    if (ANY(traced))
#endif
      result = trace_camera_ray(dx, dy, m, dz, camera, epsilon, background, depth, 1, traced, assumed, &scene,
                                &hit_id, &shadow_mask, &counts);
#if CLRT_SUBSAMPLE == CLRT_SUBSAMPLE_INTERPOLATE
    result = vsel(traced, result, interpolated);
    hit_id = traced ? hit_id : assumed;
    shadow_mask = traced ? shadow_mask : interpolated_shadow;
#endif
  } else {
    /* One loop, one inlined copy of the tracer, for both uniform and
     * adaptive supersampling (each call site of trace_camera_ray() is a
     * whole copy of it: separate loops made the program twice as long to
     * build). Adaptive (scene/sampling.hpp; the reference states the same
     * rule): the grid's four corner samples come first; a lane whose corners
     * hit the same primitive (or all miss) within T levels per channel keeps
     * their mean, the others go on with every other sample in order. */
    const int adaptive = params->adaptive;
    const int total = spp * spp;
    const int corners[4] = {0, spp - 1, spp * (spp - 1), spp * spp - 1};
    vec3 corner_color[4];
    lint corner_hit[4];
    lint refine = MASK_TRUE; /* lanes that trace sample k */
    vec3 sum;
    for (int k = 0; k < total; ++k) {
      int s = k;
      if (adaptive) {
        if (k < 4) {
          s = corners[k];
        } else {
          /* the (k - 4)th other sample, in ascending order */
          s = k - 3;
          s += s >= spp - 1;
          s += s >= spp * (spp - 1);
        }
        if (k == 4) {
          const lreal threshold = params->adaptive_threshold;
          lint flat =
              (corner_hit[1] == corner_hit[0]) & (corner_hit[2] == corner_hit[0]) & (corner_hit[3] == corner_hit[0]);
#define CORNER_SPAN(c)                                                                                 \
  (fmax(fmax(corner_color[0].c, corner_color[1].c), fmax(corner_color[2].c, corner_color[3].c)) - \
   fmin(fmin(corner_color[0].c, corner_color[1].c), fmin(corner_color[2].c, corner_color[3].c)))
          flat &= (CORNER_SPAN(x) <= threshold) & (CORNER_SPAN(y) <= threshold) & (CORNER_SPAN(z) <= threshold);
#undef CORNER_SPAN
          refine = !flat;
          if (!ANY(refine)) break;
        }
      }
      const real ox = ((real)(s % spp) + (real)0.5) / (real)spp - (real)0.5;
      const real oy = ((real)(s / spp) + (real)0.5) / (real)spp - (real)0.5;
      const lreal dx = (TO_LREAL(x) + ox) * viewport_w / (real)W;
      const lreal dy = (TO_LREAL(y) + oy) * viewport_h / (real)H;
      /* classification: sample 0's hit and shadows; the other corners' hits */
      lint sample_hit = -1;
      const int classify = k == 0 ? 1 : (adaptive && k < 4 ? 2 : 0);
      /* (the host never subsamples a supersampled frame) */
      const vec3 color = trace_camera_ray(dx, dy, m, dz, camera, epsilon, background, depth, classify, refine,
                                          (lint)ASSUME_NOTHING, &scene, k == 0 ? &hit_id : &sample_hit,
                                          &shadow_mask, &counts);
      if (adaptive && k < 4) {
        corner_color[k] = color;
        corner_hit[k] = k == 0 ? hit_id : sample_hit;
      }
      if (k == 0)
        sum = color;
      else
        sum = vsel(refine, vadd(sum, color), sum);
    }
    /* The mean of the samples traced (summed unclamped). */
    const lreal samples = (adaptive && total > 4) ? (refine ? (lreal)total : (lreal)4) : (lreal)total;
    result = v3(sum.x / samples, sum.y / samples, sum.z / samples);
  }

#ifdef CLRT_OUT_LAYERS
  /* The AOV layers: the first hit of the ray through the pixel's centre. */
  float layer_floats[CLRT_LAYER_FLOATS][CLRT_LANES];
  {
    const first_hit_layers first = first_hit(
        camera, camera_direction(TO_LREAL(x) * viewport_w / (real)W, TO_LREAL(y) * viewport_h / (real)H, m, dz), &scene);
    layer_values(&first, layer_floats);
  }
#endif

  /* One pixel per lane; lanes past the tile's edge are dropped. Only what
   * the host asked for is stored (CLRT_OUT_*, clrt_config.h), and the hit
   * ids that subsampling's second launch reads. */
#if CLRT_LANES == 1
  CANVAS_T red[1] = {TO_CANVAS(result.x)}, green[1] = {TO_CANVAS(result.y)}, blue[1] = {TO_CANVAS(result.z)};
  int hit_ids[1] = {hit_id}, shadow_masks[1] = {shadow_mask};
#ifdef CLRT_COUNT_RAYS
  int primary[1] = {counts.primary}, shadow[1] = {counts.shadow}, reflection[1] = {counts.reflection},
      sphere_tests[1] = {counts.sphere_tests}, refraction[1] = {counts.refraction};
#endif
#else
  CANVAS_T red[CLRT_LANES], green[CLRT_LANES], blue[CLRT_LANES];
  STORE_LANES(red, TO_CANVAS(result.x));
  STORE_LANES(green, TO_CANVAS(result.y));
  STORE_LANES(blue, TO_CANVAS(result.z));
#if defined(CLRT_OUT_CLASSES) || CLRT_SUBSAMPLE
  int hit_ids[CLRT_LANES], shadow_masks[CLRT_LANES];
  STORE_LANES(hit_ids, hit_id);
  STORE_LANES(shadow_masks, shadow_mask);
#endif
#ifdef CLRT_COUNT_RAYS
  int primary[CLRT_LANES], shadow[CLRT_LANES], reflection[CLRT_LANES], sphere_tests[CLRT_LANES],
      refraction[CLRT_LANES];
  STORE_LANES(primary, counts.primary);
  STORE_LANES(shadow, counts.shadow);
  STORE_LANES(reflection, counts.reflection);
  STORE_LANES(sphere_tests, counts.sphere_tests);
  STORE_LANES(refraction, counts.refraction);
#endif
#endif
  for (int j = 0; j < CLRT_LANES; ++j) {
#if CLRT_SUBSAMPLE
    const int jx = LANE_TILE_X(j), jy = py + j / CLRT_PACKET_COLS;
#else
    const int jx = px + j % CLRT_PACKET_COLS, jy = py + j / CLRT_PACKET_COLS;
#endif
    if (jx >= tile_w || jy >= tile_h) continue;
    const int idx = jy * tile_w + jx;
#ifdef CLRT_OUT_RGBA8
    vstore4((uchar4)(red[j], green[j], blue[j], 255), idx, out);
#else
    out[idx * 3 + 0] = red[j];
    out[idx * 3 + 1] = green[j];
    out[idx * 3 + 2] = blue[j];
#endif
#ifdef CLRT_OUT_LAYERS
    for (int k = 0; k < CLRT_LAYER_FLOATS; ++k) layers[idx * CLRT_LAYER_FLOATS + k] = layer_floats[k][j];
#endif
#if CLRT_SUBSAMPLE == CLRT_SUBSAMPLE_SHADE
    /* an even column's hit is pass 0's, which other work-items read now */
    const int known = ((x0 + jx) & 1) == 0;
    if (!known) aux[idx * 2 + 0] = hit_ids[j];
    aux[idx * 2 + 1] = shadow_masks[j];
#elif defined(CLRT_OUT_CLASSES) || CLRT_SUBSAMPLE
    aux[idx * 2 + 0] = hit_ids[j];
    aux[idx * 2 + 1] = shadow_masks[j];
#endif
#ifdef CLRT_COUNT_RAYS
    ray_counts[idx].primary = primary[j];
    ray_counts[idx].shadow = shadow[j];
    ray_counts[idx].reflection = reflection[j];
#if CLRT_SUBSAMPLE == CLRT_SUBSAMPLE_SHADE
    ray_counts[idx].sphere_tests = sphere_tests[j] + (known ? ray_counts[idx].sphere_tests : 0);
#else
    ray_counts[idx].sphere_tests = sphere_tests[j];
#endif
    ray_counts[idx].refraction = refraction[j];
#endif
  }
  CHECK_LOOP_LIMIT(params, status);
}
#if CLRT_SUBSAMPLE
#undef LANE_TILE_X
#endif
