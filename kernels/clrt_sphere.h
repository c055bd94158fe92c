/* clrt_sphere.h - the ray-sphere test of each precision variant: both roots
 * of |O + tD - C|^2 = r^2 for one sphere, with the self roots of a ray that
 * starts on it. The scene-wide queries that call it are clrt_query.h's. */
#ifndef CLRT_SPHERE_H
#define CLRT_SPHERE_H

#include "clrt_math.h"

#if CLRT_PRECISION != CLRT_PRECISION_NAIVE && CLRT_PRECISION != CLRT_PRECISION_FP64
/* Ray Tracing Gems ch. 7: the roots of |f + tD|^2 = r^2 (f = O - C) given
 * c = |f|^2 - r^2, the discriminant from the perpendicular distance
 * l = f + (b/a) D and the numerically stable pair of roots q/a, c/q. */
CLRT_INLINE void stable_roots(const vec3* fp, lreal c, const vec3* Dp, real r, lreal* b_out, lreal* t1, lreal* t2) {
  const vec3 f = *fp, D = *Dp;
  lreal a = vdot(D, D);
  lreal b = -vdot(f, D);
  vec3 l = vadd(f, vscale(REAL_DIVIDE(b, a), D));
  lreal disc = a * (r * r - vdot(l, l));
  lreal q = b + copysign(REAL_SQRT(disc), b);
  *t1 = disc < 0 ? (lreal)REAL_INFINITY : REAL_DIVIDE(c, q);
  *t2 = disc < 0 ? (lreal)REAL_INFINITY : REAL_DIVIDE(q, a);
  *b_out = b;
}
#endif

#if CLRT_PRECISION == CLRT_PRECISION_ROBUST
/* The roots with f = O - C and c = |f|^2 - r^2 in float-float, for the
 * spheres the host flags (host/render/conditioning.hpp): their radius or
 * distance is large against epsilon, and c, the difference of two nearly
 * equal large numbers, would be off by more than epsilon allows for rays that
 * start near the surface. */
CLRT_INLINE void compensated_roots(const vec3* Op, const vec3* Dp, __global const clrt_sphere* s, lreal* b, lreal* t1,
                                   lreal* t2) {
  const vec3 O = *Op;
  const real r = s->radius;
  lreal fxh, fxl, fyh, fyl, fzh, fzl;
  two_sum(O.x, -s->center[0], &fxh, &fxl);
  two_sum(O.y, -s->center[1], &fyh, &fyl);
  two_sum(O.z, -s->center[2], &fzh, &fzl);
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
  stable_roots(&f, c, Dp, r, b, t1, t2);
}

/* cheap_roots()'s arithmetic on values of type T, from O and D (anything
 * with members x, y, z: vectors of the lanes' rays, or one ray's scalars)
 * and the sphere (C = (cx, cy, cz), r: scalars, or a sphere per lane):
 * writes *t1, *t2 and *b_out. A macro, so that the lanes' test of one
 * sphere and one ray's test of a sphere per lane (clrt_leaf_alone.h) round
 * alike: the same expressions, so the same contractions. */
#define CHEAP_ROOTS(T, O, D, cx, cy, cz, r, b_out, t1, t2)                                                            \
  const T g_x_ = (cx) - (O).x, g_y_ = (cy) - (O).y, g_z_ = (cz) - (O).z;                                              \
  const T a_ = vdot(D, D);                                                                                            \
  const T b_ = g_x_ * (D).x + g_y_ * (D).y + g_z_ * (D).z;                                                            \
  const T x_x_ = g_y_ * (D).z - g_z_ * (D).y, x_y_ = g_z_ * (D).x - g_x_ * (D).z, x_z_ = g_x_ * (D).y - g_y_ * (D).x; \
  const T disc_ = a_ * ((r) * (r)) - (x_x_ * x_x_ + x_y_ * x_y_ + x_z_ * x_z_);                                       \
  const T sq_ = REAL_SQRT(disc_);                                                                                     \
  *(t1) = disc_ < 0 ? (T)REAL_INFINITY : REAL_DIVIDE(b_ - sq_, a_);                                                   \
  *(t2) = disc_ < 0 ? (T)REAL_INFINITY : REAL_DIVIDE(b_ + sq_, a_);                                                   \
  *(b_out) = b_

/* The roots in plain float, for the spheres the host leaves unflagged:
 * g = C - O, b = g.D and the discriminant b^2 - a c in Lagrange's form
 * a r^2 - |g x D|^2, roots (b -+ sqrt) / a. It needs no c, no division but
 * the roots' and is as fast as the book's formula (measured,
 * docs/results/archive.md); its rounding, u |g| in the ray's distance from the
 * centre, is that of the Ray Tracing Gems form, where the book's b^2 - 4ac
 * loses u |g|^2 / r (with it, unit spheres reflected in a sphere of radius
 * 2000 around the camera came out wrong on 18% of the pixels). A ray that
 * starts near the surface gets its near root to ~u r / |D|, far below
 * epsilon for the spheres the host leaves to this path
 * (host/render/conditioning.hpp). */
CLRT_INLINE void cheap_roots(const vec3* Op, const vec3* Dp, real cx, real cy, real cz, real r, lreal* b_out, lreal* t1,
                             lreal* t2) {
  const vec3 O = *Op, D = *Dp;
  CHEAP_ROOTS(lreal, O, D, cx, cy, cz, r, b_out, t1, t2);
}

