/* clrt_leaf_alone.h - a leaf's primitives against the ray of one lane of a
 * block, one primitive per SIMD lane: the leaf test of a lane that walks a
 * subtree alone (clrt_bvh.h: ray_closest(), ray_any(), in blocks of lanes
 * over a hierarchy of triangles only, or of spheres only in the robust
 * variant). The block's own leaf test (closest_in_leaf()) takes the
 * primitives one at a time against every lane's ray: for one ray, all but
 * one of its SIMD lanes are wasted, and a lone walk is what a block's
 * reflection rays mostly take.
 * The arithmetic is the lanes' test's (clrt_flat.h's WATERTIGHT_DISTANCE,
 * clrt_sphere.h's CHEAP_ROOTS: the same macros) on the same ray and
 * primitive, the ray's values broadcast and the primitives' gathered: the
 * same distances, bit for bit. The nearest is then picked by the rule of
 * the loops over every primitive - the smaller distance, then the lower id
 * - which does not depend on the order of the tests. Included by
 * clrt_bvh.h. */
#ifndef CLRT_LEAF_ALONE_H
#define CLRT_LEAF_ALONE_H

#if CLRT_LANES > 1 && CLRT_HAS_TRIANGLES && !CLRT_BVH_SPHERES
#define CLRT_LEAF_ALONE 1
#define ALONE_TRIANGLES 1
#elif CLRT_LANES > 1 && !CLRT_HAS_TRIANGLES && CLRT_PRECISION == CLRT_PRECISION_ROBUST
/* (spheres: robust's plain-float roots; a compensated sphere is tested the
 * block's way, the others' variants keep the block's leaf test) */
#define CLRT_LEAF_ALONE 1
#define ALONE_TRIANGLES 0
#endif

#ifdef CLRT_LEAF_ALONE
/* Primitives per step: 4, larger leaves take several steps (8 to a step,
 * a merged leaf's most, gathered twice the records for the small leaves
 * most walks meet: 2-7% slower, docs/results/wide-hierarchy.md). */
#define ALONE_WIDTH 4
typedef float4 alone_real;
typedef int4 alone_int;

/* One lane's ray as scalars: origin, direction, its shear (clrt_flat.h's
 * ray_shear), the primitive it starts on, and the lane. */
typedef struct lone_vec {
  real x, y, z;
} lone_vec;
typedef struct lone_ray {
  lone_vec o, d;
  real sx, sy, sz;
  int kx, ky, kz, self, lane;
} lone_ray;

CLRT_INLINE lone_ray lone_ray_of(const vec3* O, const vec3* D SHEAR_ARG, lint self, int j) {
  lone_ray r;
  r.o.x = LANE_OF((*O).x, j);
  r.o.y = LANE_OF((*O).y, j);
  r.o.z = LANE_OF((*O).z, j);
  r.d.x = LANE_OF((*D).x, j);
  r.d.y = LANE_OF((*D).y, j);
  r.d.z = LANE_OF((*D).z, j);
#if ALONE_TRIANGLES
  r.sx = LANE_OF(shear->sx, j);
  r.sy = LANE_OF(shear->sy, j);
  r.sz = LANE_OF(shear->sz, j);
  r.kx = LINT_LANE(shear->kx, j);
  r.ky = LINT_LANE(shear->ky, j);
  r.kz = LINT_LANE(shear->kz, j);
#endif
  r.self = LINT_LANE(self, j);
  r.lane = j;
  return r;
}

/* Lanes of t inside (tmin, tmax). */
#define ALONE_ANY(m) (lane_or4(m) != 0)
#define ALONE_INSIDE(t, tmin, tmax) (((alone_real)(tmin) < (t)) & ((t) < (alone_real)(tmax)))

#define GATHER(v, c) ((alone_real)(v[0].c, v[1].c, v[2].c, v[3].c))

/* Both distances of ray r to leaf entries [k, k + n) (1 <= n <=
 * ALONE_WIDTH; lane l holds entry k + min(l, n - 1)), and their ids:
 * infinity where it misses (a triangle's twice; none for the triangle it
 * starts on, the self roots for the sphere it starts on). Returns 1, with
 * nothing set, where the step holds a compensated sphere. */
