/* clrt_query_all.h - the scene-wide queries by testing every primitive, in
 * index order (the book's loops): builds without -DCLRT_BVH take
 * closest_intersection() and any_intersection() from here (clrt_query.h
 * states what they answer). The loops over the flat primitives serve the
 * hierarchy's builds too: planes are not in its leaves (clrt_bvh.h). */
#ifndef CLRT_QUERY_ALL_H
#define CLRT_QUERY_ALL_H

#include "clrt_flat.h"
#include "clrt_sphere.h"

/* Closest plane or triangle hit in (tmin, tmax), folded into *closest and
 * *best (ties to the lower id), for the loops over every primitive. With
 * the hierarchy only the planes come here (triangles are in its leaves). */
CLRT_INLINE void closest_flat(const vec3* O, const vec3* D, real tmin, real tmax, lint self, const scene_data* scene,
                              int with_triangles, lreal* closest, lint* best, lint* tests) {
  __global const clrt_params* params = scene->params;
  for (int k = 0; k < CLRT_PLANE_COUNT(params); ++k) {
    const int id = PLANE_ID0(params) + k;
    const lreal t = plane_distance(O, D, &scene->planes[k]);
    const lint nearer = (t < *closest) & (tmin < t) & (t < tmax) & (self != id);
    *closest = nearer ? t : *closest;
    *best = nearer ? (lint)id : *best;
  }
  *tests += (lint)CLRT_PLANE_COUNT(params);
#if CLRT_HAS_TRIANGLES
  if (!with_triangles) return;
  const ray_shear shear = shear_of(D);
  for (int k = 0; k < CLRT_TRIANGLE_COUNT(params); ++k) {
    const int id = TRIANGLE_ID0(params) + k;
    const lreal t = triangle_distance(O, &shear, &scene->triangles[k], TRIANGLE_LO(scene, k));
    const lint nearer = (t < *closest) & (tmin < t) & (t < tmax) & (self != id);
    *closest = nearer ? t : *closest;
    *best = nearer ? (lint)id : *best;
  }
  *tests += (lint)CLRT_TRIANGLE_COUNT(params);
#endif
}

/* Whether a plane or triangle blocks (tmin, tmax), per lane (for the lanes
 * of `active`; stops early when all are blocked). */
CLRT_INLINE lint any_flat(const vec3* O, const vec3* D, real tmin, real tmax, lint self, lint active,
                          const scene_data* scene, int with_triangles, lint* tests) {
  __global const clrt_params* params = scene->params;
  lint blocked = 0;
  for (int k = 0; k < CLRT_PLANE_COUNT(params); ++k) {
    const lreal t = plane_distance(O, D, &scene->planes[k]);
    blocked |= (tmin < t) & (t < tmax) & (self != PLANE_ID0(params) + k);
  }
  *tests += (lint)CLRT_PLANE_COUNT(params);
#if CLRT_HAS_TRIANGLES
  if (!with_triangles) return blocked;
  const ray_shear shear = shear_of(D);
  *tests += (lint)CLRT_TRIANGLE_COUNT(params);
  for (int k = 0; k < CLRT_TRIANGLE_COUNT(params); ++k) {
    if (ALL(blocked | !active)) break;
    const lreal t = triangle_distance(O, &shear, &scene->triangles[k], TRIANGLE_LO(scene, k));
    blocked |= (tmin < t) & (t < tmax) & (self != TRIANGLE_ID0(params) + k);
  }
#endif
  return blocked;
}

#ifndef CLRT_BVH
/* Closest hit in (tmin, tmax) per lane; the primitive id or -1. */
CLRT_INLINE lint closest_intersection(const vec3* O, const vec3* D, real tmin, real tmax, lint self, lint active,
                                      const scene_data* scene, lreal* t_out, lint* tests) {
  (void)active; /* (every lane's test costs the same as one lane's) */
  __global const clrt_params* params = scene->params;
  *tests += (lint)CLRT_SPHERE_COUNT(params);
  lreal closest = REAL_INFINITY;
  lint best = -1;
  CLRT_UNROLL for (int i = 0; i < CLRT_SPHERE_COUNT(params); ++i) {
    lreal t1, t2;
    intersect(O, D, scene->spheres, i, self == i, &t1, &t2);
    lint nearer = (t1 < closest) & (tmin < t1) & (t1 < tmax);
    closest = nearer ? t1 : closest;
    best = nearer ? (lint)i : best;
    nearer = (t2 < closest) & (tmin < t2) & (t2 < tmax);
    closest = nearer ? t2 : closest;
    best = nearer ? (lint)i : best;
  }
#if CLRT_HAS_PLANES || CLRT_HAS_TRIANGLES
  closest_flat(O, D, tmin, tmax, self, scene, 1, &closest, &best, tests);
#endif
  *t_out = closest;
  return best;
}

/* Any hit in (tmin, tmax) per lane: the book asks ClosestIntersection for a
 * blocker, but only whether one exists matters, so testing stops as soon as
 * every lane that needs the answer (`active`) has found one. */
CLRT_INLINE lint any_intersection(const vec3* O, const vec3* D, real tmin, real tmax, lint self, lint active,
                                  const scene_data* scene, lint* tests) {
  __global const clrt_params* params = scene->params;
  /* counted as every sphere, like the first bounce of the book's loop */
  *tests += (lint)CLRT_SPHERE_COUNT(params);
  lint blocked = 0;
  for (int i = 0; i < CLRT_SPHERE_COUNT(params); ++i) {
#ifndef CLRT_SHADOW_ALL_SPHERES /* (measurement knob: no early exit) */
    if (ALL(blocked | !active)) break;
#endif
    lreal t1, t2;
    intersect(O, D, scene->spheres, i, self == i, &t1, &t2);
    blocked |= ((tmin < t1) & (t1 < tmax)) | ((tmin < t2) & (t2 < tmax));
  }
#if CLRT_HAS_PLANES || CLRT_HAS_TRIANGLES
  if (!ALL(blocked | !active)) blocked |= any_flat(O, D, tmin, tmax, self, active & !blocked, scene, 1, tests);
#endif
  return blocked;
}
#endif /* CLRT_BVH */

#endif /* CLRT_QUERY_ALL_H */
