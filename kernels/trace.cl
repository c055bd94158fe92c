/* trace.cl - one work-item per pixel: primary ray, shadow rays and
 * bounded-depth reflections with an explicit stack (no recursion).
 *
 * Build-time configuration (all -D options are produced in one place on the
 * host, host/build_options.cpp):
 *   CLRT_PREC            0 naive, 1 stable, 2 robust (default), 3 fast, 4 fp64
 *   CLRT_SPECIALIZED     scene-specific build: the counts below are constants
 *   CLRT_DEPTH, CLRT_N_SPHERES, CLRT_N_LIGHTS
 *   CLRT_HAS_AMBIENT, CLRT_HAS_POINT, CLRT_HAS_DIRECTIONAL,
 *   CLRT_HAS_SPECULAR, CLRT_HAS_REFLECTIVE  (0/1; generic build: all 1)
 *   CLRT_COUNT_RAYS      write per-pixel ray counters
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
#define NSPH CLRT_N_SPHERES
#define NLIG CLRT_N_LIGHTS
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

/* ---- scalar type ------------------------------------------------------ */
#if CLRT_PREC == CLRT_P_FP64
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
typedef double real;
typedef double3 real3;
#define RINF ((double)INFINITY)
/* hi + lo rebuilds the host's double to ~48 bits */
#define LD(hi, lo) ((double)(hi) + (double)(lo))
#else
typedef float real;
typedef float3 real3;
#define RINF INFINITY
#define LD(hi, lo) (hi)
#endif
#define LD3(a, lo) ((real3)(LD((a)[0], (lo)[0]), LD((a)[1], (lo)[1]), LD((a)[2], (lo)[2])))

#if CLRT_PREC == CLRT_P_FAST
#define RSQRT_DIV(x) native_sqrt(x)
#define RDIV(a, b) native_divide((a), (b))
#define RPOW(a, b) native_powr((a), (b))
#else
#define RSQRT_DIV(x) sqrt(x)
#define RDIV(a, b) ((a) / (b))
#define RPOW(a, b) pow((a), (b))
#endif

#ifdef CLRT_COUNT_RAYS
#define COUNT(field, n) (counts.field += (n))
#else
#define COUNT(field, n) ((void)0)
#endif

/* ---- error-free transformations (robust mode) ------------------------- */
#if CLRT_PREC == CLRT_P_ROBUST
/* s + e == a + b exactly (Knuth's TwoSum; no reassociation is allowed by
 * OpenCL C unless -cl-unsafe-math-optimizations, which robust never uses). */
inline float2 two_sum(float a, float b) {
  float s = a + b;
  float bb = s - a;
  float e = (a - (s - bb)) + (b - bb);
  return (float2)(s, e);
}
/* (hi, lo) sum of squares of a float-float 3-vector, as float-float. */
inline float2 ff_norm2(float3 h, float3 l) {
  float p0 = h.x * h.x, p1 = h.y * h.y, p2 = h.z * h.z;
  float e0 = fma(h.x, h.x, -p0) + 2.0f * h.x * l.x;
  float e1 = fma(h.y, h.y, -p1) + 2.0f * h.y * l.y;
  float e2 = fma(h.z, h.z, -p2) + 2.0f * h.z * l.z;
  float2 s = two_sum(p0, p1);
  float2 t = two_sum(s.x, p2);
  return (float2)(t.x, s.y + t.y + e0 + e1 + e2);
}
#endif

/* Both roots of |O + tD - C|^2 = r^2, or (inf, inf). `self` is true when O
 * lies on this sphere (the hit a secondary ray starts from). */
