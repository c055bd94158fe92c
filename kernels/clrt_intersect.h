/* clrt_intersect.h - ray-sphere intersection per precision variant, and the
 * closest-hit and any-hit queries over the scene's spheres. */
#ifndef CLRT_INTERSECT_H
#define CLRT_INTERSECT_H

#include "clrt_math.h"

/* Both roots of |O + tD - C|^2 = r^2, or (inf, inf). `self` is set in the
 * lanes whose O lies on this sphere (the hit a secondary ray starts from). */
CLRT_INLINE void intersect(const vec3* Op, const vec3* Dp, __global const clrt_sphere* s, lint self, lreal* t1,
                           lreal* t2) {
  const vec3 O = *Op, D = *Dp;
  const real Cx = REAL_FROM_HI_LO(s->center[0], s->center_lo[0]), Cy = REAL_FROM_HI_LO(s->center[1], s->center_lo[1]),
             Cz = REAL_FROM_HI_LO(s->center[2], s->center_lo[2]);
  const real r = REAL_FROM_HI_LO(s->radius, s->radius_lo);
#if CLRT_PRECISION == CLRT_PRECISION_NAIVE || CLRT_PRECISION == CLRT_PRECISION_FP64
  /* The book, literally. */
  vec3 CO = v3(O.x - Cx, O.y - Cy, O.z - Cz);
  lreal a = vdot(D, D);
  lreal b = 2 * vdot(CO, D);
  lreal c = vdot(CO, CO) - r * r;
  lreal disc = b * b - 4 * a * c;
  lreal sq = sqrt(disc);
  /* disc < 0: no hit (a select per lane, not a branch) */
  *t1 = disc < 0 ? (lreal)REAL_INFINITY : (-b + sq) / (2 * a);
  *t2 = disc < 0 ? (lreal)REAL_INFINITY : (-b - sq) / (2 * a);
#else
  /* Ray Tracing Gems ch. 7: discriminant from the perpendicular distance and
   * the numerically stable pair of roots q/a, c/q. */
#if CLRT_PRECISION == CLRT_PRECISION_ROBUST
  /* f = O - C and c = |f|^2 - r^2 in float-float: c is the product of two
   * nearly equal large numbers' difference, the source of self-hits. */
  lreal fxh, fxl, fyh, fyl, fzh, fzl;
  two_sum(O.x, -Cx, &fxh, &fxl);
  two_sum(O.y, -Cy, &fyh, &fyl);
  two_sum(O.z, -Cz, &fzh, &fzl);
  vec3 fh = v3(fxh, fyh, fzh);
  vec3 fl = v3(fxl - s->center_lo[0], fyl - s->center_lo[1], fzl - s->center_lo[2]);
  lreal f2h, f2l;
  ff_norm2(&fh, &fl, &f2h, &f2l);
  float rr = r * r;
  float rr_e = fma(r, r, -rr) + 2.0f * r * s->radius_lo;
  lreal cdh, cdl;
  two_sum(f2h, -rr, &cdh, &cdl);
  lreal c = cdh + (cdl + (f2l - rr_e));
  vec3 f = vadd(fh, fl);
#else
  vec3 f = v3(O.x - Cx, O.y - Cy, O.z - Cz);
  lreal c = vdot(f, f) - r * r;
#endif
  lreal a = vdot(D, D);
  lreal b = -vdot(f, D);
  vec3 l = vadd(f, vscale(REAL_DIVIDE(b, a), D));
  lreal disc = a * (r * r - vdot(l, l));
  lreal q = b + copysign(REAL_SQRT(disc), b);
  lreal u1 = disc < 0 ? (lreal)REAL_INFINITY : REAL_DIVIDE(c, q);
  lreal u2 = disc < 0 ? (lreal)REAL_INFINITY : REAL_DIVIDE(q, a);
#if CLRT_SELF_ROOTS
  u1 = self ? (lreal)0 : u1;
  u2 = self ? REAL_DIVIDE(2 * b, a) : u2;
#endif
  *t1 = u1;
  *t2 = u2;
#endif
}

#ifdef CLRT_BVH
#include "clrt_bvh.h"
#else
/* The queries below test every sphere; with -DCLRT_BVH clrt_bvh.h gives the
 * same answers through the hierarchy (`nodes`, `primitives`, unused here).
 * `tests` counts the sphere tests per lane. */

/* Closest hit in (tmin, tmax) per lane; the sphere index or -1. */
CLRT_INLINE lint closest_intersection(const vec3* O, const vec3* D, real tmin, real tmax, lint self,
                                      __global const clrt_params* params, __global const clrt_sphere* spheres,
                                      __global const clrt_bvh_node* nodes, __global const int* primitives,
                                      lreal* t_out, lint* tests) {
  *tests += (lint)CLRT_SPHERE_COUNT(params);
  lreal closest = REAL_INFINITY;
  lint best = -1;
  CLRT_UNROLL for (int i = 0; i < CLRT_SPHERE_COUNT(params); ++i) {
    lreal t1, t2;
    intersect(O, D, &spheres[i], self == i, &t1, &t2);
    lint nearer = (t1 < closest) & (tmin < t1) & (t1 < tmax);
    closest = nearer ? t1 : closest;
    best = nearer ? (lint)i : best;
    nearer = (t2 < closest) & (tmin < t2) & (t2 < tmax);
    closest = nearer ? t2 : closest;
    best = nearer ? (lint)i : best;
  }
  *t_out = closest;
  return best;
}

/* Any hit in (tmin, tmax) per lane: the book asks ClosestIntersection for a
 * blocker, but only whether one exists matters, so testing stops as soon as
 * every lane that needs the answer (`active`) has found one. */
CLRT_INLINE lint any_intersection(const vec3* O, const vec3* D, real tmin, real tmax, lint self, lint active,
                                  __global const clrt_params* params, __global const clrt_sphere* spheres,
                                  __global const clrt_bvh_node* nodes, __global const int* primitives, lint* tests) {
  /* counted as every sphere, like the first bounce of the book's loop */
  *tests += (lint)CLRT_SPHERE_COUNT(params);
  lint blocked = 0;
  for (int i = 0; i < CLRT_SPHERE_COUNT(params); ++i) {
#ifndef CLRT_SHADOW_ALL_SPHERES /* (measurement knob: no early exit) */
    if (ALL(blocked | !active)) break;
#endif
    lreal t1, t2;
    intersect(O, D, &spheres[i], self == i, &t1, &t2);
    blocked |= ((tmin < t1) & (t1 < tmax)) | ((tmin < t2) & (t2 < tmax));
  }
  return blocked;
}
#endif /* CLRT_BVH */

#endif /* CLRT_INTERSECT_H */
