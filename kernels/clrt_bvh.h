/* clrt_bvh.h - closest-hit and any-hit queries (clrt_query.h) through the
 * bounding volume hierarchy (clrt_layout.h: clrt_wide_node, up to
 * CLRT_BVH_WIDTH children per node), built with -DCLRT_BVH in place of the
 * loops over every primitive of clrt_query_all.h (nothing here exists in
 * other builds). Same answers as those loops, lane by lane:
 *  - a child is entered when any lane's ray may meet its box inside that
 *    lane's interval; every primitive the loops would test and could win is
 *    in such a child (boxes are padded beyond every rounding of the
 *    primitive tests: on the host for the primitive's share, here for the
 *    ray origin's, padded_origins(); and the slab test below widens its
 *    interval by far more than its own rounding);
 *  - a child is dropped only when its widened entry distance is beyond every
 *    lane's closest hit so far (strictly: a primitive at the same distance
 *    may still win the tie);
 *  - equal distances go to the lower primitive id, as in the loops, which
 *    see primitives in index order.
 * One ray per work-item (CLRT_LANES 1) tests a node's children together,
 * one SIMD lane per child (float4 or float8). A block of lanes tests the
 * children one after the other, one SIMD lane per ray, and enters a child
 * that any lane needs, for the lanes that met it; below a node that only
 * one or two lanes met, each of them walks alone (solo_closest(),
 * solo_any()). Either way the hit children, leaves and inner nodes
 * alike, are pushed nearest last, each with its entry distance (the smallest
 * over the lanes that meet it), so the nearest is visited first and a popped
 * child beyond the closest hit is skipped. Shadow rays take any hit and end
 * the walk at the first; they too go nearest first, where the usual blocker
 * is (unordered, they tested 25% more spheres: docs/results/wide-hierarchy.md). The
 * walk is iterative; CLRT_BVH_STACK entries always suffice (clrt_layout.h). */
#ifndef CLRT_BVH_H
#define CLRT_BVH_H

#include "clrt_query_all.h"

#ifdef CLRT_BVH

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

/* The ray's share of the boxes' padding (clrt_layout.h, CLRT_BVH_PAD_*):
 * the lower planes tested from O + p, the upper ones from O - p, is the box
 * widened by p on every side, p = pad x max|O|, at no cost per node. (The
 * rounding of O +- p, 2^-24 max|O|, is far inside p.) */
#define CLRT_RAY_PAD ((real)CLRT_BVH_PAD(CLRT_PRECISION, CLRT_BVH_SPHERES))
typedef struct box_origins {
  vec3 lower, upper; /* where the lower and upper planes are seen from */
} box_origins;

CLRT_INLINE box_origins padded_origins(const vec3* O) {
  const lreal p = BMAX(BMAX(fabs((*O).x), fabs((*O).y)), fabs((*O).z)) * CLRT_RAY_PAD;
  box_origins out;
  out.lower = v3((*O).x + p, (*O).y + p, (*O).z + p);
  out.upper = v3((*O).x - p, (*O).y - p, (*O).z - p);
  return out;
}

/* Lanes whose ray may meet child k's box within (tmin, limit); `enter`
 * gets their entry distances, widened by CLRT_BOX_SLACK like the exit. */
CLRT_INLINE lint child_overlap(__global const clrt_wide_node* node, int k, const box_origins* O, const vec3* inverse,
                               real tmin, lreal limit, lreal* enter_out) {
  const lreal x0 = ((real)node->lower[0][k] - O->lower.x) * (*inverse).x;
  const lreal x1 = ((real)node->upper[0][k] - O->upper.x) * (*inverse).x;
  const lreal y0 = ((real)node->lower[1][k] - O->lower.y) * (*inverse).y;
  const lreal y1 = ((real)node->upper[1][k] - O->upper.y) * (*inverse).y;
  const lreal z0 = ((real)node->lower[2][k] - O->lower.z) * (*inverse).z;
  const lreal z1 = ((real)node->upper[2][k] - O->upper.z) * (*inverse).z;
  lreal enter = BMAX(BMAX(BMIN(x0, x1), BMIN(y0, y1)), BMIN(z0, z1));
  lreal leave = BMIN(BMIN(BMAX(x0, x1), BMAX(y0, y1)), BMAX(z0, z1));
  const lreal slack = (fabs(enter) + fabs(leave)) * CLRT_BOX_SLACK;
  enter -= slack;
  leave += slack;
  *enter_out = enter;
  return (enter <= leave) & (leave >= tmin) & (enter <= limit);
}