inline void intersect(real3 O, real3 D, __global const clrt_sphere* s, bool self, real* t1, real* t2) {
  const real3 C = LD3(s->center, s->center_lo);
  const real r = LD(s->radius, s->radius_lo);
#if CLRT_PREC == CLRT_P_NAIVE || CLRT_PREC == CLRT_P_FP64
  /* The book, literally. */
  real3 CO = O - C;
  real a = dot(D, D);
  real b = 2 * dot(CO, D);
  real c = dot(CO, CO) - r * r;
  real disc = b * b - 4 * a * c;
  if (disc < 0) {
    *t1 = *t2 = RINF;
    return;
  }
  real sq = sqrt(disc);
  *t1 = (-b + sq) / (2 * a);
  *t2 = (-b - sq) / (2 * a);
#else
  /* Ray Tracing Gems ch. 7: discriminant from the perpendicular distance and
   * the numerically stable pair of roots q/a, c/q. */
#if CLRT_PREC == CLRT_P_ROBUST
  /* f = O - C and c = |f|^2 - r^2 in float-float: c is the product of two
   * nearly equal large numbers' difference, the source of self-hits. */
  float2 fx = two_sum(O.x, -C.x), fy = two_sum(O.y, -C.y), fz = two_sum(O.z, -C.z);
  float3 fh = (float3)(fx.x, fy.x, fz.x);
  float3 fl = (float3)(fx.y - s->center_lo[0], fy.y - s->center_lo[1], fz.y - s->center_lo[2]);
  float2 f2 = ff_norm2(fh, fl);
  float rr = r * r;
  float rr_e = fma(r, r, -rr) + 2.0f * r * s->radius_lo;
  float2 cd = two_sum(f2.x, -rr);
  real c = cd.x + (cd.y + (f2.y - rr_e));
  real3 f = fh + fl;
#else
  real3 f = O - C;
  real c = dot(f, f) - r * r;
#endif
  real a = dot(D, D);
  real b = -dot(f, D);
#if CLRT_SELF_ROOTS
  if (self) {
    *t1 = 0;
    *t2 = RDIV(2 * b, a);
    return;
  }
#endif
  real3 l = f + RDIV(b, a) * D;
  real disc = a * (r * r - dot(l, l));
  if (disc < 0) {
    *t1 = *t2 = RINF;
    return;
  }
  real q = b + copysign(RSQRT_DIV(disc), b);
  *t1 = RDIV(c, q);
  *t2 = RDIV(q, a);
#endif
}

/* Closest hit in (tmin, tmax); returns the sphere index or -1. */
inline int closest_intersection(real3 O, real3 D, real tmin, real tmax, int self, __global const clrt_params* P,
                                __global const clrt_sphere* spheres, real* t_out) {
  real closest = RINF;
  int best = -1;
  for (int i = 0; i < NSPH; ++i) {
    real t1, t2;
    intersect(O, D, &spheres[i], i == self, &t1, &t2);
    if (t1 < closest && tmin < t1 && t1 < tmax) {
      closest = t1;
      best = i;
    }
    if (t2 < closest && tmin < t2 && t2 < tmax) {
      closest = t2;
      best = i;
    }
  }
  *t_out = closest;
  return best;
}

/* Any hit in (tmin, tmax): the book asks ClosestIntersection for a blocker,
 * but only whether one exists matters, so stop at the first. */
inline bool any_intersection(real3 O, real3 D, real tmin, real tmax, int self, __global const clrt_params* P,
                             __global const clrt_sphere* spheres) {
  for (int i = 0; i < NSPH; ++i) {
    real t1, t2;
    intersect(O, D, &spheres[i], i == self, &t1, &t2);
    if ((tmin < t1 && t1 < tmax) || (tmin < t2 && t2 < tmax)) return true;
  }
  return false;
}

inline real3 reflect_ray(real3 R, real3 N) { return 2 * dot(N, R) * N - R; }

typedef struct {
  int primary, shadow, reflection, sphere_tests;
} counters;

