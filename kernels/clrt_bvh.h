/* clrt_bvh.h - closest-hit and any-hit queries through the bounding volume
 * hierarchy (clrt_layout.h: clrt_bvh_node), built with -DCLRT_BVH in place
 * of the loops over every sphere of clrt_intersect.h. Same answers as those
 * loops, lane by lane:
 *  - a node is entered when any lane's ray may meet its box inside that
 *    lane's interval; every sphere the loops would test and could win is in
 *    such a node (boxes are padded on the host beyond every rounding of the
 *    sphere test, and the slab test below widens its interval by far more
 *    than its own rounding);
 *  - equal distances go to the lower sphere index, as in the loops, which
 *    see spheres in index order.
 * The lanes of a work-item walk the tree together (a node is visited when
 * any lane needs it; the sphere test is per lane), nearer child first by the
 * first lane's direction. The walk is iterative; its stack holds one node per
 * level at most, so CLRT_BVH_MAX_DEPTH entries suffice (the host never builds
 * deeper). */
#ifndef CLRT_BVH_H
#define CLRT_BVH_H

#include "clrt_math.h"

/* Relative widening of a box's entry/exit distances: float slab arithmetic
 * is off by a few ulps (2^-22 or so); 2^-16 keeps every ray a box may hold. */
#define CLRT_BOX_SLACK ((real)1.52587890625e-05)

/* Per-lane reciprocal direction; a zero component becomes a tiny one of the
 * same sign, so that no slab gives 0 * inf = NaN. */
CLRT_INLINE vec3 inverse_direction(const vec3* D) {
  const lreal tiny = (lreal)1e-30f;
  return v3(1 / ((*D).x == 0 ? copysign(tiny, (*D).x) : (*D).x), 1 / ((*D).y == 0 ? copysign(tiny, (*D).y) : (*D).y),
            1 / ((*D).z == 0 ? copysign(tiny, (*D).z) : (*D).z));
}

/* min and max as selects: no operand is NaN here (finite box corners and
 * origins times nonzero finite reciprocals), and PoCL's fmin/fmax keep NaN rules
 * that cost ~12% of a frame (docs/developer/kernel.md). */
#define BMIN(a, b) ((a) < (b) ? (a) : (b))
#define BMAX(a, b) ((a) > (b) ? (a) : (b))

/* Lanes whose ray may meet the box within (tmin, limit), the entry and exit
 * distances widened by CLRT_BOX_SLACK. */
CLRT_INLINE lint box_overlap(__global const clrt_bvh_node* node, const vec3* O, const vec3* inverse, real tmin,
                             lreal limit) {
  const lreal x0 = ((real)node->lower[0] - (*O).x) * (*inverse).x, x1 = ((real)node->upper[0] - (*O).x) * (*inverse).x;
  const lreal y0 = ((real)node->lower[1] - (*O).y) * (*inverse).y, y1 = ((real)node->upper[1] - (*O).y) * (*inverse).y;
  const lreal z0 = ((real)node->lower[2] - (*O).z) * (*inverse).z, z1 = ((real)node->upper[2] - (*O).z) * (*inverse).z;
  lreal enter = BMAX(BMAX(BMIN(x0, x1), BMIN(y0, y1)), BMIN(z0, z1));
  lreal leave = BMIN(BMIN(BMAX(x0, x1), BMAX(y0, y1)), BMAX(z0, z1));
  const lreal slack = (fabs(enter) + fabs(leave)) * CLRT_BOX_SLACK;
  enter -= slack;
  leave += slack;
  return (enter <= leave) & (leave >= tmin) & (enter <= limit);
}

/* The child to visit first: the one on the side the first lane's ray comes
 * from along the node's split axis. */
CLRT_INLINE int nearer_child(__global const clrt_bvh_node* node, const vec3* D) {
  const int axis = -node->count - 1;
  const real d = FIRST_LANE(axis == 0 ? (*D).x : axis == 1 ? (*D).y : (*D).z);
  return d >= 0 ? node->first : node->first + 1;
}

/* An inner node: go on with the nearer child, keep the other for later. */
CLRT_INLINE int descend(__global const clrt_bvh_node* node, const vec3* D, int* stack, int* top) {
  const int near = nearer_child(node, D);
  stack[(*top)++] = near == node->first ? node->first + 1 : node->first;
  return near;
}

/* The distances to leaf entry `entry` (a sphere's two roots, or a triangle's
 * distance twice); returns the primitive's id. A ray never meets the
 * triangle it starts on again (its id is `self`). */
