/* trace.cl - primary ray, shadow rays and bounded-depth reflections with an
 * explicit stack (no recursion), per pixel.
 *
 * A work-item shades CLRT_LANES horizontally adjacent pixels, one per SIMD
 * lane of `lreal` (float8 by default in specialized float builds; 1 = one
 * pixel per work-item, a plain scalar, in generic and fp64 builds). Every
 * lane runs exactly the per-pixel algorithm - its own ray, its own explicit
 * stack (lane j of each frame) - with branches turned into per-lane masks;
 * loops stop when no lane needs them any more. PoCL does not vectorize this
 * kernel across work-items by itself (see docs/performance.md), so the lanes
 * are written out; the scalar build runs the same code with 1-lane masks.
 *
 * Build-time configuration (all -D options are produced in one place on the
 * host, host/build_options.cpp):
 *   CLRT_PREC            0 naive, 1 stable, 2 robust (default), 3 fast, 4 fp64
 *   CLRT_SPECIALIZED     scene-specific build: the counts below are constants
 *   CLRT_DEPTH
 *   CLRT_N_SPHERES, CLRT_N_LIGHTS  specialized, small scenes only: constant
 *                        loop bounds, loops unrolled (the host leaves them out
 *                        past a bound, kMaxUnrolled* in build_options.hpp)
 *   CLRT_HAS_AMBIENT, CLRT_HAS_POINT, CLRT_HAS_DIRECTIONAL,
 *   CLRT_HAS_SPECULAR, CLRT_HAS_REFLECTIVE  (0/1; generic build: all 1)
 *   CLRT_COUNT_RAYS      write per-pixel ray counters
 *   CLRT_LANES           pixels per work-item: 1 (default), 4, 8 or 16
 *   CLRT_LIGHT_TYPES     specialized: each light's type, e.g. "0,1,2"
 */
#include "clrt_layout.h"

#define CLRT_P_NAIVE 0
#define CLRT_P_STABLE 1
#define CLRT_P_ROBUST 2
#define CLRT_P_FAST 3
#define CLRT_P_FP64 4

#ifndef CLRT_PREC
#define CLRT_PREC CLRT_P_ROBUST
#endif
/* Robust and fast modes know which sphere a secondary ray starts on: for it
 * |f|^2 - r^2 is exactly 0, so its roots are exactly 0 and 2b/a. Computing
 * them from a rounded hit point instead is what lets float32 rays hit their
 * own sphere (shadow acne on the radius-5000 floor). */
#if CLRT_PREC == CLRT_P_ROBUST || CLRT_PREC == CLRT_P_FAST
#define CLRT_SELF_ROOTS 1
#else
#define CLRT_SELF_ROOTS 0
#endif

#ifdef CLRT_SPECIALIZED
#ifdef CLRT_N_SPHERES
#define NSPH CLRT_N_SPHERES
#define NLIG CLRT_N_LIGHTS
#else
#define NSPH (P->n_spheres)
#define NLIG (P->n_lights)
#endif
#define DEPTH CLRT_DEPTH
#define STACK_SIZE (CLRT_DEPTH + 1)
#else
#define NSPH (P->n_spheres)
#define NLIG (P->n_lights)
#define DEPTH (min(P->depth, CLRT_MAX_DEPTH))
#define STACK_SIZE (CLRT_MAX_DEPTH + 1)
#ifndef CLRT_HAS_AMBIENT
#define CLRT_HAS_AMBIENT 1
#endif
#ifndef CLRT_HAS_POINT
#define CLRT_HAS_POINT 1
#endif
#ifndef CLRT_HAS_DIRECTIONAL
#define CLRT_HAS_DIRECTIONAL 1
#endif
#ifndef CLRT_HAS_SPECULAR
#define CLRT_HAS_SPECULAR 1
#endif
#ifndef CLRT_HAS_REFLECTIVE
#define CLRT_HAS_REFLECTIVE 1
#endif
#endif

