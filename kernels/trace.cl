/* trace.cl - the render kernel: the book's image, a tile at a time. Each
 * work-item shades a block of CLRT_LANES pixels, one per SIMD lane; every
 * lane runs exactly the per-pixel algorithm (its own rays, its own slots of
 * the tree walk) with branches turned into per-lane masks. This file is the
 * entry points only: what a launch does, in order, each step a call into the
 * part that owns it.
 *
 * A tile is one launch of `render` over its columns. With subsampling
 * (-DCLRT_SUBSAMPLE, clrt_subsample.h) it is two: interpolate launches
 * `render` over the even columns, then over the odd ones (one entry point:
 * PoCL compiles each on its own, and both launches shade); shade launches
 * `camera_hits` over the even columns, then `render` over all. A program
 * defines only the entry points its host launches.
 *
 * The parts, each included once (host/cl/kernel_source.cpp expands them):
 *   clrt_layout.h       structs and codes shared with the host
 *   clrt_kernel_args.h  the entry points' arguments, shared with the host
 *   clrt_config.h       the -D options from the host, defaults, derived switches
 *   clrt_lanes.h        the precision's scalar, lane types and mask helpers
 *   clrt_math.h         3-vectors, hi/lo values, per-precision arithmetic
 *   clrt_scene.h        the scene's buffers as one struct, the primitive ids
 *   clrt_sphere.h       ray-sphere roots per precision (one sphere)
 *   clrt_flat.h         ray-plane and watertight ray-triangle tests (one primitive)
 *   clrt_query.h        the scene-wide closest-hit and any-hit queries, from:
 *     clrt_query_all.h    testing every primitive, and
 *     clrt_bvh.h          walking the hierarchy (-DCLRT_BVH)
 *   clrt_shade.h        hit material, ComputeLighting with its shadow rays, reflection, refraction
 *   clrt_ray_tree.h     a camera ray and its tree of reflected and refracted rays (trace_camera_ray)
 *   clrt_camera.h       camera rays: canvas point to direction
 *   clrt_block.h        which tile pixel each lane shades
 *   clrt_subsample.h    subsampling's two launches (--subsample)
 *   clrt_samples.h      a pixel's colour: one ray, or N x N (--spp, adaptive)
 *   clrt_film.h         the stores: colour, classes, ray counters
 *   clrt_layers.h       the AOV layers' first hit and store (-DCLRT_OUT_LAYERS)
 *   clrt_device_status.h  checks of a work-item's own run (the status word) */
#include "clrt_block.h"
#include "clrt_camera.h"
#include "clrt_device_status.h"
#include "clrt_film.h"
#include "clrt_kernel_args.h"
#include "clrt_layers.h"
#include "clrt_ray_tree.h"
#include "clrt_samples.h"
#include "clrt_subsample.h"

/* Shades the block's pixels of a tile launch (the columns of first_column
 * and column_step: every column of the tile, or with subsampling one parity
 * of them, clrt_subsample.h). */
__kernel void render(CLRT_RENDER_PARAMS) {
  const pixel_block block =
      block_of((int)get_global_id(0), (int)get_global_id(1), first_column, column_step, tile_w, tile_h);
  if (!block_in_tile(&block)) return;
  const scene_data scene = {params, spheres, lights, nodes, primitives, leaf_spheres, planes, triangles, triangles_lo, triangle_slots, materials};
  const camera_view view = camera_of(params);
  /* the canvas point of each lane's pixel */
  lint x, y;
  canvas_point(&view, x0 + lanes_tile_x(&block), y0 + lanes_tile_y(&block), &x, &y);
  const subsample_guess guess = guess_from_neighbours(&block, x0, classes, colors);

  const ray_tree_settings settings = ray_tree_settings_of(params);
  lint hit_id = -1, shadow_mask = 0;
  lane_ray_counts counts = {(lint)0, (lint)0, (lint)0, (lint)0, (lint)0};
  const vec3 result = pixel_color(&view, &settings, x, y, &guess, &scene, &hit_id, &shadow_mask, &counts);
#ifdef CLRT_OUT_LAYERS
  /* The AOV layers: the first hit of the ray through the pixel's centre. */
  float layer_floats[CLRT_LAYER_FLOATS][CLRT_LANES];
  pixel_layers(&view, x, y, &scene, layer_floats);
#endif

  store_pixels(&block, x0, result, hit_id, shadow_mask, &counts, colors, classes, counters);
#ifdef CLRT_OUT_LAYERS
  store_layers(&block, layer_floats, layers);
#endif
  CHECK_LOOP_LIMIT(params, status);
}

#if CLRT_SUBSAMPLE == CLRT_SUBSAMPLE_SHADE
/* Shade's first launch: the camera hits of the even columns, which render
 * then shades and its odd columns assume (clrt_subsample.h). */
__kernel void camera_hits(CLRT_RENDER_PARAMS) {
  const pixel_block block =
      block_of((int)get_global_id(0), (int)get_global_id(1), first_column, column_step, tile_w, tile_h);
  if (!block_in_tile(&block)) return;
  const scene_data scene = {params, spheres, lights, nodes, primitives, leaf_spheres, planes, triangles, triangles_lo, triangle_slots, materials};
  store_camera_hits(&block, x0, y0, &scene, classes, counters);
  CHECK_LOOP_LIMIT(params, status);
}
#endif
