/* clrt_subsample.h - the book's subsampling (host/scene/sampling.hpp), one
 * ray per pixel in two launches (the host's order, an in-order queue):
 *   shade:       camera_hits finds the camera hits of the image's even
 *                columns (no shading); then render shades every pixel, even
 *                ones on their own hit, odd ones on their neighbours' where
 *                they agree (assumed_intersection()); a block searches only
 *                when one of its lanes has no hit to go on;
 *   interpolate: render over the even columns, which it traces; then render
 *                over the odd ones, interpolating where the neighbours agree.
 * What a pixel takes from the first launch follows from its column's
 * parity, not from the launch; the launches' columns are clrt_block.h's.
 * Between them the tile's classes buffer carries the hit ids (and
 * interpolate's colours stay in its colours buffer). Builds without
 * -DCLRT_SUBSAMPLE use only ASSUME_NOTHING and the guess that assumes
 * nothing. */
#ifndef CLRT_SUBSAMPLE_H
#define CLRT_SUBSAMPLE_H

#include "clrt_block.h"
#include "clrt_camera.h"
#include "clrt_query.h"

/* No assumed primary hit: the search decides (see below). */
#define ASSUME_NOTHING (-2)

#if CLRT_SUBSAMPLE == CLRT_SUBSAMPLE_SHADE
/* Subsampling, shade mode (host/scene/sampling.hpp): a camera ray whose pixel's
 * neighbours hit the same primitive is tested against that primitive only.
 * `assumed` per lane: a primitive id, -1 (both neighbours missed: no hit,
 * no test) or ASSUME_NOTHING. Returns the hit per lane of `alive`, or
 * ASSUME_NOTHING where the closest_intersection() search must decide (no
 * assumption, or the ray passes the assumed primitive by). Lanes that
 * assume the same primitive test it together; the loop runs once per
 * distinct id among the lanes (mostly once: the block's pixels are
 * neighbours). */
/* The closest hit in (tmin, infinity) on primitive `id` (uniform), per lane;
 * infinity on a miss. */
CLRT_INLINE lreal primitive_distance(const vec3* O, const vec3* D, real tmin, int id, const scene_data* scene) {
  __global const clrt_params* params = scene->params;
  lreal t = REAL_INFINITY;
  if (id < CLRT_SPHERE_COUNT(params)) {
    lreal t1, t2;
    intersect(O, D, scene->spheres, id, (lint)0, &t1, &t2);
    t = ((tmin < t1) & (t1 < t)) ? t1 : t; /* both roots, as closest_intersection() takes them */
    t = ((tmin < t2) & (t2 < t)) ? t2 : t;
    return t;
  }
#if CLRT_HAS_PLANES
  if (id < TRIANGLE_ID0(params)) {
    const lreal d = plane_distance(O, D, &scene->planes[id - PLANE_ID0(params)]);
    return ((tmin < d) & (d < t)) ? d : t;
  }
#endif
#if CLRT_HAS_TRIANGLES
  {
    const ray_shear shear = shear_of(D);
    const int slot = TRIANGLE_SLOT(scene, id - TRIANGLE_ID0(params));
    const lreal d = triangle_distance(O, &shear, &scene->triangles[slot], TRIANGLE_LO(scene, slot));
    t = ((tmin < d) & (d < t)) ? d : t;
  }
#endif
  return t;
}

CLRT_INLINE lint assumed_intersection(const vec3* O, const vec3* D, real tmin, lint assumed, lint alive,
                                      const scene_data* scene, lreal* t_out, lint* tests) {
  lint hit = (alive & (assumed == (lint)-1)) ? (lint)-1 : (lint)ASSUME_NOTHING;
  lreal t = REAL_INFINITY;
  lint todo = alive & (assumed >= (lint)0);
  while (ANY(todo)) {
    const int id = LANE_MIN(todo ? assumed : (lint)INT_MAX);
    const lint these = todo & (assumed == (lint)id);
    const lreal d = primitive_distance(O, D, tmin, id, scene);
    const lint found = these & (d < REAL_INFINITY);
    hit = found ? (lint)id : hit;
    t = found ? d : t;
    *tests += these ? (lint)1 : (lint)0;
    todo &= !these;
  }
  *t_out = t;
  return hit;
}
#endif

/* What a pixel takes from its neighbours, per lane: the primitive to assume
 * (a primitive id, -1: both neighbours missed, or ASSUME_NOTHING), and with
 * interpolation the lanes that trace their ray at all, and the others'
 * mean colour and shadow mask. */
typedef struct subsample_guess {
  lint assumed;
  lint traced;
#if CLRT_SUBSAMPLE == CLRT_SUBSAMPLE_INTERPOLATE
  vec3 interpolated;
  lint interpolated_shadow;
#endif
} subsample_guess;

#if CLRT_SUBSAMPLE == CLRT_SUBSAMPLE_SHADE
/* Shade's first launch (camera_hits): the camera hits of the block's pixels
 * in a tile at image column x0 and row y0 (the one ray through each
 * pixel, as trace_camera_ray() casts it), stored for render with the tests
 * they took. */