/* Helpers are forced inline (PoCL otherwise keeps intersect() out of line,
 * a call per ray-sphere test), and specialized builds of small scenes unroll
 * the loops whose bounds are constants there. */
#define CLRT_INLINE inline __attribute__((always_inline))
#if defined(CLRT_SPECIALIZED) && defined(CLRT_N_SPHERES)
#define CLRT_UNROLL _Pragma("unroll")
#else
#define CLRT_UNROLL
#endif

/* ---- scalar and 3-vector types --------------------------------------- */
#if CLRT_PREC == CLRT_P_FP64
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
typedef double real;
#define RINF ((double)INFINITY)
/* hi + lo rebuilds the host's double to ~48 bits */
#define LD(hi, lo) ((double)(hi) + (double)(lo))
#else
typedef float real;
#define RINF INFINITY
#define LD(hi, lo) (hi)
#endif

/* Lane types: lreal holds one value per pixel of the work-item, lint the
 * matching integers and masks. Masks are what comparisons return: 0/1 for
 * scalars, 0/-1 for vectors, so they are only ever combined with & | ! and
 * other masks of the same kind, and consumed by ?: or ANY/ALL. */
#ifndef CLRT_LANES
#define CLRT_LANES 1
#endif
#if CLRT_LANES == 1
typedef real lreal;
typedef int lint;
#define ANY(m) (m)
#define ALL(m) (m)
#define TO_LREAL(i) ((real)(i))
#define LANE_IOTA 0
#elif CLRT_LANES == 4
typedef float4 lreal;
typedef int4 lint;
#define TO_LREAL(i) convert_float4(i)
#define LANE_IOTA ((int4)(0, 1, 2, 3))
#elif CLRT_LANES == 8
typedef float8 lreal;
typedef int8 lint;
#define TO_LREAL(i) convert_float8(i)
#define LANE_IOTA ((int8)(0, 1, 2, 3, 4, 5, 6, 7))
#elif CLRT_LANES == 16
typedef float16 lreal;
typedef int16 lint;
#define TO_LREAL(i) convert_float16(i)
#define LANE_IOTA ((int16)(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15))
#else
#error "CLRT_LANES must be 1, 4, 8 or 16"
#endif
#if CLRT_LANES > 1
#if CLRT_PREC == CLRT_P_FP64
#error "fp64 builds use CLRT_LANES=1"
#endif
#define ANY(m) any(m)
#define ALL(m) all(m)
#endif
#define MASK_TRUE ((lint)(CLRT_LANES == 1 ? 1 : -1))
#if CLRT_LANES == 1
#define AS_LINT(x) as_int(x)
#define AS_LREAL(i) as_float(i)
#define TO_LINT(x) ((int)(x))
#else
#define LCAT(a, b) a##b
#define LXCAT(a, b) LCAT(a, b)
#define AS_LINT(x) LXCAT(as_int, CLRT_LANES)(x)
#define AS_LREAL(i) LXCAT(as_float, CLRT_LANES)(i)
#define TO_LINT(x) LXCAT(convert_int, CLRT_LANES)(x) /* truncates, like (int) */
#endif

/* A 3-vector as three lane values, not float3: a 3-component vector per
 * pixel would need one more lane dimension. Macros, not functions, because
 * structs passed or returned by value are coerced to <2 x float> pairs by the
 * target ABI. Plain component formulas (dot = x*x' + y*y' + z*z'). */
