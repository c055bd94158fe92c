/* clrt_layers.h - the AOV layers (-DCLRT_OUT_LAYERS, host/image/layers.hpp):
 * the first hit of the camera ray through each pixel's centre - distance,
 * shading normal, colour and primitive id - written beside the colour, only
 * in builds that asked for them (a frame without layers compiles none of
 * this).
 *
 * The layers' ray is cast on its own, after the pixel's colour: the ray
 * through (x, y), the one spp 1 traces, whatever the sampling (supersampled
 * pixels average colours, not surfaces; subsampled pixels that were
 * interpolated have no ray of their own). It is not counted in the ray
 * counters (CLRT_COUNT_RAYS). */
#ifndef CLRT_LAYERS_H
#define CLRT_LAYERS_H

#include "clrt_block.h"
#include "clrt_camera.h"
#include "clrt_shade.h"

#ifdef CLRT_OUT_LAYERS
/* The buffer's layout is clrt_layout.h's (CLRT_LAYER_*); the host writes a
 * miss's distance as +inf, the kernel stores 0 there, so that no build
 * (-cl-fast-relaxed-math assumes no infinities) has to carry one. */

/* A pixel's layers, per lane. */
typedef struct first_hit_layers {
  lreal distance;
  vec3 normal, albedo;
  lint id;
} first_hit_layers;

/* The first hit of the camera ray O + t D (t > 1, as camera rays start at
 * the projection plane) in each lane. */
CLRT_INLINE first_hit_layers first_hit(const vec3 O, const vec3 D, const scene_data* scene) {
  first_hit_layers out;
  lreal t;
  lint tests = 0;
  out.id = closest_intersection(&O, &D, 1, REAL_INFINITY, (lint)-1, MASK_TRUE, scene, &t, &tests);
  const lint found = out.id >= 0;
  const hit_surface surface = hit_material(out.id, scene); /* zeros where nothing is hit */
  const lreal along = found ? t : (lreal)0;
  const vec3 Pt = vadd(O, vscale(along, D));
  const vec3 N = surface_normal(&surface, &Pt, &D);
  const vec3 zero = v3(0, 0, 0);
  out.distance = along * vlen(D);
  out.normal = vsel(found, N, zero);
  out.albedo = vsel(found, vscale((real)(1.0 / 255.0), surface.color), zero);
  return out;
}

/* A lane value as stored: float, and an id's bits. */
#if CLRT_LANES == 1
#define LAYER_FLOAT(v) ((float)(v))
#define LAYER_ID_BITS(i) as_float(i)
#define STORE_LAYER(lanes, value) ((lanes)[0] = (value))
#else
#define LAYER_FLOAT(v) (v)
#define LAYER_ID_BITS(i) AS_LREAL(i)
#define STORE_LAYER(lanes, value) STORE_LANES(lanes, value)
#endif

/* values[k][j]: float k of lane j's pixel. */
CLRT_INLINE void layer_values(const first_hit_layers* layers, float values[CLRT_LAYER_FLOATS][CLRT_LANES]) {
  STORE_LAYER(values[CLRT_LAYER_DISTANCE], LAYER_FLOAT(layers->distance));
  STORE_LAYER(values[CLRT_LAYER_NORMAL + 0], LAYER_FLOAT(layers->normal.x));
  STORE_LAYER(values[CLRT_LAYER_NORMAL + 1], LAYER_FLOAT(layers->normal.y));
  STORE_LAYER(values[CLRT_LAYER_NORMAL + 2], LAYER_FLOAT(layers->normal.z));
  STORE_LAYER(values[CLRT_LAYER_ALBEDO + 0], LAYER_FLOAT(layers->albedo.x));
  STORE_LAYER(values[CLRT_LAYER_ALBEDO + 1], LAYER_FLOAT(layers->albedo.y));
  STORE_LAYER(values[CLRT_LAYER_ALBEDO + 2], LAYER_FLOAT(layers->albedo.z));
  STORE_LAYER(values[CLRT_LAYER_ID], LAYER_ID_BITS(layers->id));
}

/* The layers of each lane's pixel (x, y): its centre's camera ray. */
CLRT_INLINE void pixel_layers(const camera_view* view, const lint x, const lint y, const scene_data* scene,
                              float values[CLRT_LAYER_FLOATS][CLRT_LANES]) {
  const first_hit_layers first = first_hit(view->origin, canvas_direction(view, TO_LREAL(x), TO_LREAL(y)), scene);
  layer_values(&first, values);
}

/* values[k][j] to float k of lane j's pixel, for the lanes in the tile. */
CLRT_INLINE void store_layers(const pixel_block* block, float values[CLRT_LAYER_FLOATS][CLRT_LANES],
                              __global float* layers) {
  for (int j = 0; j < CLRT_LANES; ++j) {
    if (!lane_in_tile(block, j)) continue;
    const int idx = lane_tile_y(block, j) * block->tile_w + lane_tile_x(block, j);
    for (int k = 0; k < CLRT_LAYER_FLOATS; ++k) layers[idx * CLRT_LAYER_FLOATS + k] = values[k][j];
  }
}
#endif

#endif /* CLRT_LAYERS_H */