/* Whether sphere `index` (at s) takes the compensated path: a constant in
 * specialized builds, one for all spheres (CLRT_COMPENSATED_SPHERES) or one
 * per sphere with the unrolled counts (CLRT_COMPENSATED_FLAGS), else its
 * flag, read at run time. */
#if defined(CLRT_COMPENSATED_SPHERES)
#define SPHERE_COMPENSATED(index, s) CLRT_COMPENSATED_SPHERES
#elif defined(CLRT_SPECIALIZED) && defined(CLRT_COMPENSATED_FLAGS) && CLRT_N_SPHERES > 0
__constant int clrt_compensated_flags[CLRT_N_SPHERES] = {CLRT_COMPENSATED_FLAGS};
#define SPHERE_COMPENSATED(index, s) (clrt_compensated_flags[index])
#else
#define SPHERE_COMPENSATED(index, s) ((s)->compensated)
#endif
/* The same flag for a hierarchy's leaf copy (clrt_leaf_sphere) whose radius
 * field is `w`: its sign bit, unless the build makes it a constant. */
#if defined(CLRT_COMPENSATED_SPHERES)
#define LEAF_COMPENSATED(w) CLRT_COMPENSATED_SPHERES
#else
#define LEAF_COMPENSATED(w) signbit(w)
#endif
#else
#define LEAF_COMPENSATED(w) 0 /* (no compensated path) */
#endif

/* A ray that starts on the sphere (where `self` is set): its roots are 0
 * and 2b/a, b = (C - O).D and a = D.D, exactly, not what the rounding of
 * its origin would make them. One place for the lanes' test
 * (float_sphere_roots()) and one ray's test of a sphere per lane
 * (clrt_leaf_alone.h). */
#define SELF_ROOTS(T, self, b, a, t1, t2) \
  (t1) = (self) ? (T)0 : (t1);            \
  (t2) = (self) ? REAL_DIVIDE(2 * (b), (a)) : (t2)

#if CLRT_PRECISION != CLRT_PRECISION_NAIVE && CLRT_PRECISION != CLRT_PRECISION_FP64
/* Both roots of |O + tD - C|^2 = r^2 in a float variant, or (inf, inf), for
 * a sphere given by value (C = (cx, cy, cz) and r, the hi parts: the scene's
 * record or the hierarchy's leaf copy, clrt_leaf_sphere, give the same
 * floats and so the same roots); its record `s` is read only by the
 * compensated path (robust, `compensated` set). `self` is set in the lanes
 * whose O lies on this sphere (the hit a secondary ray starts from). */
CLRT_INLINE void float_sphere_roots(const vec3* Op, const vec3* Dp, real cx, real cy, real cz, real r, int compensated,
                                    __global const clrt_sphere* s, lint self, lreal* t1, lreal* t2) {
  lreal b, u1, u2;
#if CLRT_PRECISION == CLRT_PRECISION_ROBUST
  /* uniform across the lanes: every lane tests the same sphere */
  if (compensated)
    compensated_roots(Op, Dp, s, &b, &u1, &u2);
  else
    cheap_roots(Op, Dp, cx, cy, cz, r, &b, &u1, &u2);
#else
  (void)compensated;
  (void)s;
  const vec3 O = *Op;
  vec3 f = v3(O.x - cx, O.y - cy, O.z - cz);
  lreal c = vdot(f, f) - r * r;
  stable_roots(&f, c, Dp, r, &b, &u1, &u2);
#endif
#if CLRT_SELF_ROOTS
  const vec3 D = *Dp;
  SELF_ROOTS(lreal, self, b, vdot(D, D), u1, u2);
#endif
  *t1 = u1;
  *t2 = u2;
}
#endif

/* Both roots of |O + tD - C|^2 = r^2 for sphere `index`, or (inf, inf).
 * `self` is set in the lanes whose O lies on this sphere (the hit a
 * secondary ray starts from). */
CLRT_INLINE void intersect(const vec3* Op, const vec3* Dp, __global const clrt_sphere* spheres, int index, lint self,
                           lreal* t1, lreal* t2) {
  __global const clrt_sphere* s = &spheres[index];
#if CLRT_PRECISION == CLRT_PRECISION_NAIVE || CLRT_PRECISION == CLRT_PRECISION_FP64
  /* The book, literally. */
  const vec3 O = *Op, D = *Dp;
  const real Cx = REAL_FROM_HI_LO(s->center[0], s->center_lo[0]), Cy = REAL_FROM_HI_LO(s->center[1], s->center_lo[1]),
             Cz = REAL_FROM_HI_LO(s->center[2], s->center_lo[2]);
  const real r = REAL_FROM_HI_LO(s->radius, s->radius_lo);
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
#if CLRT_PRECISION == CLRT_PRECISION_ROBUST
  const int compensated = SPHERE_COMPENSATED(index, s);
#else
  const int compensated = 0;
#endif
  float_sphere_roots(Op, Dp, s->center[0], s->center[1], s->center[2], s->radius, compensated, s, self, t1, t2);
#endif
}

#endif /* CLRT_SPHERE_H */