typedef struct {
  lreal x, y, z;
} vec3;
#define v3(x, y, z) ((vec3){(x), (y), (z)})
#define vadd(a, b) v3((a).x + (b).x, (a).y + (b).y, (a).z + (b).z)
#define vsub(a, b) v3((a).x - (b).x, (a).y - (b).y, (a).z - (b).z)
#define vscale(s, a) v3((s) * (a).x, (s) * (a).y, (s) * (a).z)
#define vneg(a) v3(-(a).x, -(a).y, -(a).z)
#define vdot(a, b) ((a).x * (b).x + (a).y * (b).y + (a).z * (b).z)
#define vlen(a) sqrt(vdot((a), (a)))
/* per lane: m ? a : b */
#define vsel(m, a, b) v3((m) ? (a).x : (b).x, (m) ? (a).y : (b).y, (m) ? (a).z : (b).z)
#define LD3(a, lo) v3(LD((a)[0], (lo)[0]), LD((a)[1], (lo)[1]), LD((a)[2], (lo)[2]))

#if CLRT_PREC == CLRT_P_FAST
#define RSQRT_DIV(x) native_sqrt(x)
#define RDIV(a, b) native_divide((a), (b))
#else
#define RSQRT_DIV(x) sqrt(x)
#define RDIV(a, b) ((a) / (b))
#endif
#if CLRT_PREC == CLRT_P_FP64 || defined(CLRT_LIB_POW)
#define RPOW(a, b) pow((a), (b))
#else
#define RPOW(a, b) spec_pow((a), (b))
#endif

#if CLRT_PREC != CLRT_P_FP64
/* x^s for the specular term (0 < x <~ 1, s >= 0) as exp2(s * log2(x)) in
 * plain arithmetic: the library pow is an out-of-line call, and one call in
 * the work-item body stops PoCL from vectorizing across work-items. Error:
 * log2 has a few ulp relative error (the sqrt(2) range split avoids the
 * cancellation near x = 1), so x^s = 2^(s log2 x) carries an absolute error
 * below u * ln2 * max(y * |log2 y|) ~ 0.4 ulp of 1 on top of exp2's own few
 * ulp - far below one 8-bit level of the 0..255 colour. */
CLRT_INLINE lreal spec_log2(lreal x) {
  lint ix = AS_LINT(x);
  lint e = ((ix >> 23) & 0xff) - 127;
  lreal m = AS_LREAL((ix & 0x007fffff) | 0x3f800000); /* [1, 2) */
  lint big = m > 1.41421356f;
  m = big ? 0.5f * m : m;
  e = big ? e + 1 : e;
  /* ln(m) = 2 atanh(t) = 2 t (1 + t^2/3 + t^4/5 + ...), |t| <= 0.172 */
  lreal t = (m - 1.0f) / (m + 1.0f);
  lreal t2 = t * t;
  lreal p = fma(t2, fma(t2, fma(t2, fma(t2, 1.0f / 9, 1.0f / 7), 1.0f / 5), 1.0f / 3), 1.0f);
  return TO_LREAL(e) + (2.0f * t * p) * 1.44269504088896341f;
}
CLRT_INLINE lreal spec_exp2(lreal y) {
  y = fmax(y, -150.0f);
  lreal fi = TO_LREAL(TO_LINT(y)); /* truncation, then to the nearest integer */
  fi = (y - fi > 0.5f) ? fi + 1.0f : fi;
  fi = (fi - y > 0.5f) ? fi - 1.0f : fi;
  lreal g = (y - fi) * 0.693147180559945309f; /* |g| <= 0.5 ln 2 */
  /* e^g, Taylor to degree 7: truncation error < 6e-9 relative */
  lreal p = fma(g, 1.0f / 5040, 1.0f / 720);
  p = fma(g, p, 1.0f / 120);
  p = fma(g, p, 1.0f / 24);
  p = fma(g, p, 1.0f / 6);
  p = fma(g, p, 0.5f);
  p = fma(g, p, 1.0f);
  p = fma(g, p, 1.0f);
  lint i = TO_LINT(fi);
  lreal scale = AS_LREAL((clamp(i, -126, 127) + 127) << 23);
  return i < -126 ? (lreal)0.0f : p * scale;
}
CLRT_INLINE lreal spec_pow(lreal x, lreal s) { return spec_exp2(s * spec_log2(x)); }
#endif

