/* clrt_ray_tree.h - the rays of one camera ray: primary, shadow (through
 * compute_lighting(), clrt_shade.h), and the tree of reflected and
 * refracted rays below it, walked without recursion within bounded memory.
 * The host states the same tree's size and cut-off (host/scene/ray_tree.hpp)
 * and the reference the same colours (host/reference/reference.cpp). */
#ifndef CLRT_RAY_TREE_H
#define CLRT_RAY_TREE_H

#include "clrt_shade.h"
#include "clrt_subsample.h"

/* What every ray of a frame's trees shares. */
typedef struct ray_tree_settings {
  real epsilon;    /* the t_min of secondary rays (the book's epsilon) */
  vec3 background; /* a miss's colour */
  int depth;       /* the recursion depth: levels of rays below the camera ray */
} ray_tree_settings;

CLRT_INLINE ray_tree_settings ray_tree_settings_of(__global const clrt_params* params) {
  ray_tree_settings settings;
  settings.epsilon = REAL_FROM_HI_LO(params->epsilon, params->epsilon_lo);
  settings.background = v3(params->background[0], params->background[1], params->background[2]);
  settings.depth = CLRT_RECURSION_DEPTH(params);
  return settings;
}

/* One camera ray per lane, from `camera` along camera_D, and the rays it
 * spawns: the book's TraceRay without recursion, in the lanes of `active`.
 * Returns its colour; `classify` 1 (a pixel's first sample) stores its
 * primary hit and blocked lights in *hit_id and *shadow_mask, 2 its primary
 * hit only, 0 neither. `assumed` is the primary hit subsampling assumes per
 * lane (assumed_intersection(), clrt_subsample.h; used by
 * CLRT_SUBSAMPLE_SHADE only).
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
CLRT_INLINE vec3 trace_camera_ray(const vec3 camera_D, const vec3 camera, const ray_tree_settings* settings,
                                  const int classify, const lint active, const lint assumed, const scene_data* scene,
                                  lint* hit_id, lint* shadow_mask, lane_ray_counts* counts) {
  const real epsilon = settings->epsilon;
  const vec3 background = settings->background;
  const int depth = settings->depth;
  vec3 D = camera_D;
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
      const lint searched =
          closest_intersection(&O, &D, tmin, REAL_INFINITY, self, search, scene, &searched_t, &searched_tests);
      hit = search ? searched : hit;
      t = search ? searched_t : t;
      tests += search ? searched_tests : (lint)0;
    }
#else
    const lint hit = closest_intersection(&O, &D, tmin, REAL_INFINITY, self, alive, scene, &t, &tests);
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

#endif /* CLRT_RAY_TREE_H */