CLRT_INLINE void store_camera_hits(const pixel_block* block, const int x0, const int y0, const scene_data* scene,
                                   __global int* classes, __global clrt_ray_counts* counters) {
  const camera_view view = camera_of(scene->params);
  lint x, y;
  canvas_point(&view, x0 + lanes_tile_x(block), y0 + lanes_tile_y(block), &x, &y);
  const vec3 D = canvas_direction(&view, TO_LREAL(x), TO_LREAL(y));
  lreal t;
  lint tests = 0;
  const lint hit = closest_intersection(&view.origin, &D, 1, REAL_INFINITY, (lint)-1, MASK_TRUE, scene, &t, &tests);
#if CLRT_LANES == 1
  int hits[1] = {hit}, searched[1] = {tests};
#else
  int hits[CLRT_LANES], searched[CLRT_LANES];
  STORE_LANES(hits, hit);
  STORE_LANES(searched, tests);
#endif
  for (int j = 0; j < CLRT_LANES; ++j) {
    if (!lane_in_tile(block, j)) continue;
    const int idx = lane_tile_y(block, j) * block->tile_w + lane_tile_x(block, j);
    classes[idx * 2] = hits[j];
#ifdef CLRT_COUNT_RAYS
    counters[idx].sphere_tests = searched[j]; /* render adds its own */
#endif
  }
}
#endif

/* The guess of each lane's pixel: in an odd column, the primitive both its
 * neighbours hit (the first launch stored their hit ids in classes, and
 * with interpolation their colours in colours), where both exist in the
 * tile (the host gives whole rows, so only the image's last column lacks
 * one); in an even column, with shade, its own hit, with interpolation
 * nothing (it is traced). Lanes past the tile's edge assume a miss: no
 * work, never stored. Without subsampling nothing is assumed and every
 * lane traces. */
CLRT_INLINE subsample_guess guess_from_neighbours(const pixel_block* block, const int x0,
                                                  __global const int* classes, __global const CANVAS_T* colors) {
  subsample_guess guess;
  guess.assumed = ASSUME_NOTHING;
  guess.traced = MASK_TRUE;
#if CLRT_SUBSAMPLE == CLRT_SUBSAMPLE_INTERPOLATE
  guess.interpolated = v3(0, 0, 0);
  guess.interpolated_shadow = 0;
#endif
#if CLRT_SUBSAMPLE
  const int tile_w = block->tile_w;
  int neighbours[CLRT_LANES];
#if CLRT_SUBSAMPLE == CLRT_SUBSAMPLE_INTERPOLATE
  float mean_red[CLRT_LANES], mean_green[CLRT_LANES], mean_blue[CLRT_LANES];
  int shadow_both[CLRT_LANES];
#endif
  for (int j = 0; j < CLRT_LANES; ++j) {
    const int jx = lane_tile_x(block, j), jy = lane_tile_y(block, j);
    neighbours[j] = -1;
#if CLRT_SUBSAMPLE == CLRT_SUBSAMPLE_INTERPOLATE
    mean_red[j] = mean_green[j] = mean_blue[j] = 0;
    shadow_both[j] = 0;
#endif
    if (jx >= tile_w || jy >= block->tile_h) continue;
    neighbours[j] = ASSUME_NOTHING;
    if (((x0 + jx) & 1) == 0) { /* an even column */
#if CLRT_SUBSAMPLE == CLRT_SUBSAMPLE_SHADE
      neighbours[j] = classes[(jy * tile_w + jx) * 2]; /* found by camera_hits' search */
#endif
      continue;
    }
    if (jx < 1 || jx + 1 >= tile_w) continue;
    const int left = jy * tile_w + jx - 1, right = left + 2;
    if (classes[left * 2] != classes[right * 2]) continue;
    neighbours[j] = classes[left * 2];
#if CLRT_SUBSAMPLE == CLRT_SUBSAMPLE_INTERPOLATE
    /* the mean of the neighbours' canvas colours (exact in float) */
#ifdef CLRT_OUT_RGBA8
    const float4 l = convert_float4(vload4(left, colors)), r = convert_float4(vload4(right, colors));
#else
    const float4 l = convert_float4(convert_uchar4_sat_rte(
                     (float4)(colors[left * 3], colors[left * 3 + 1], colors[left * 3 + 2], 0))),
                 r = convert_float4(convert_uchar4_sat_rte(
                     (float4)(colors[right * 3], colors[right * 3 + 1], colors[right * 3 + 2], 0)));
#endif
    mean_red[j] = (l.x + r.x) * 0.5f;
    mean_green[j] = (l.y + r.y) * 0.5f;
    mean_blue[j] = (l.z + r.z) * 0.5f;
    shadow_both[j] = classes[left * 2 + 1] & classes[right * 2 + 1];
#endif
  }
  guess.assumed = LOAD_LANES(neighbours);
#if CLRT_SUBSAMPLE == CLRT_SUBSAMPLE_INTERPOLATE
  guess.interpolated = v3(LOAD_LANES(mean_red), LOAD_LANES(mean_green), LOAD_LANES(mean_blue));
  guess.interpolated_shadow = LOAD_LANES(shadow_both);
  guess.traced = guess.assumed == (lint)ASSUME_NOTHING;
#endif
#endif
  return guess;
}

#if CLRT_SUBSAMPLE == CLRT_SUBSAMPLE_INTERPOLATE
/* Interpolate's pixels without a ray of their own take the guess: colour,
 * hit and shadow mask. */
CLRT_INLINE void take_interpolated(const subsample_guess* guess, vec3* result, lint* hit_id, lint* shadow_mask) {
  *result = vsel(guess->traced, *result, guess->interpolated);
  *hit_id = guess->traced ? *hit_id : guess->assumed;
  *shadow_mask = guess->traced ? *shadow_mask : guess->interpolated_shadow;
}
#endif

#endif /* CLRT_SUBSAMPLE_H */
