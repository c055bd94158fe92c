/* clrt_leaf_alone.h - a leaf's triangles against the ray of one lane of a
 * block, one triangle per SIMD lane: the leaf test of a lane that walks a
 * subtree alone (clrt_bvh.h: ray_closest(), ray_any(), in blocks of lanes
 * over a hierarchy of triangles only). The block's own leaf test
 * (closest_in_leaf()) takes the triangles one at a time against every
 * lane's ray: for one ray, all but one of its SIMD lanes are wasted, and a
 * lone walk is what a block's reflection rays mostly take.
 * The arithmetic is triangle_distance()'s (clrt_flat.h: the same macro,
 * WATERTIGHT_DISTANCE) on the same ray and triangle, the ray's values
 * broadcast and the triangles' gathered: the same distances, bit for bit. The nearest is
 * then picked by the rule of the loops over every primitive - the smaller
 * distance, then the lower id - which does not depend on the order in
 * which the triangles are tested. Included by clrt_bvh.h. */
#ifndef CLRT_LEAF_ALONE_H
#define CLRT_LEAF_ALONE_H

#if CLRT_LANES > 1 && CLRT_HAS_TRIANGLES && !CLRT_BVH_SPHERES
#define CLRT_LEAF_ALONE 1

/* Triangles per test: 8 (a merged leaf's most, kWideLeafMax; larger leaves
 * take several). */
#define ALONE_WIDTH 8
typedef float8 alone_real;
typedef int8 alone_int;

/* One lane's ray, as scalars (its shear: clrt_flat.h's ray_shear). */
typedef struct lone_ray {
  real ox, oy, oz, sx, sy, sz;
  int kx, ky, kz, self, lane;
} lone_ray;

CLRT_INLINE lone_ray lone_ray_of(const vec3* O, const ray_shear* s, lint self, int j) {
  lone_ray r;
  r.ox = LANE_OF((*O).x, j);
  r.oy = LANE_OF((*O).y, j);
  r.oz = LANE_OF((*O).z, j);
  r.sx = LANE_OF(s->sx, j);
  r.sy = LANE_OF(s->sy, j);
  r.sz = LANE_OF(s->sz, j);
  r.kx = LINT_LANE(s->kx, j);
  r.ky = LINT_LANE(s->ky, j);
  r.kz = LINT_LANE(s->kz, j);
  r.self = LINT_LANE(self, j);
  r.lane = j;
  return r;
}

CLRT_INLINE real alone_min_real(alone_real x) {
  const float4 h = BMIN(x.lo, x.hi);
  const float2 g = BMIN(h.lo, h.hi);
  return BMIN(g.x, g.y);
}
CLRT_INLINE int alone_min_int(alone_int x) {
  const int4 h = min(x.lo, x.hi);
  const int2 g = min(h.lo, h.hi);
  return min(g.x, g.y);
}
CLRT_INLINE int alone_any(alone_int m) {
  const int4 h = m.lo | m.hi;
  const int2 g = h.lo | h.hi;
  return (g.x | g.y) != 0;
}

/* The distances of ray r to triangles tri[0 .. n) (1 <= n <= ALONE_WIDTH;
 * lane l holds triangle min(l, n - 1)), with their ids (`id`): infinity
 * where it misses, and for its own triangle (id r->self). */
CLRT_INLINE alone_real alone_distances(const lone_ray* r, __global const clrt_triangle* tri, int n, int id0,
                                       alone_int* id) {
#pragma OPENCL FP_CONTRACT OFF
  /* each record as three float4s: v0 and material, v1 and index, v2 */
  float4 p[ALONE_WIDTH], q[ALONE_WIDTH], w4[ALONE_WIDTH];
  for (int l = 0; l < ALONE_WIDTH; ++l) {
    __global const float* f = (__global const float*)&tri[min(l, n - 1)];
    p[l] = vload4(0, f);
    q[l] = vload4(1, f);
    w4[l] = vload4(2, f);
  }
#define GATHER(v, c) ((alone_real)(v[0].c, v[1].c, v[2].c, v[3].c, v[4].c, v[5].c, v[6].c, v[7].c))
  const alone_real Ax = GATHER(p, x) - r->ox, Ay = GATHER(p, y) - r->oy, Az = GATHER(p, z) - r->oz;
  const alone_real Bx = GATHER(q, x) - r->ox, By = GATHER(q, y) - r->oy, Bz = GATHER(q, z) - r->oz;
  const alone_real Cx = GATHER(w4, x) - r->ox, Cy = GATHER(w4, y) - r->oy, Cz = GATHER(w4, z) - r->oz;
  *id = (alone_int)id0 + as_int8(GATHER(q, w));
#undef GATHER
  WATERTIGHT_DISTANCE(alone_real, alone_int, Ax, Ay, Az, Bx, By, Bz, Cx, Cy, Cz, r->kx, r->ky, r->kz, r->sx, r->sy,
                      r->sz, t);
  return *id == (alone_int)r->self ? (alone_real)REAL_INFINITY : t;
}

/* Lane r->lane's closest hit among leaf entries [first, first + count) in
 * (tmin, tmax), below its `closest` so far (ties to the lower id). */
CLRT_INLINE void closest_in_leaf_alone(int first, int count, const lone_ray* r, real tmin, real tmax,
                                       const scene_data* scene, lreal* closest, lint* best, lint* tests) {
  const int id0 = TRIANGLE_ID0(scene->params);
  real nearest_t = LANE_OF(*closest, r->lane);
  int nearest = LINT_LANE(*best, r->lane);
  for (int k = first; k < first + count; k += ALONE_WIDTH) {
    alone_int id;
    const alone_real t = alone_distances(r, &scene->triangles[k], min(ALONE_WIDTH, first + count - k), id0, &id);
    const alone_int in = ((alone_real)tmin < t) & (t < (alone_real)tmax);
    if (!alone_any(in)) continue;
    /* the least distance, then the least id at it */
    const real m = alone_min_real(in ? t : (alone_real)INFINITY);
    const int i = alone_min_int((in & (t == (alone_real)m)) ? id : (alone_int)INT_MAX);
    if (m < nearest_t || (m == nearest_t && i < nearest)) {
      nearest_t = m;
      nearest = i;
    }
  }
  const lint mine = LANE_IOTA == (lint)r->lane;
  *closest = mine ? (lreal)nearest_t : *closest;
  *best = mine ? (lint)nearest : *best;
  *tests += mine ? (lint)count : (lint)0;
}

/* Whether lane r->lane's ray meets a triangle of leaf entries [first,
 * first + count) in (tmin, tmax). */
CLRT_INLINE int any_in_leaf_alone(int first, int count, const lone_ray* r, real tmin, real tmax,
                                  const scene_data* scene, lint* tests) {
  const int id0 = TRIANGLE_ID0(scene->params);
  *tests += LANE_IOTA == (lint)r->lane ? (lint)count : (lint)0;
  for (int k = first; k < first + count; k += ALONE_WIDTH) {
    alone_int id;
    const alone_real t = alone_distances(r, &scene->triangles[k], min(ALONE_WIDTH, first + count - k), id0, &id);
    if (alone_any(((alone_real)tmin < t) & (t < (alone_real)tmax))) return 1;
  }
  return 0;
}
#endif

#endif /* CLRT_LEAF_ALONE_H */