/* ---- error-free transformations (robust mode) ------------------------- */
#if CLRT_PREC == CLRT_P_ROBUST
/* s + e == a + b exactly (Knuth's TwoSum; no reassociation is allowed by
 * OpenCL C unless -cl-unsafe-math-optimizations, which robust never uses).
 * Results through pointers: a returned pair would become a <2 x float>. */
CLRT_INLINE void two_sum(lreal a, lreal b, lreal* s_out, lreal* e_out) {
  lreal s = a + b;
  lreal bb = s - a;
  *e_out = (a - (s - bb)) + (b - bb);
  *s_out = s;
}
/* (hi, lo) sum of squares of a float-float 3-vector, as float-float. */
CLRT_INLINE void ff_norm2(const vec3* h, const vec3* l, lreal* hi, lreal* lo) {
  lreal p0 = h->x * h->x, p1 = h->y * h->y, p2 = h->z * h->z;
  lreal e0 = fma(h->x, h->x, -p0) + 2.0f * h->x * l->x;
  lreal e1 = fma(h->y, h->y, -p1) + 2.0f * h->y * l->y;
  lreal e2 = fma(h->z, h->z, -p2) + 2.0f * h->z * l->z;
  lreal s, se, t, te;
  two_sum(p0, p1, &s, &se);
  two_sum(s, p2, &t, &te);
  *hi = t;
  *lo = se + te + e0 + e1 + e2;
}
#endif

/* Both roots of |O + tD - C|^2 = r^2, or (inf, inf). `self` is set in the
 * lanes whose O lies on this sphere (the hit a secondary ray starts from). */
CLRT_INLINE void intersect(const vec3* Op, const vec3* Dp, __global const clrt_sphere* s, lint self, lreal* t1,
                           lreal* t2) {
  const vec3 O = *Op, D = *Dp;
  const real Cx = LD(s->center[0], s->center_lo[0]), Cy = LD(s->center[1], s->center_lo[1]),
             Cz = LD(s->center[2], s->center_lo[2]);
  const real r = LD(s->radius, s->radius_lo);
#if CLRT_PREC == CLRT_P_NAIVE || CLRT_PREC == CLRT_P_FP64
  /* The book, literally. */
  vec3 CO = v3(O.x - Cx, O.y - Cy, O.z - Cz);
  lreal a = vdot(D, D);
  lreal b = 2 * vdot(CO, D);
  lreal c = vdot(CO, CO) - r * r;
  lreal disc = b * b - 4 * a * c;
  lreal sq = sqrt(disc);
  /* disc < 0: no hit (a select per lane, not a branch) */
  *t1 = disc < 0 ? (lreal)RINF : (-b + sq) / (2 * a);
  *t2 = disc < 0 ? (lreal)RINF : (-b - sq) / (2 * a);
#else
  /* Ray Tracing Gems ch. 7: discriminant from the perpendicular distance and
   * the numerically stable pair of roots q/a, c/q. */
#if CLRT_PREC == CLRT_P_ROBUST
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
  vec3 l = vadd(f, vscale(RDIV(b, a), D));
  lreal disc = a * (r * r - vdot(l, l));
  lreal q = b + copysign(RSQRT_DIV(disc), b);
  lreal u1 = disc < 0 ? (lreal)RINF : RDIV(c, q);
  lreal u2 = disc < 0 ? (lreal)RINF : RDIV(q, a);
#if CLRT_SELF_ROOTS
  u1 = self ? (lreal)0 : u1;
  u2 = self ? RDIV(2 * b, a) : u2;
#endif
  *t1 = u1;
  *t2 = u2;
#endif
}

