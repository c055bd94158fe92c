/* clrt_samples.h - a pixel's colour from its camera rays: the one ray
 * through its centre, or supersampling's N x N grid (--spp N,
 * clrt_params.spp), uniform or adaptive.
 *
 * Supersampling: pixel (x, y) is sampled at the canvas points
 * (x + o_i, y + o_j), o_k = (k + 0.5) / N - 0.5 for k = 0..N-1, sample
 * s = j * N + i; N = 1 is the one ray through (x, y). The samples' colours
 * are summed unclamped and divided by N^2 before the store; the pixel's
 * classification (hit sphere, shadow mask) is that of sample 0, at
 * (x + o_0, y + o_0). The reference states the same rule
 * (host/reference/reference.cpp; tests/render/test_supersampling.cpp checks
 * that they agree). */
#ifndef CLRT_SAMPLES_H
#define CLRT_SAMPLES_H

#include "clrt_camera.h"
#include "clrt_ray_tree.h"
#include "clrt_subsample.h"

/* The colour of each lane's pixel (x, y), with its classification in
 * *hit_id and *shadow_mask. `guess` is subsampling's (one ray per pixel:
 * the host never subsamples a supersampled frame). */
CLRT_INLINE vec3 pixel_color(const camera_view* view, const ray_tree_settings* settings, const lint x, const lint y,
                             const subsample_guess* guess, const scene_data* scene, lint* hit_id, lint* shadow_mask,
                             lane_ray_counts* counts) {
  const int spp = CLRT_SAMPLES_PER_AXIS(scene->params);
  vec3 result;
  if (spp == 1) {
    /* The one ray through (x, y), apart from the sample loop below: the
     * loop around it cost the single-ray render 5% of the demo's kernel
     * time (docs/results/archive.md). */
    const vec3 D = canvas_direction(view, TO_LREAL(x), TO_LREAL(y));
#if CLRT_SUBSAMPLE == CLRT_SUBSAMPLE_INTERPOLATE
    result = v3(0, 0, 0);
    if (ANY(guess->traced))
#endif
      result = trace_camera_ray(D, view->origin, settings, 1, guess->traced, guess->assumed, scene, hit_id,
                                shadow_mask, counts);
#if CLRT_SUBSAMPLE == CLRT_SUBSAMPLE_INTERPOLATE
    take_interpolated(guess, &result, hit_id, shadow_mask);
#endif
    return result;
  }
  /* One loop, one inlined copy of the tracer, for both uniform and
   * adaptive supersampling (each call site of trace_camera_ray() is a
   * whole copy of it: separate loops made the program twice as long to
   * build). Adaptive (scene/sampling.hpp; the reference states the same
   * rule): the grid's four corner samples come first; a lane whose corners
   * hit the same primitive (or all miss) within T levels per channel keeps
   * their mean, the others go on with every other sample in order. */
  const int adaptive = scene->params->adaptive;
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
        const lreal threshold = scene->params->adaptive_threshold;
        lint flat =
            (corner_hit[1] == corner_hit[0]) & (corner_hit[2] == corner_hit[0]) & (corner_hit[3] == corner_hit[0]);
#define CORNER_SPAN(c)                                                                             \
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
    /* classification: sample 0's hit and shadows; the other corners' hits */
    lint sample_hit = -1;
    const int classify = k == 0 ? 1 : (adaptive && k < 4 ? 2 : 0);
    /* (the host never subsamples a supersampled frame) */
    const vec3 D = canvas_direction(view, TO_LREAL(x) + ox, TO_LREAL(y) + oy);
    const vec3 color = trace_camera_ray(D, view->origin, settings, classify, refine, (lint)ASSUME_NOTHING, scene,
                                        k == 0 ? hit_id : &sample_hit, shadow_mask, counts);
    if (adaptive && k < 4) {
      corner_color[k] = color;
      corner_hit[k] = k == 0 ? *hit_id : sample_hit;
    }
    if (k == 0)
      sum = color;
    else
      sum = vsel(refine, vadd(sum, color), sum);
  }
  /* The mean of the samples traced (summed unclamped). */
  const lreal samples = (adaptive && total > 4) ? (refine ? (lreal)total : (lreal)4) : (lreal)total;
  return v3(sum.x / samples, sum.y / samples, sum.z / samples);
}

#endif /* CLRT_SAMPLES_H */