#if CLRT_HAS_TRIANGLES
#define SHEAR_ARG , const ray_shear* shear
#define SHEAR_PASS , &shear
#else
#define SHEAR_ARG
#define SHEAR_PASS
#endif
CLRT_INLINE int entry_roots(int entry, const vec3* O, const vec3* D SHEAR_ARG, lint self, const scene_data* scene,
                            lreal* t1, lreal* t2, lint* tests) {
  const int i = entry & CLRT_PRIMITIVE_INDEX_MASK;
  *tests += (lint)1;
#if CLRT_HAS_TRIANGLES
  if ((entry >> CLRT_PRIMITIVE_KIND_SHIFT) == CLRT_PRIMITIVE_TRIANGLE) {
    const int id = TRIANGLE_ID0(scene->params) + i;
    const lreal t = triangle_distance(O, shear, &scene->triangles[i]);
    *t1 = self == id ? (lreal)REAL_INFINITY : t;
    *t2 = *t1;
    return id;
  }
#endif
  intersect(O, D, scene->spheres, i, self == i, t1, t2);
  return i;
}

/* Closest hit in (tmin, tmax) per lane: the sphere index or -1. */
CLRT_INLINE lint closest_intersection(const vec3* O, const vec3* D, real tmin, real tmax, lint self,
                                      const scene_data* scene, lreal* t_out, lint* tests) {
  __global const clrt_bvh_node* nodes = scene->nodes;
  __global const int* primitives = scene->primitives;
  const vec3 inverse = inverse_direction(D);
  lreal closest = REAL_INFINITY;
  lint best = -1;
#if CLRT_HAS_PLANES
  /* planes first (they are not in the hierarchy): a near plane shortens
   * every box test below */
  closest_flat(O, D, tmin, tmax, self, scene, 0, &closest, &best, tests);
#endif
#if CLRT_HAS_TRIANGLES
  const ray_shear shear = shear_of(D);
#endif
  int stack[CLRT_BVH_MAX_DEPTH];
  int top = 0, index = 0;
  for (;;) {
    __global const clrt_bvh_node* node = &nodes[index];
    if (ANY(box_overlap(node, O, &inverse, tmin, BMIN(closest, (lreal)tmax)))) {
      if (node->count < 0) {
        index = descend(node, D, stack, &top);
        continue;
      }
      for (int k = node->first; k < node->first + node->count; ++k) {
        lreal t1, t2;
        const int i = entry_roots(primitives[k], O, D SHEAR_PASS, self, scene, &t1, &t2, tests);
        /* ties to the lower index, as the loop over every sphere gives them */
        lint nearer = ((t1 < closest) | ((t1 == closest) & ((lint)i < best))) & (tmin < t1) & (t1 < tmax);
        closest = nearer ? t1 : closest;
        best = nearer ? (lint)i : best;
        nearer = ((t2 < closest) | ((t2 == closest) & ((lint)i < best))) & (tmin < t2) & (t2 < tmax);
        closest = nearer ? t2 : closest;
        best = nearer ? (lint)i : best;
      }
    }
    if (top == 0) break;
    index = stack[--top];
  }
  *t_out = closest;
  return best;
}

/* Any hit in (tmin, tmax) per lane, for the lanes in `active`; the walk ends
 * when every one of them is blocked. */
CLRT_INLINE lint any_intersection(const vec3* O, const vec3* D, real tmin, real tmax, lint self, lint active,
                                  const scene_data* scene, lint* tests) {
  __global const clrt_bvh_node* nodes = scene->nodes;
  __global const int* primitives = scene->primitives;
  const vec3 inverse = inverse_direction(D);
  lint blocked = 0;
#if CLRT_HAS_PLANES
  blocked = any_flat(O, D, tmin, tmax, self, active, scene, 0, tests);
#endif
#if CLRT_HAS_TRIANGLES
  const ray_shear shear = shear_of(D);
#endif
  int stack[CLRT_BVH_MAX_DEPTH];
  int top = 0, index = 0;
  for (;;) {
    const lint open = active & !blocked;
    if (!ANY(open)) break;
    __global const clrt_bvh_node* node = &nodes[index];
    if (ANY(open & box_overlap(node, O, &inverse, tmin, (lreal)tmax))) {
      if (node->count < 0) {
        index = descend(node, D, stack, &top);
        continue;
      }
      for (int k = node->first; k < node->first + node->count; ++k) {
        lreal t1, t2;
        entry_roots(primitives[k], O, D SHEAR_PASS, self, scene, &t1, &t2, tests);
        blocked |= ((tmin < t1) & (t1 < tmax)) | ((tmin < t2) & (t2 < tmax));
      }
    }
    if (top == 0) break;
    index = stack[--top];
  }
  return blocked;
}

#endif /* CLRT_BVH_H */