/* One ray, every child of a node at once: the same slab test as above on
 * CLRT_BVH_WIDTH-wide vectors of the precision's scalar (the one-ray walk,
 * and a block's rays that walk alone: below). */
#if CLRT_BVH_WIDTH == 4
#define WIDE_LOAD(p) vload4(0, p)
#define WIDE_STORE(v, p) vstore4(v, 0, p)
#if CLRT_PRECISION == CLRT_PRECISION_FP64
typedef double4 wide_real;
typedef long4 wide_mask;
#define TO_WIDE_REAL(v) convert_double4(v)
#define TO_WIDE_MASK(v) convert_long4(v)
#define WIDE_MASK_TO_INT(v) convert_int4(v)
#else
typedef float4 wide_real;
typedef int4 wide_mask;
#define TO_WIDE_REAL(v) (v)
#define TO_WIDE_MASK(v) (v)
#define WIDE_MASK_TO_INT(v) (v)
#endif
#elif CLRT_BVH_WIDTH == 8
#define WIDE_LOAD(p) vload8(0, p)
#define WIDE_STORE(v, p) vstore8(v, 0, p)
#if CLRT_PRECISION == CLRT_PRECISION_FP64
typedef double8 wide_real;
typedef long8 wide_mask;
#define TO_WIDE_REAL(v) convert_double8(v)
#define TO_WIDE_MASK(v) convert_long8(v)
#define WIDE_MASK_TO_INT(v) convert_int8(v)
#else
typedef float8 wide_real;
typedef int8 wide_mask;
#define TO_WIDE_REAL(v) (v)
#define TO_WIDE_MASK(v) (v)
#define WIDE_MASK_TO_INT(v) (v)
#endif
#else
#error "CLRT_BVH_WIDTH must be 4 or 8"
#endif

/* The children whose box one ray may meet within (tmin, limit) (hit[k]
 * nonzero) and their widened entry distances; the ray's padded origins
 * (lx, ly, lz for the lower planes, ux, uy, uz for the upper) and its
 * reciprocal direction (ix, iy, iz). */
CLRT_INLINE void ray_children(__global const clrt_wide_node* node, real lx, real ly, real lz, real ux, real uy, real uz,
                              real ix, real iy, real iz, real tmin, real limit, real* enter_out, int* hit_out) {
  const wide_real x0 = (TO_WIDE_REAL(WIDE_LOAD(node->lower[0])) - lx) * ix;
  const wide_real x1 = (TO_WIDE_REAL(WIDE_LOAD(node->upper[0])) - ux) * ix;
  const wide_real y0 = (TO_WIDE_REAL(WIDE_LOAD(node->lower[1])) - ly) * iy;
  const wide_real y1 = (TO_WIDE_REAL(WIDE_LOAD(node->upper[1])) - uy) * iy;
  const wide_real z0 = (TO_WIDE_REAL(WIDE_LOAD(node->lower[2])) - lz) * iz;
  const wide_real z1 = (TO_WIDE_REAL(WIDE_LOAD(node->upper[2])) - uz) * iz;
  wide_real enter = BMAX(BMAX(BMIN(x0, x1), BMIN(y0, y1)), BMIN(z0, z1));
  wide_real leave = BMIN(BMIN(BMAX(x0, x1), BMAX(y0, y1)), BMAX(z0, z1));
  const wide_real slack = (fabs(enter) + fabs(leave)) * CLRT_BOX_SLACK;
  enter -= slack;
  leave += slack;
  const wide_mask used = TO_WIDE_MASK(WIDE_LOAD(node->count) != 0);
  const wide_mask hit = (enter <= leave) & (leave >= tmin) & (enter <= limit) & used;
  WIDE_STORE(enter, enter_out);
  WIDE_STORE(WIDE_MASK_TO_INT(hit), hit_out);
}