/* Closest hit in (tmin, tmax) per lane; the sphere index or -1. */
CLRT_INLINE lint closest_intersection(const vec3* O, const vec3* D, real tmin, real tmax, lint self,
                                      __global const clrt_params* P, __global const clrt_sphere* spheres,
                                      lreal* t_out) {
  lreal closest = RINF;
  lint best = -1;
  CLRT_UNROLL for (int i = 0; i < NSPH; ++i) {
    lreal t1, t2;
    intersect(O, D, &spheres[i], self == i, &t1, &t2);
    lint m1 = (t1 < closest) & (tmin < t1) & (t1 < tmax);
    closest = m1 ? t1 : closest;
    best = m1 ? (lint)i : best;
    lint m2 = (t2 < closest) & (tmin < t2) & (t2 < tmax);
    closest = m2 ? t2 : closest;
    best = m2 ? (lint)i : best;
  }
  *t_out = closest;
  return best;
}

/* Any hit in (tmin, tmax) per lane: the book asks ClosestIntersection for a
 * blocker, but only whether one exists matters, so testing stops as soon as
 * every lane that needs the answer (`active`) has found one. */
CLRT_INLINE lint any_intersection(const vec3* O, const vec3* D, real tmin, real tmax, lint self, lint active,
                                  __global const clrt_params* P, __global const clrt_sphere* spheres) {
  lint blocked = 0;
  for (int i = 0; i < NSPH; ++i) {
#ifndef CLRT_SHADOW_ALL_SPHERES /* (measurement knob: no early exit) */
    if (ALL(blocked | !active)) break;
#endif
    lreal t1, t2;
    intersect(O, D, &spheres[i], self == i, &t1, &t2);
    blocked |= ((tmin < t1) & (t1 < tmax)) | ((tmin < t2) & (t2 < tmax));
  }
  return blocked;
}

/* 2 (N.R) N - R */
#define reflect_ray(R, N) vsub(vscale(2 * vdot((N), (R)), (N)), (R))

/* Light types: a specialized build knows each light's type (CLRT_LIGHT_TYPES,
 * e.g. "0,1,2"), so the type tests of the light loop fold away. */
#if defined(CLRT_SPECIALIZED) && defined(CLRT_LIGHT_TYPES) && CLRT_N_LIGHTS > 0
__constant int clrt_light_types[CLRT_N_LIGHTS] = {CLRT_LIGHT_TYPES};
#define LIGHT_TYPE(li, Lg) (clrt_light_types[li])
#else
#define LIGHT_TYPE(li, Lg) ((Lg)->type)
#endif

#ifdef CLRT_COUNT_RAYS
/* adds n in the lanes of mask m */
#define COUNT(field, m, n) (field += (m) ? (lint)(n) : (lint)0)
#else
#define COUNT(field, m, n) ((void)0)
#endif

