/* clrt_film.h - the stores of a block's pixels into the tile's buffers:
 * colour (float, or 8-bit with CLRT_OUT_RGBA8: clrt_lanes.h's canvas rule),
 * classes (hit id and shadow mask per pixel; with CLRT_OUT_CLASSES, and
 * always for subsampling's second launch, which reads them) and the ray
 * counters (CLRT_COUNT_RAYS). Only what the host asked for is stored
 * (CLRT_OUT_*, clrt_config.h); lanes past the tile's edge are dropped. The
 * AOV layers have their own store (clrt_layers.h). Lanes are spilled to
 * per-lane arrays first: a vector's lane j is not addressable by a loop
 * index. */
#ifndef CLRT_FILM_H
#define CLRT_FILM_H

#include "clrt_block.h"
#include "clrt_math.h"

CLRT_INLINE void store_pixels(const pixel_block* block, const int x0, const vec3 result, const lint hit_id,
                              const lint shadow_mask, const lane_ray_counts* counts, __global CANVAS_T* colors,
                              __global int* classes, __global clrt_ray_counts* counters) {
#if CLRT_LANES == 1
  CANVAS_T red[1] = {TO_CANVAS(result.x)}, green[1] = {TO_CANVAS(result.y)}, blue[1] = {TO_CANVAS(result.z)};
  int hit_ids[1] = {hit_id}, shadow_masks[1] = {shadow_mask};
#ifdef CLRT_COUNT_RAYS
  int primary[1] = {counts->primary}, shadow[1] = {counts->shadow}, reflection[1] = {counts->reflection},
      sphere_tests[1] = {counts->sphere_tests}, refraction[1] = {counts->refraction};
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
  STORE_LANES(primary, counts->primary);
  STORE_LANES(shadow, counts->shadow);
  STORE_LANES(reflection, counts->reflection);
  STORE_LANES(sphere_tests, counts->sphere_tests);
  STORE_LANES(refraction, counts->refraction);
#endif
#endif
  for (int j = 0; j < CLRT_LANES; ++j) {
    if (!lane_in_tile(block, j)) continue;
    const int idx = lane_tile_y(block, j) * block->tile_w + lane_tile_x(block, j);
#ifdef CLRT_OUT_RGBA8
    vstore4((uchar4)(red[j], green[j], blue[j], 255), idx, colors);
#else
    colors[idx * 3 + 0] = red[j];
    colors[idx * 3 + 1] = green[j];
    colors[idx * 3 + 2] = blue[j];
#endif
#if CLRT_SUBSAMPLE == CLRT_SUBSAMPLE_SHADE
    /* an even column's hit is pass 0's, which other work-items read now */
    const int known = ((x0 + lane_tile_x(block, j)) & 1) == 0;
    if (!known) classes[idx * 2 + 0] = hit_ids[j];
    classes[idx * 2 + 1] = shadow_masks[j];
#elif defined(CLRT_OUT_CLASSES) || CLRT_SUBSAMPLE
    classes[idx * 2 + 0] = hit_ids[j];
    classes[idx * 2 + 1] = shadow_masks[j];
#endif
#ifdef CLRT_COUNT_RAYS
    counters[idx].primary = primary[j];
    counters[idx].shadow = shadow[j];
    counters[idx].reflection = reflection[j];
#if CLRT_SUBSAMPLE == CLRT_SUBSAMPLE_SHADE
    counters[idx].sphere_tests = sphere_tests[j] + (known ? counters[idx].sphere_tests : 0);
#else
    counters[idx].sphere_tests = sphere_tests[j];
#endif
    counters[idx].refraction = refraction[j];
#endif
  }
}

#endif /* CLRT_FILM_H */