#if CLRT_LANES == 1
CLRT_INLINE void node_children(__global const clrt_wide_node* node, const box_origins* O, const vec3* inverse,
                               real tmin, lreal limit, lint active, real* enter_out, int* hit_out) {
  ray_children(node, O->lower.x, O->lower.y, O->lower.z, O->upper.x, O->upper.y, O->upper.z, (*inverse).x, (*inverse).y,
               (*inverse).z, tmin, limit, enter_out, hit_out);
  (void)active;
}
#else
/* The smallest of the lanes of an lreal (selects: no NaN here). */
CLRT_INLINE real lane_min_real(lreal x) {
#if CLRT_LANES == 16
  const float8 h8 = BMIN(x.lo, x.hi);
  const float4 h4 = BMIN(h8.lo, h8.hi);
#elif CLRT_LANES == 8
  const float4 h4 = BMIN(x.lo, x.hi);
#else
  const float4 h4 = x;
#endif
  const float2 h2 = BMIN(h4.lo, h4.hi);
  return BMIN(h2.x, h2.y);
}

/* A lane mask as bits (lane i, bit i) and back. */
CLRT_INLINE int lane_bits(lint lanes) {
  return LANE_OR(lanes & ((lint)1 << LANE_IOTA));
}
CLRT_INLINE lint bits_lanes(int bits) {
  return (((lint)bits >> LANE_IOTA) & 1) != 0;
}

/* A block of rays, child after child: hit[k] is the bits of the lanes of
 * `active` that may meet child k's box within their interval (0: none);
 * enter[k] the smallest widened entry distance of those lanes. */
CLRT_INLINE void node_children(__global const clrt_wide_node* node, const box_origins* O, const vec3* inverse,
                               real tmin, lreal limit, lint active, real* enter_out, int* hit_out) {
  for (int k = 0; k < CLRT_BVH_WIDTH; ++k) {
    hit_out[k] = 0;
    if (node->count[k] == 0) continue;
    lreal enter;
    const lint lanes = active & child_overlap(node, k, O, inverse, tmin, limit, &enter);
    if (!ANY(lanes)) continue;
    hit_out[k] = lane_bits(lanes);
    enter_out[k] = lane_min_real(lanes ? enter : (lreal)REAL_INFINITY);
  }
}
#endif

/* The stack of a walk: the children it has yet to visit, each with its
 * entry distance and, in a block walk, the bits of the lanes that met its
 * box. */
#if CLRT_LANES > 1
#define STACK_LANES(statement) statement
#else
#define STACK_LANES(statement)
#endif
typedef struct walk_stack {
  int child[CLRT_BVH_STACK];
  real enter[CLRT_BVH_STACK];
  STACK_LANES(int lanes[CLRT_BVH_STACK];)
} walk_stack;

/* Pushes the children of node `index` that hit[] names, keeping those pushed
 * since the call farthest first (insertion: at most CLRT_BVH_WIDTH of them).
 * Inner children are pushed as their node index, leaves as ~(index *
 * CLRT_BVH_WIDTH + slot): their entries are read only when popped
 * (leaf_entries()), and a leaf popped beyond the closest hit is never read. */