__kernel void render(__global const clrt_params* P, __global const clrt_sphere* spheres,
                     __global const clrt_light* lights, __global float* out, __global int* aux,
                     __global clrt_ray_counts* ray_counts, const int x0, const int y0, const int tile_w,
                     const int tile_h) {
  const int gx = (int)get_global_id(0), gy = (int)get_global_id(1);
  const int px = gx * CLRT_LANES; /* first pixel of this work-item in the tile */
  if (px >= tile_w || gy >= tile_h) return;
  const int W = P->width, H = P->height;
  const lint col = x0 + px + LANE_IOTA;
  const int row = y0 + gy;
  const lint x = col - W / 2;
  const int y = H / 2 - 1 - row;
#ifdef CLRT_COUNT_RAYS
  lint n_primary = 1, n_shadow = 0, n_reflection = 0, n_tests = 0;
#endif

  /* CanvasToViewport, then the camera rotation. */
  const lreal dx = TO_LREAL(x) * LD(P->viewport[0], P->viewport_lo[0]) / (real)W;
  const real dy = (real)y * LD(P->viewport[1], P->viewport_lo[1]) / (real)H, dz = LD(P->proj_d, P->proj_d_lo);
  real m[9];
  for (int k = 0; k < 9; ++k) m[k] = LD(P->rotation[k], P->rotation_lo[k]);
  vec3 D = v3(m[0] * dx + m[1] * dy + m[2] * dz, m[3] * dx + m[4] * dy + m[5] * dz, m[6] * dx + m[7] * dy + m[8] * dz);
  vec3 O = LD3(P->origin, P->origin_lo);
  const real eps = LD(P->epsilon, P->epsilon_lo);
  const vec3 background = v3(P->background[0], P->background[1], P->background[2]);

  /* Explicit stack: one frame (local colour, reflectivity) per bounce that
   * continues; unwound below as (1 - r) * local + r * reflected. A frame is
   * pushed only by a bounce that continues, so frame k always belongs to
   * bounce k and sp (per lane) is the number of frames. */
  vec3 stack_local[STACK_SIZE];
  lreal stack_r[STACK_SIZE];
  lint sp = 0;
  vec3 result = background;
  real tmin = 1;  /* the same for all lanes: 1 for primary rays, eps after */
  lint self = -1; /* sphere the lane's current ray starts on */
  lint hit_id = -1, shadow_mask = 0;
  lint alive = MASK_TRUE; /* lanes whose ray of this bounce exists */
  const int depth = DEPTH;

  for (int bounce = 0; bounce <= depth; ++bounce) {
    lreal t;
    lint si = closest_intersection(&O, &D, tmin, RINF, self, P, spheres, &t);
    COUNT(n_tests, alive, NSPH);
    lint miss = alive & (si < 0);
    result = vsel(miss, background, result);
    alive &= !miss;
    if (!ANY(alive)) break;

    /* The hit sphere's data, per lane. */
    vec3 C = v3(0, 0, 0), color = v3(0, 0, 0);
    lreal spec = 0, refl = 0;
    for (int i = 0; i < NSPH; ++i) {
      __global const clrt_sphere* S = &spheres[i];
      lint h = si == i;
      C = vsel(h, LD3(S->center, S->center_lo), C);
      color = vsel(h, v3(S->color[0], S->color[1], S->color[2]), color);
      spec = h ? (lreal)S->specular : spec;
      refl = h ? (lreal)S->reflective : refl;
    }
    const vec3 Pt = vadd(O, vscale(t, D));
    vec3 N = vsub(Pt, C);
    N = vscale(1 / vlen(N), N);
    const vec3 V = vneg(D);
    if (bounce == 0) hit_id = alive ? si : hit_id;

    /* ComputeLighting */
    lreal intensity = 0;
    const lreal length_n = vlen(N);
    const lreal length_v = vlen(V);
    CLRT_UNROLL for (int li = 0; li < NLIG; ++li) {
      __global const clrt_light* Lg = &lights[li];
      const int type = LIGHT_TYPE(li, Lg);
      const real li_intensity = Lg->intensity;
#if CLRT_HAS_AMBIENT
      if (type == CLRT_LIGHT_AMBIENT) {
        intensity += li_intensity;
        continue;
      }
#endif
#if CLRT_HAS_POINT || CLRT_HAS_DIRECTIONAL
      const vec3 Lv = LD3(Lg->vec, Lg->vec_lo);
      vec3 L;
      real tmax;
#if CLRT_HAS_POINT && CLRT_HAS_DIRECTIONAL
      if (type == CLRT_LIGHT_POINT) {
        L = vsub(Lv, Pt);
        tmax = 1;
      } else {
        L = Lv;
        tmax = RINF;
      }
#elif CLRT_HAS_POINT
      L = vsub(Lv, Pt);
      tmax = 1;
#else
      L = Lv;
      tmax = RINF;
#endif
      COUNT(n_shadow, alive, 1);
      COUNT(n_tests, alive, NSPH);
      const lint blocked = any_intersection(&Pt, &L, eps, tmax, si, alive, P, spheres);
      if (bounce == 0 && li < 32) shadow_mask |= (blocked & alive) ? (lint)(int)(1u << li) : (lint)0;
      const lint lit = alive & !blocked;
      const lreal n_dot_l = vdot(N, L);
      intensity = (lit & (n_dot_l > 0)) ? intensity + li_intensity * RDIV(n_dot_l, length_n * vlen(L)) : intensity;
#if CLRT_HAS_SPECULAR
      const lint shiny = lit & (spec != -1);
      if (ANY(shiny)) {
        const vec3 R = reflect_ray(L, N);
        const lreal r_dot_v = vdot(R, V);
        const lint m = shiny & (r_dot_v > 0);
        intensity = m ? intensity + li_intensity * RPOW(RDIV(r_dot_v, vlen(R) * length_v), spec) : intensity;
      }
#endif
#endif
    }
    const vec3 local_color = vscale(intensity, color);
#if CLRT_HAS_REFLECTIVE
    const lint stop = bounce >= depth ? alive : alive & (refl <= 0);
#else
    const lint stop = alive;
#endif
    result = vsel(stop, local_color, result);
    alive &= !stop;
    if (!ANY(alive)) break;
    stack_local[bounce] = local_color;
    stack_r[bounce] = refl;
    sp = alive ? (lint)(bounce + 1) : sp;
    const vec3 Rdir = reflect_ray(V, N);
    O = vsel(alive, Pt, O);
    D = vsel(alive, Rdir, D);
    self = alive ? si : self;
    tmin = eps;
    COUNT(n_reflection, alive, 1);
  }
  /* Unwind: frames [sp, top) were never pushed in a lane and are skipped. */
#if CLRT_LANES == 1
  for (int k = sp - 1; k >= 0; --k) {
#else
  for (int k = min(depth, STACK_SIZE) - 1; k >= 0; --k) {
#endif
    const vec3 blended = vadd(vscale(1 - stack_r[k], stack_local[k]), vscale(stack_r[k], result));
    result = vsel(k < sp, blended, result);
  }

  /* One pixel per lane; lanes past the tile's right edge are dropped. */
#if CLRT_LANES == 1
  float rx[1] = {(float)result.x}, ry[1] = {(float)result.y}, rz[1] = {(float)result.z};
  int hid[1] = {hit_id}, smk[1] = {shadow_mask};
#ifdef CLRT_COUNT_RAYS
  int c0[1] = {n_primary}, c1[1] = {n_shadow}, c2[1] = {n_reflection}, c3[1] = {n_tests};
#endif
#else
#define LANES_TO(arr, v) LXCAT(vstore, CLRT_LANES)((v), 0, (arr))
  float rx[CLRT_LANES], ry[CLRT_LANES], rz[CLRT_LANES];
  int hid[CLRT_LANES], smk[CLRT_LANES];
  LANES_TO(rx, result.x);
  LANES_TO(ry, result.y);
  LANES_TO(rz, result.z);
  LANES_TO(hid, hit_id);
  LANES_TO(smk, shadow_mask);
#ifdef CLRT_COUNT_RAYS
  int c0[CLRT_LANES], c1[CLRT_LANES], c2[CLRT_LANES], c3[CLRT_LANES];
  LANES_TO(c0, n_primary);
  LANES_TO(c1, n_shadow);
  LANES_TO(c2, n_reflection);
  LANES_TO(c3, n_tests);
#endif
#endif
  for (int j = 0; j < CLRT_LANES; ++j) {
    if (px + j >= tile_w) break;
    const int idx = gy * tile_w + px + j;
    out[idx * 3 + 0] = rx[j];
    out[idx * 3 + 1] = ry[j];
    out[idx * 3 + 2] = rz[j];
    aux[idx * 2 + 0] = hid[j];
    aux[idx * 2 + 1] = smk[j];
#ifdef CLRT_COUNT_RAYS
    ray_counts[idx].primary = c0[j];
    ray_counts[idx].shadow = c1[j];
    ray_counts[idx].reflection = c2[j];
    ray_counts[idx].sphere_tests = c3[j];
#endif
  }
}