CLRT_INLINE int alone_roots(const lone_ray* r, const scene_data* scene, int k, int n, alone_real* t1, alone_real* t2,
                            alone_int* id) {
#if ALONE_TRIANGLES
#pragma OPENCL FP_CONTRACT OFF
  /* each record as three float4s: v0 and material, v1 and index, v2 */
  float4 p[ALONE_WIDTH], q[ALONE_WIDTH], w4[ALONE_WIDTH];
  for (int l = 0; l < ALONE_WIDTH; ++l) {
    __global const float* f = (__global const float*)&scene->triangles[k + min(l, n - 1)];
    p[l] = vload4(0, f);
    q[l] = vload4(1, f);
    w4[l] = vload4(2, f);
  }
  const alone_real Ax = GATHER(p, x) - r->o.x, Ay = GATHER(p, y) - r->o.y, Az = GATHER(p, z) - r->o.z;
  const alone_real Bx = GATHER(q, x) - r->o.x, By = GATHER(q, y) - r->o.y, Bz = GATHER(q, z) - r->o.z;
  const alone_real Cx = GATHER(w4, x) - r->o.x, Cy = GATHER(w4, y) - r->o.y, Cz = GATHER(w4, z) - r->o.z;
  *id = (alone_int)TRIANGLE_ID0(scene->params) + as_int4(GATHER(q, w));
  WATERTIGHT_DISTANCE(alone_real, alone_int, Ax, Ay, Az, Bx, By, Bz, Cx, Cy, Cz, r->kx, r->ky, r->kz, r->sx, r->sy,
                      r->sz, t);
  *t1 = *id == (alone_int)r->self ? (alone_real)REAL_INFINITY : t;
  *t2 = *t1;
#else
  /* the leaf copies (clrt_leaf_sphere: centre, radius with the compensated
   * flag in its sign bit) and the entries' sphere indices */
  float4 c[ALONE_WIDTH];
  int index[ALONE_WIDTH];
  for (int l = 0; l < ALONE_WIDTH; ++l) {
    c[l] = vload4(0, scene->leaf_spheres[k + min(l, n - 1)].center);
    index[l] = scene->primitives[k + min(l, n - 1)] & CLRT_PRIMITIVE_INDEX_MASK;
  }
  const alone_real w = GATHER(c, w);
#if defined(CLRT_COMPENSATED_SPHERES)
  if (CLRT_COMPENSATED_SPHERES) return 1;
#else
  if (ALONE_ANY(signbit(w))) return 1;
#endif
  *id = vload4(0, index);
  alone_real b;
  CHEAP_ROOTS(alone_real, r->o, r->d, GATHER(c, x), GATHER(c, y), GATHER(c, z), fabs(w), &b, t1, t2);
#if CLRT_SELF_ROOTS
  /* (float_sphere_roots()'s self roots) */
  SELF_ROOTS(alone_real, *id == (alone_int)r->self, b, vdot(r->d, r->d), *t1, *t2);
#endif
#endif
  return 0;
}
#undef GATHER

/* Lane r->lane's closest hit among leaf entries [first, first + count) in
 * (tmin, tmax), below its `closest` so far (ties to the lower id); a step
 * that holds a compensated sphere goes the block's way (closest_in_leaf(),
 * every lane). */
CLRT_INLINE void closest_in_leaf_alone(int first, int count, const lone_ray* r, const vec3* O, const vec3* D SHEAR_ARG,
                                       real tmin, real tmax, lint self, const scene_data* scene, lreal* closest,
                                       lint* best, lint* tests) {
  const lint mine = LANE_IOTA == (lint)r->lane;
  real nearest_t = LANE_OF(*closest, r->lane);
  int nearest = LINT_LANE(*best, r->lane);
  for (int k = first; k < first + count; k += ALONE_WIDTH) {
    const int n = min(ALONE_WIDTH, first + count - k);
    alone_real t1, t2;
    alone_int id;
    if (alone_roots(r, scene, k, n, &t1, &t2, &id)) {
      *closest = mine ? (lreal)nearest_t : *closest;
      *best = mine ? (lint)nearest : *best;
      closest_in_leaf(k, n, O, D SHEAR_PASS_PTR, tmin, tmax, self, scene, closest, best, tests);
      nearest_t = LANE_OF(*closest, r->lane);
      nearest = LINT_LANE(*best, r->lane);
      continue;
    }
    *tests += mine ? (lint)n : (lint)0;
    const alone_int in1 = ALONE_INSIDE(t1, tmin, tmax);
    const alone_int in2 = ALONE_INSIDE(t2, tmin, tmax);
    if (!ALONE_ANY(in1 | in2)) continue;
    /* the least distance, then the least id at it (the lanes outside the
     * interval, below tmax <= REAL_INFINITY, take no part) */
    const real m = BMIN(lane_min4_real(in1 ? t1 : (alone_real)REAL_INFINITY),
                        lane_min4_real(in2 ? t2 : (alone_real)REAL_INFINITY));
    const int i = lane_min4(((in1 & (t1 == (alone_real)m)) | (in2 & (t2 == (alone_real)m))) ? id : (alone_int)INT_MAX);
    if (m < nearest_t || (m == nearest_t && i < nearest)) {
      nearest_t = m;
      nearest = i;
    }
  }
  *closest = mine ? (lreal)nearest_t : *closest;
  *best = mine ? (lint)nearest : *best;
}

/* Whether lane r->lane's ray meets a primitive of leaf entries [first,
 * first + count) in (tmin, tmax) (a compensated sphere's step: the block's
 * way, any_in_leaf(), every lane). */
CLRT_INLINE int any_in_leaf_alone(int first, int count, const lone_ray* r, const vec3* O, const vec3* D SHEAR_ARG,
                                  real tmin, real tmax, lint self, const scene_data* scene, lint* blocked,
                                  lint* tests) {
  for (int k = first; k < first + count; k += ALONE_WIDTH) {
    const int n = min(ALONE_WIDTH, first + count - k);
    alone_real t1, t2;
    alone_int id;
    if (alone_roots(r, scene, k, n, &t1, &t2, &id)) {
      *blocked |= any_in_leaf(k, n, O, D SHEAR_PASS_PTR, tmin, tmax, self, scene, tests);
      if (LINT_LANE(*blocked, r->lane)) return 1;
      continue;
    }
    *tests += LANE_IOTA == (lint)r->lane ? (lint)n : (lint)0;
    if (ALONE_ANY(ALONE_INSIDE(t1, tmin, tmax) | ALONE_INSIDE(t2, tmin, tmax))) return 1;
  }
  return 0;
}
#endif

#endif /* CLRT_LEAF_ALONE_H */