CLRT_INLINE void push_hits(__global const clrt_wide_node* node, int index, const real* enter, const int* hit,
                           walk_stack* stack, int* top) {
  const int base = *top;
  for (int slot = 0; slot < CLRT_BVH_WIDTH; ++slot) {
    if (!hit[slot]) continue;
    const int child = node->count[slot] > 0 ? ~(index * CLRT_BVH_WIDTH + slot) : node->child[slot];
    int k = (*top)++;
    while (k > base && stack->enter[k - 1] < enter[slot]) {
      stack->child[k] = stack->child[k - 1];
      stack->enter[k] = stack->enter[k - 1];
      STACK_LANES(stack->lanes[k] = stack->lanes[k - 1]);
      --k;
    }
    stack->child[k] = child;
    stack->enter[k] = enter[slot];
    STACK_LANES(stack->lanes[k] = hit[slot]);
  }
}

/* One step of either walk: tests node `index`'s children against the lanes
 * of `active` and pushes those hit, nearest on top. */
CLRT_INLINE void push_children(__global const clrt_wide_node* nodes, int index, const box_origins* O,
                               const vec3* inverse, real tmin, lreal limit, lint active, walk_stack* stack, int* top) {
  __global const clrt_wide_node* node = &nodes[index];
  real enter[CLRT_BVH_WIDTH];
  int hit[CLRT_BVH_WIDTH];
  node_children(node, O, inverse, tmin, limit, active, enter, hit);
  push_hits(node, index, enter, hit, stack, top);
}

/* The primitive entries [*first, *first + *count) of the leaf that stack
 * entry `reference` (~(node * CLRT_BVH_WIDTH + slot), negative) stands for. */
CLRT_INLINE void leaf_entries(__global const clrt_wide_node* nodes, int reference, int* first, int* count) {
  const int slot = ~reference;
  __global const clrt_wide_node* parent = &nodes[slot / CLRT_BVH_WIDTH];
  *first = parent->child[slot % CLRT_BVH_WIDTH];
  *count = parent->count[slot % CLRT_BVH_WIDTH];
}

/* The distances to the primitive of leaf entry k (a sphere's two roots, or
 * a triangle's distance twice); returns the primitive's id. A ray never
 * meets the triangle it starts on again (its id is `self`). Float variants
 * read a sphere's centre and radius from the leaf copy beside the entry
 * (clrt_leaf_sphere), the others from the scene's record. */
#if CLRT_HAS_TRIANGLES
#define SHEAR_ARG , const ray_shear* shear
#define SHEAR_PASS , &shear
#define SHEAR_PASS_PTR , shear
#else
#define SHEAR_ARG
#define SHEAR_PASS
#define SHEAR_PASS_PTR
#endif
CLRT_INLINE int entry_roots(int k, const vec3* O, const vec3* D SHEAR_ARG, lint self, const scene_data* scene,
                            lreal* t1, lreal* t2, lint* tests) {
  const int entry = scene->primitives[k];
  const int i = entry & CLRT_PRIMITIVE_INDEX_MASK;
  *tests += (lint)1;
#if CLRT_HAS_TRIANGLES
  if ((entry >> CLRT_PRIMITIVE_KIND_SHIFT) == CLRT_PRIMITIVE_TRIANGLE) {
    /* (entries name a triangle's place in the buffer, its record its id) */
    __global const clrt_triangle* tri = &scene->triangles[i];
    const int id = TRIANGLE_ID0(scene->params) + tri->index;
    const lreal t = triangle_distance(O, shear, tri, TRIANGLE_LO(scene, i));
    *t1 = self == id ? (lreal)REAL_INFINITY : t;
    *t2 = *t1;
    return id;
  }
#endif
#if CLRT_PRECISION != CLRT_PRECISION_NAIVE && CLRT_PRECISION != CLRT_PRECISION_FP64
  const float4 leaf = vload4(0, scene->leaf_spheres[k].center);
  float_sphere_roots(O, D, leaf.x, leaf.y, leaf.z, fabs(leaf.w), LEAF_COMPENSATED(leaf.w), &scene->spheres[i],
                     self == i, t1, t2);
#else
  intersect(O, D, scene->spheres, i, self == i, t1, t2);
#endif
  return i;
}