__kernel void render(__global const clrt_params* P, __global const clrt_sphere* spheres,
                     __global const clrt_light* lights, __global float* out, __global int* aux,
                     __global clrt_ray_counts* ray_counts, const int x0, const int y0, const int tile_w,
                     const int tile_h) {
  const int gx = (int)get_global_id(0), gy = (int)get_global_id(1);
  if (gx >= tile_w || gy >= tile_h) return;
  const int W = P->width, H = P->height;
  const int col = x0 + gx, row = y0 + gy;
  const int x = col - W / 2;
  const int y = H / 2 - 1 - row;
#ifdef CLRT_COUNT_RAYS
  counters counts = {1, 0, 0, 0};
#endif

  /* CanvasToViewport, then the camera rotation. */
  const real3 d = (real3)((real)x * (real)P->viewport[0] / (real)W, (real)y * (real)P->viewport[1] / (real)H,
                          (real)P->proj_d);
  real m[9];
  for (int k = 0; k < 9; ++k) m[k] = LD(P->rotation[k], P->rotation_lo[k]);
  real3 D = (real3)(m[0] * d.x + m[1] * d.y + m[2] * d.z, m[3] * d.x + m[4] * d.y + m[5] * d.z,
                    m[6] * d.x + m[7] * d.y + m[8] * d.z);
  real3 O = LD3(P->origin, P->origin_lo);
  const real eps = (real)P->epsilon;
  const real3 background = (real3)(P->background[0], P->background[1], P->background[2]);

  /* Explicit stack: one frame (local colour, reflectivity) per bounce that
   * continues; unwound below as (1 - r) * local + r * reflected. */
  real3 stack_local[STACK_SIZE];
  real stack_r[STACK_SIZE];
  int sp = 0;
  real3 result = background;
  real tmin = 1;
  int self = -1; /* sphere the current ray starts on */
  int hit_id = -1, shadow_mask = 0;
  const int depth = DEPTH;

  for (int bounce = 0; bounce <= depth; ++bounce) {
    real t;
    int si = closest_intersection(O, D, tmin, RINF, self, P, spheres, &t);
#ifdef CLRT_COUNT_RAYS
    counts.sphere_tests += NSPH;
#endif
    if (si < 0) {
      result = background;
      break;
    }
    __global const clrt_sphere* S = &spheres[si];
    const real3 C = LD3(S->center, S->center_lo);
    const real3 Pt = O + t * D;
    real3 N = Pt - C;
    N = N * (1 / length(N));
    const real3 V = -D;
    const real spec = S->specular;
    if (bounce == 0) hit_id = si;

    /* ComputeLighting */
    real intensity = 0;
    const real length_n = length(N);
    const real length_v = length(V);
    for (int li = 0; li < NLIG; ++li) {
      __global const clrt_light* Lg = &lights[li];
      const int type = Lg->type;
#if CLRT_HAS_AMBIENT
      if (type == CLRT_LIGHT_AMBIENT) {
        intensity += Lg->intensity;
        continue;
      }
#endif
      real3 L;
      real tmax;
#if CLRT_HAS_POINT && CLRT_HAS_DIRECTIONAL
      if (type == CLRT_LIGHT_POINT) {
        L = LD3(Lg->vec, Lg->vec_lo) - Pt;
        tmax = 1;
      } else {
        L = LD3(Lg->vec, Lg->vec_lo);
        tmax = RINF;
      }
#elif CLRT_HAS_POINT
      L = LD3(Lg->vec, Lg->vec_lo) - Pt;
      tmax = 1;
#elif CLRT_HAS_DIRECTIONAL
      L = LD3(Lg->vec, Lg->vec_lo);
      tmax = RINF;
#else
      continue;
#endif
#if CLRT_HAS_POINT || CLRT_HAS_DIRECTIONAL
#ifdef CLRT_COUNT_RAYS
      counts.shadow += 1;
      counts.sphere_tests += NSPH;
#endif
      if (any_intersection(Pt, L, eps, tmax, si, P, spheres)) {
        if (bounce == 0 && li < 32) shadow_mask |= (int)(1u << li);
        continue;
      }
      const real n_dot_l = dot(N, L);
      if (n_dot_l > 0) intensity += Lg->intensity * RDIV(n_dot_l, length_n * length(L));
#if CLRT_HAS_SPECULAR
      if (spec != -1) {
        const real3 R = reflect_ray(L, N);
        const real r_dot_v = dot(R, V);
        if (r_dot_v > 0) intensity += Lg->intensity * RPOW(RDIV(r_dot_v, length(R) * length_v), spec);
      }
#endif
#endif
    }
    const real3 local_color = intensity * (real3)(S->color[0], S->color[1], S->color[2]);
    const real r = S->reflective;
#if CLRT_HAS_REFLECTIVE
    if (bounce >= depth || r <= 0) {
      result = local_color;
      break;
    }
    stack_local[sp] = local_color;
    stack_r[sp] = r;
    ++sp;
    const real3 Rdir = reflect_ray(V, N);
    O = Pt;
    D = Rdir;
    self = si;
    tmin = eps;
#ifdef CLRT_COUNT_RAYS
    counts.reflection += 1;
#endif
#else
    result = local_color;
    break;
#endif
  }
  while (sp > 0) {
    --sp;
    result = (1 - stack_r[sp]) * stack_local[sp] + stack_r[sp] * result;
  }

  const int idx = gy * tile_w + gx;
  out[idx * 3 + 0] = (float)result.x;
  out[idx * 3 + 1] = (float)result.y;
  out[idx * 3 + 2] = (float)result.z;
  aux[idx * 2 + 0] = hit_id;
  aux[idx * 2 + 1] = shadow_mask;
#ifdef CLRT_COUNT_RAYS
  ray_counts[idx].primary = counts.primary;
  ray_counts[idx].shadow = counts.shadow;
  ray_counts[idx].reflection = counts.reflection;
  ray_counts[idx].sphere_tests = counts.sphere_tests;
#endif
}