/* The primitive entries of leaf child [first, first + count) against the
 * lanes' rays: the nearest root in (tmin, tmax) below `closest`, ties to
 * the lower id. */
CLRT_INLINE void closest_in_leaf(int first, int count, const vec3* O, const vec3* D SHEAR_ARG, real tmin, real tmax,
                                 lint self, const scene_data* scene, lreal* closest, lint* best, lint* tests) {
  for (int k = first; k < first + count; ++k) {
    lreal t1, t2;
    const int i = entry_roots(k, O, D SHEAR_PASS_PTR, self, scene, &t1, &t2, tests);
    /* ties to the lower index, as the loop over every sphere gives them */
    lint nearer = ((t1 < *closest) | ((t1 == *closest) & ((lint)i < *best))) & (tmin < t1) & (t1 < tmax);
    *closest = nearer ? t1 : *closest;
    *best = nearer ? (lint)i : *best;
    nearer = ((t2 < *closest) | ((t2 == *closest) & ((lint)i < *best))) & (tmin < t2) & (t2 < tmax);
    *closest = nearer ? t2 : *closest;
    *best = nearer ? (lint)i : *best;
  }
}

/* The lanes whose ray meets a primitive entry of leaf child [first, first +
 * count) in (tmin, tmax). */
CLRT_INLINE lint any_in_leaf(int first, int count, const vec3* O, const vec3* D SHEAR_ARG, real tmin, real tmax,
                             lint self, const scene_data* scene, lint* tests) {
  lint blocked = 0;
  for (int k = first; k < first + count; ++k) {
    lreal t1, t2;
    entry_roots(k, O, D SHEAR_PASS_PTR, self, scene, &t1, &t2, tests);
    blocked |= ((tmin < t1) & (t1 < tmax)) | ((tmin < t2) & (t2 < tmax));
  }
  return blocked;
}

#if CLRT_LANES > 1
/* A block's rays part ways after a bounce: below a node that few of its
 * lanes' rays meet (CLRT_SOLO_LANES or fewer), a block walk would test each
 * box lane after lane (CLRT_BVH_WIDTH slab tests of the block) for one or
 * two rays. Those lanes walk that subtree alone instead, one ray at a time,
 * every child of a node in one test (ray_children()), as the one-ray walk
 * does; a leaf's primitives are still tested against every lane's ray (it
 * costs the one ray's price, and a hit found for another lane is as valid
 * as any: the closest hit is the least over every primitive a lane's walk
 * must test, and more tests only shorten the walk). */
#ifndef CLRT_SOLO_LANES
#ifdef CLRT_LOOP_LIMIT_PROBE
/* (llvmpipe ends a work-item after 65 535 loop iterations in all, and a
 * lane's walk of its own adds its iterations to the block's: 10 000
 * spheres at 16 lanes ran past it) */
#define CLRT_SOLO_LANES 0
#else
/* 1, 2, 4 and 8 measured within the machine's noise of each other; 16 (every
 * ray alone below the root) was slower (docs/results/wide-hierarchy.md) */
#define CLRT_SOLO_LANES 2
#endif
#endif
#define LANE_OF(vector, j) (((const real*)&(vector))[j])
#define LINT_LANE(vector, j) (((const int*)&(vector))[j])

/* Lane j's ray, for ray_children(). */
typedef struct solo_ray {
  real lx, ly, lz, ux, uy, uz, ix, iy, iz;
} solo_ray;
CLRT_INLINE solo_ray solo_ray_of(const box_origins* O, const vec3* inverse, int j) {
  solo_ray r;
  r.lx = LANE_OF(O->lower.x, j);
  r.ly = LANE_OF(O->lower.y, j);
  r.lz = LANE_OF(O->lower.z, j);
  r.ux = LANE_OF(O->upper.x, j);
  r.uy = LANE_OF(O->upper.y, j);
  r.uz = LANE_OF(O->upper.z, j);
  r.ix = LANE_OF((*inverse).x, j);
  r.iy = LANE_OF((*inverse).y, j);
  r.iz = LANE_OF((*inverse).z, j);
  return r;
}

/* Lane j's closest-hit walk of the subtree under node `root`, on the stack
 * above `base`. */
CLRT_INLINE void solo_closest(int root, int j, const solo_ray* r, const vec3* O, const vec3* D SHEAR_ARG, real tmin,
                              real tmax, lint self, const scene_data* scene, lreal* closest, lint* best, lint* tests,
                              walk_stack* stack, int base) {
  __global const clrt_wide_node* nodes = scene->nodes;
  int top = base, index = root;
  for (;;) {
    real enter[CLRT_BVH_WIDTH];
    int hit[CLRT_BVH_WIDTH];
    ray_children(&nodes[index], r->lx, r->ly, r->lz, r->ux, r->uy, r->uz, r->ix, r->iy, r->iz, tmin,
                 BMIN(LANE_OF(*closest, j), tmax), enter, hit);
    push_hits(&nodes[index], index, enter, hit, stack, &top);
    index = -1;
    while (top > base) {
      --top;
      if (stack->enter[top] > LANE_OF(*closest, j)) continue;
      if (stack->child[top] >= 0) {
        index = stack->child[top];
        break;
      }
      int first, count;
      leaf_entries(nodes, stack->child[top], &first, &count);
      closest_in_leaf(first, count, O, D SHEAR_PASS_PTR, tmin, tmax, self, scene, closest, best, tests);
    }
    if (index < 0) return;
  }
}

/* Lane j's any-hit walk of the subtree under node `root`, on the stack
 * above `base`: it ends when lane j is blocked. */
CLRT_INLINE void solo_any(int root, int j, const solo_ray* r, const vec3* O, const vec3* D SHEAR_ARG, real tmin,
                          real tmax, lint self, const scene_data* scene, lint* blocked, lint* tests, walk_stack* stack,
                          int base) {
  __global const clrt_wide_node* nodes = scene->nodes;
  int top = base, index = root;
  for (;;) {
    real enter[CLRT_BVH_WIDTH];
    int hit[CLRT_BVH_WIDTH];
    ray_children(&nodes[index], r->lx, r->ly, r->lz, r->ux, r->uy, r->uz, r->ix, r->iy, r->iz, tmin, tmax, enter, hit);
    push_hits(&nodes[index], index, enter, hit, stack, &top);
    index = -1;
    while (top > base) {
      --top;
      if (stack->child[top] >= 0) {
        index = stack->child[top];
        break;
      }
      int first, count;
      leaf_entries(nodes, stack->child[top], &first, &count);
      *blocked |= any_in_leaf(first, count, O, D SHEAR_PASS_PTR, tmin, tmax, self, scene, tests);
      if (LINT_LANE(*blocked, j)) return;
    }
    if (index < 0) return;
  }
}

/* The lowest set bit's index, and the bits without it. */
#define LOWEST_BIT(bits) (31 - clz((bits) & -(bits)))
#endif

/* Closest hit in (tmin, tmax) per lane: the primitive id or -1. */
CLRT_INLINE lint closest_intersection(const vec3* O, const vec3* D, real tmin, real tmax, lint self,
                                      const scene_data* scene, lreal* t_out, lint* tests) {
  __global const clrt_wide_node* nodes = scene->nodes;
  const vec3 inverse = inverse_direction(D);
  const box_origins origins = padded_origins(O);
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
  walk_stack stack;
  int top = 0, index = 0;
  lint lanes = MASK_TRUE; /* those whose ray met node `index`'s box */
  for (;;) {
    push_children(nodes, index, &origins, &inverse, tmin, BMIN(closest, (lreal)tmax), lanes, &stack, &top);
    /* the nearest child still worth a visit (beyond every lane's closest
     * hit, none is): leaves are tested on the way to it */
    index = -1;
    while (top > 0) {
      --top;
      if (!ANY(stack.enter[top] <= closest)) continue;
      if (stack.child[top] >= 0) {
#if CLRT_LANES > 1
        int bits = stack.lanes[top];
        if (popcount(bits) <= CLRT_SOLO_LANES) {
          const int child = stack.child[top]; /* (each walk reuses its slot) */
          for (; bits != 0; bits &= bits - 1) {
            const int j = LOWEST_BIT(bits);
            const solo_ray r = solo_ray_of(&origins, &inverse, j);
            solo_closest(child, j, &r, O, D SHEAR_PASS, tmin, tmax, self, scene, &closest, &best, tests, &stack, top);
          }
          continue;
        }
        lanes = bits_lanes(bits);
#endif
        index = stack.child[top];
        break;
      }
      int first, count;
      leaf_entries(nodes, stack.child[top], &first, &count);
      closest_in_leaf(first, count, O, D SHEAR_PASS, tmin, tmax, self, scene, &closest, &best, tests);
    }
    if (index < 0) break;
  }
  *t_out = closest;
  return best;
}

/* Any hit in (tmin, tmax) per lane, for the lanes in `active`; the walk ends
 * when every one of them is blocked. */
CLRT_INLINE lint any_intersection(const vec3* O, const vec3* D, real tmin, real tmax, lint self, lint active,
                                  const scene_data* scene, lint* tests) {
  __global const clrt_wide_node* nodes = scene->nodes;
  const vec3 inverse = inverse_direction(D);
  const box_origins origins = padded_origins(O);
#if CLRT_HAS_TRIANGLES
  const ray_shear shear = shear_of(D);
#endif
  /* planes first, as the closest-hit walk: one may block every lane */
#if CLRT_HAS_PLANES
  lint blocked = any_flat(O, D, tmin, tmax, self, active, scene, 0, tests);
#else
  lint blocked = 0;
#endif
  walk_stack stack;
  int top = 0, index = 0;
  lint lanes = MASK_TRUE; /* those whose ray met node `index`'s box */
  for (;;) {
    const lint open = active & !blocked & lanes;
    if (!ANY(open)) break;
    /* nearest first, as the closest-hit walk: a blocker near the surface
     * (the usual one) is found before the far subtrees are walked */
    push_children(nodes, index, &origins, &inverse, tmin, (lreal)tmax, open, &stack, &top);
    index = -1;
    while (top > 0) {
      --top;
      if (stack.child[top] >= 0) {
#if CLRT_LANES > 1
        int bits = stack.lanes[top] & lane_bits(active & !blocked);
        if (bits == 0) continue;
        if (popcount(bits) <= CLRT_SOLO_LANES) {
          const int child = stack.child[top]; /* (each walk reuses its slot) */
          for (; bits != 0; bits &= bits - 1) {
            const int j = LOWEST_BIT(bits);
            if (LINT_LANE(blocked, j)) continue;
            const solo_ray r = solo_ray_of(&origins, &inverse, j);
            solo_any(child, j, &r, O, D SHEAR_PASS, tmin, tmax, self, scene, &blocked, tests, &stack, top);
          }
          if (ALL(blocked | !active)) return blocked;
          continue;
        }
        lanes = bits_lanes(bits);
#endif
        index = stack.child[top];
        break;
      }
      int first, count;
      leaf_entries(nodes, stack.child[top], &first, &count);
      blocked |= any_in_leaf(first, count, O, D SHEAR_PASS, tmin, tmax, self, scene, tests);
      if (ALL(blocked | !active)) return blocked;
    }
    if (index < 0) break;
  }
  return blocked;
}

#endif /* CLRT_BVH */

#endif /* CLRT_BVH_H */
