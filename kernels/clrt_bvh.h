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
 * One ray's walk (ray_closest(), ray_any(): one ray per work-item, and a
 * block's lanes that walk alone) tests a node's children together, one SIMD
 * lane per child (float4 or float8), and pushes those hit without a branch
 * per child: their keys (entry distance and slot) sorted in SIMD and stored
 * whole (ray_push()). A block of lanes (CLRT_LANES > 1) tests the children
 * one after the other, one SIMD lane per ray, and enters a child that any
 * lane needs, for the lanes that met it; below a node that only one or two
 * lanes met, each of them walks alone, and tests a leaf's primitives side
 * by side, one per SIMD lane (clrt_leaf_alone.h). Either way the hit
 * children, leaves and inner nodes alike, are pushed nearest last, each
 * with its entry distance (the smallest over the lanes that meet it), so
 * the nearest is visited first and a popped child beyond the closest hit
 * is skipped. Shadow rays take any hit and end the walk at the first; they
 * too go nearest first, where the usual blocker is (unordered, they tested
 * 25% more spheres: docs/results/wide-hierarchy.md). The walk is iterative;
 * CLRT_BVH_STACK entries always suffice (clrt_layout.h). */
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
/* The box tests' multiply-add: fma() where the host knows the device fuses
 * it in hardware (-DCLRT_FAST_FMA: GPUs, and CPU drivers on a CPU with FMA
 * instructions: PoCL's mad() is a multiply and an add, 1.02-1.07x slower
 * on spheres, docs/results/wide-hierarchy.md), else mad(), which a device
 * may fuse or not: either rounding is inside the padding below. (OpenCL's
 * FP_FAST_FMAF would say it, but neither PoCL nor rusticl defines it.) */
#ifdef CLRT_FAST_FMA
#define BOX_MAD(a, b, c) fma(a, b, c)
#else
#define BOX_MAD(a, b, c) mad(a, b, c)
#endif

/* A slab's distance (plane - origin) / D as plane * inverse - origin *
 * inverse, one multiply-add (BOX_MAD(): fused or not) per plane with the
 * products below taken once per ray: it adds a rounding of ~2^-24 |O| to
 * the plane's distance (of origin * inverse) where the difference had
 * none, far inside the ray's padding p (2^-17 |O| and more: CLRT_BVH_PAD_*);
 * the rest is relative to the distance, inside CLRT_BOX_SLACK, as before. */
typedef struct box_origins {
  vec3 lower, upper; /* where the lower and upper planes are seen from, times the inverse direction */
} box_origins;

CLRT_INLINE box_origins padded_origins(const vec3* O, const vec3* inverse) {
  const lreal p = BMAX(BMAX(fabs((*O).x), fabs((*O).y)), fabs((*O).z)) * CLRT_RAY_PAD;
  box_origins out;
  out.lower = v3(((*O).x + p) * (*inverse).x, ((*O).y + p) * (*inverse).y, ((*O).z + p) * (*inverse).z);
  out.upper = v3(((*O).x - p) * (*inverse).x, ((*O).y - p) * (*inverse).y, ((*O).z - p) * (*inverse).z);
  return out;
}

/* A distance moved down (up) by CLRT_BOX_SLACK of itself, whatever its sign:
 * an entry (exit) distance widened beyond the slab arithmetic's rounding,
 * which is relative to the distance (the rest is inside the ray's padding:
 * box_origins). Clipped to (tmin, limit) before, as they are, the widening
 * covers the bounds too. */
#define WIDEN_DOWN(t) BOX_MAD(-fabs(t), CLRT_BOX_SLACK, t)
#define WIDEN_UP(t) BOX_MAD(fabs(t), CLRT_BOX_SLACK, t)

/* Lanes whose ray may meet child k's box within (tmin, limit); `enter`
 * gets their entry distances, widened as the exit is. */
CLRT_INLINE lint child_overlap(__global const clrt_wide_node* node, int k, const box_origins* O, const vec3* inverse,
                               real tmin, lreal limit, lreal* enter_out) {
  const lreal x0 = BOX_MAD((lreal)node->lower[0][k], (*inverse).x, -O->lower.x);
  const lreal x1 = BOX_MAD((lreal)node->upper[0][k], (*inverse).x, -O->upper.x);
  const lreal y0 = BOX_MAD((lreal)node->lower[1][k], (*inverse).y, -O->lower.y);
  const lreal y1 = BOX_MAD((lreal)node->upper[1][k], (*inverse).y, -O->upper.y);
  const lreal z0 = BOX_MAD((lreal)node->lower[2][k], (*inverse).z, -O->lower.z);
  const lreal z1 = BOX_MAD((lreal)node->upper[2][k], (*inverse).z, -O->upper.z);
  /* the interval inside (tmin, limit) first, then widened (WIDEN_*) */
  const lreal enter = WIDEN_DOWN(BMAX(BMAX(BMIN(x0, x1), BMIN(y0, y1)), BMAX(BMIN(z0, z1), (lreal)tmin)));
  const lreal leave = WIDEN_UP(BMIN(BMIN(BMAX(x0, x1), BMAX(y0, y1)), BMIN(BMAX(z0, z1), limit)));
  *enter_out = enter;
  return enter <= leave;
}

/* One ray, every child of a node at once: the same slab test as above on
 * CLRT_BVH_WIDTH-wide vectors of the precision's scalar (the one-ray walk,
 * and a block's rays that walk alone: below). */
#include "clrt_bvh_wide.h"

/* The children whose box one ray may meet within (tmin, limit) (nonzero
 * lanes of the result) and their widened entry distances (`enter`). One ray
 * knows per axis which of a box's planes it meets first (its direction's
 * sign), so it reads that row of the node (`near_*`: the offset of the
 * lower or upper row, in floats) and the other (`far_*`), seen from the
 * padded origin that goes with each (times the reciprocal direction:
 * `near_origin`, `far_origin`), and needs no min and max per pair. */
typedef struct slab_ray {
  int near_x, near_y, near_z, far_x, far_y, far_z;
  real near_origin_x, near_origin_y, near_origin_z, far_origin_x, far_origin_y, far_origin_z;
  real ix, iy, iz;
} slab_ray;
#define NODE_ROW(node, offset) TO_WIDE_REAL(WIDE_LOAD((__global const clrt_f32*)(node) + (offset)))
CLRT_INLINE wide_mask ray_boxes(__global const clrt_wide_node* node, const slab_ray* r, real tmin, real limit,
                                wide_real* enter_out) {
  const wide_real nx = BOX_MAD(NODE_ROW(node, r->near_x), (wide_real)r->ix, (wide_real)-r->near_origin_x);
  const wide_real fx = BOX_MAD(NODE_ROW(node, r->far_x), (wide_real)r->ix, (wide_real)-r->far_origin_x);
  const wide_real ny = BOX_MAD(NODE_ROW(node, r->near_y), (wide_real)r->iy, (wide_real)-r->near_origin_y);
  const wide_real fy = BOX_MAD(NODE_ROW(node, r->far_y), (wide_real)r->iy, (wide_real)-r->far_origin_y);
  const wide_real nz = BOX_MAD(NODE_ROW(node, r->near_z), (wide_real)r->iz, (wide_real)-r->near_origin_z);
  const wide_real fz = BOX_MAD(NODE_ROW(node, r->far_z), (wide_real)r->iz, (wide_real)-r->far_origin_z);
  const wide_real enter = WIDEN_DOWN(BMAX(BMAX(nx, ny), BMAX(nz, (wide_real)tmin)));
  const wide_real leave = WIDEN_UP(BMIN(BMIN(fx, fy), BMIN(fz, (wide_real)limit)));
  const wide_mask used = TO_WIDE_MASK(WIDE_LOAD(node->count) != 0);
  *enter_out = enter;
  return (enter <= leave) & used;
}

/* Lane j of a vector (LANES 1: the scalar itself). */
#define LANE_OF(vector, j) (((const real*)&(vector))[j])
#define LINT_LANE(vector, j) (((const int*)&(vector))[j])

/* Lane j's ray, for ray_boxes(). */
CLRT_INLINE slab_ray slab_ray_of(const box_origins* O, const vec3* inverse, int j) {
  slab_ray r;
  r.ix = LANE_OF((*inverse).x, j);
  r.iy = LANE_OF((*inverse).y, j);
  r.iz = LANE_OF((*inverse).z, j);
  /* (rows of clrt_wide_node: lower x, y, z, then upper x, y, z) */
  const int ax = r.ix < 0, ay = r.iy < 0, az = r.iz < 0; /* (never 0: inverse_direction()) */
  r.near_x = (3 * ax + 0) * CLRT_BVH_WIDTH;
  r.near_y = (3 * ay + 1) * CLRT_BVH_WIDTH;
  r.near_z = (3 * az + 2) * CLRT_BVH_WIDTH;
  r.far_x = (3 * !ax + 0) * CLRT_BVH_WIDTH;
  r.far_y = (3 * !ay + 1) * CLRT_BVH_WIDTH;
  r.far_z = (3 * !az + 2) * CLRT_BVH_WIDTH;
  const real lx = LANE_OF(O->lower.x, j), ly = LANE_OF(O->lower.y, j), lz = LANE_OF(O->lower.z, j);
  const real ux = LANE_OF(O->upper.x, j), uy = LANE_OF(O->upper.y, j), uz = LANE_OF(O->upper.z, j);
  r.near_origin_x = ax ? ux : lx;
  r.near_origin_y = ay ? uy : ly;
  r.near_origin_z = az ? uz : lz;
  r.far_origin_x = ax ? lx : ux;
  r.far_origin_y = ay ? ly : uy;
  r.far_origin_z = az ? lz : uz;
  return r;
}

/* The stack of a walk: the children it has yet to visit, each as the index
 * of its parent node (`node`) and a key (`enter`): its entry distance with
 * its slot in the parent in the low bits (ENTRY_KEY). In a block walk, also
 * the bits of the lanes that met its box. A leaf's entries and an inner
 * child's index are read from the parent when popped (entry_child()): a
 * child popped beyond the closest hit is never read. */
typedef struct walk_stack {
  /* (room above the top for a whole node's keys: ray_push()) */
  int node[CLRT_BVH_STACK + CLRT_BVH_WIDTH];
  real enter[CLRT_BVH_STACK + CLRT_BVH_WIDTH];
#if CLRT_LANES > 1
  int lanes[CLRT_BVH_STACK]; /* (block_push() alone writes them) */
#endif
} walk_stack;

/* A child's key from the bits of its entry distance (clamped to at least 0,
 * so the bits order as the distances do) and its slot: the bits lowered by
 * CLRT_BVH_WIDTH ulps, then the slot in the low bits, so the key never
 * exceeds the distance (a child is skipped only when the key is beyond the
 * closest hit). `zero` is 0 of the bits' type. */
#define ENTRY_KEY(bits, slot, zero) ((max((bits)-CLRT_BVH_WIDTH, zero) & ~(CLRT_BVH_WIDTH - 1)) | (slot))
#if CLRT_PRECISION == CLRT_PRECISION_FP64
#define KEY_SLOT(key) ((int)(as_long(key) & (CLRT_BVH_WIDTH - 1)))
#else
#define KEY_SLOT(key) (as_int(key) & (CLRT_BVH_WIDTH - 1))
#endif

/* The child that stack entry `top` names: its node (*count < 0) or its first
 * primitive entry (*count of them). */
CLRT_INLINE int entry_child(__global const clrt_wide_node* nodes, const walk_stack* stack, int top, int* count) {
  __global const clrt_wide_node* parent = &nodes[stack->node[top]];
  const int slot = KEY_SLOT(stack->enter[top]);
  *count = parent->count[slot];
  return parent->child[slot];
}

/* One ray at node `index`: pushes the children whose box it may meet within
 * (tmin, limit), nearest on top, without a branch per child (the slot loop
 * it replaces mispredicted one in most slots: docs/results/wide-hierarchy.md).
 * The keys, misses as -1, are sorted largest first and stored whole; the top
 * rises by the hits, so the misses land above it. */
CLRT_INLINE void ray_push(__global const clrt_wide_node* nodes, int index, const slab_ray* r, real tmin, real limit,
                          walk_stack* stack, int* top) {
  wide_real enter;
  const wide_mask hit = ray_boxes(&nodes[index], r, tmin, limit, &enter);
  const wide_mask key = ENTRY_KEY(AS_WIDE_KEY(BMAX(enter, (wide_real)0)), WIDE_KEY_IOTA, (wide_mask)0);
  WIDE_STORE(AS_WIDE_REAL(sort_descending(select((wide_mask)-1, key, hit))), &stack->enter[*top]);
  WIDE_STORE((wide_int)index, &stack->node[*top]);
  *top -= wide_sum(WIDE_MASK_TO_INT(hit));
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
  *tests += (lint)1;
#if CLRT_HAS_TRIANGLES && !CLRT_BVH_SPHERES
  /* Every entry a triangle: the k-th entry names place k (the host lays the
   * triangles out in the entries' order: test_bvh.cpp), so the record's
   * load need not wait for the entry's. */
  const int entry = (CLRT_PRIMITIVE_TRIANGLE << CLRT_PRIMITIVE_KIND_SHIFT) | k;
#else
  const int entry = scene->primitives[k];
#endif
  const int i = entry & CLRT_PRIMITIVE_INDEX_MASK;
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

/* Asks the cache for what a visit of child `slot` of `node` reads first: its
 * wide node, or its leaf's first primitive records (triangles in a
 * hierarchy of triangles alone, sphere copies in float variants). A walk
 * pushes a node's children nearest last and visits all but the nearest
 * after a subtree, so their loads, which a walk of a large scene waits on
 * (docs/results/wide-hierarchy.md), can be under way meanwhile. OpenCL's
 * prefetch() does nothing on PoCL; clang's builtin gives the CPU's prefetch
 * instruction. Only where clang compiles the kernel for a CPU (PoCL), and
 * not with -DCLRT_NO_PREFETCH (for A/B runs through --cl-options). Block
 * walks ask for each child they push (block_push()); one ray's walk asks,
 * on each visit, for the entry below the one it pops (prefetch_next(): the
 * next it visits when this one is a leaf, and a sibling it comes back to):
 * 1.06x on the million-triangle mesh. Asking for every child it pushes
 * made it 6-8% slower on 10^4-10^6 spheres, for the next two 5%
 * (docs/results/wide-hierarchy.md). */
#if (defined(__x86_64__) || defined(__aarch64__)) && !defined(CLRT_NO_PREFETCH)
#define CLRT_CACHE_LINE 64
CLRT_INLINE void prefetch_bytes(__global const void* p, int bytes) {
  __global const char* c = (__global const char*)p;
  for (int i = 0; i < bytes; i += CLRT_CACHE_LINE) __builtin_prefetch(c + i);
}
CLRT_INLINE void prefetch_child(const scene_data* scene, __global const clrt_wide_node* node, int slot) {
  const int count = node->count[slot], child = node->child[slot];
  if (count < 0) {
    prefetch_bytes(&scene->nodes[child], (int)sizeof(clrt_wide_node));
    return;
  }
  /* (the first lines of a leaf: up to 4 triangles, 8 sphere copies) */
#if CLRT_HAS_TRIANGLES && !CLRT_BVH_SPHERES
  prefetch_bytes(&scene->triangles[child], min(count, 4) * (int)sizeof(clrt_triangle));
#elif !CLRT_HAS_TRIANGLES && CLRT_PRECISION != CLRT_PRECISION_NAIVE && CLRT_PRECISION != CLRT_PRECISION_FP64
  prefetch_bytes(&scene->leaf_spheres[child], min(count, 8) * (int)sizeof(clrt_leaf_sphere));
#endif
}
#else
#define prefetch_child(scene, node, slot)
#endif

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

#include "clrt_leaf_alone.h"

/* Asks for the child of the stack entry below `top` (if above `base`). */
CLRT_INLINE void prefetch_next(const scene_data* scene, const walk_stack* stack, int top, int base) {
  if (top > base) prefetch_child(scene, &scene->nodes[stack->node[top - 1]], KEY_SLOT(stack->enter[top - 1]));
}

/* Lane j's closest-hit walk of the subtree under node `root` (LANES 1:
 * the one ray's whole walk), on the stack above `base`. A leaf's
 * primitives are tested against every lane's ray (in a block, it costs the
 * one ray's price, and a hit found for another lane is as valid as any: the
 * closest hit is the least over every primitive a lane's walk must test,
 * and more tests only shorten the walk). */
CLRT_INLINE void ray_closest(int root, int j, const slab_ray* r, const vec3* O, const vec3* D SHEAR_ARG, real tmin,
                             real tmax, lint self, const scene_data* scene, lreal* closest, lint* best, lint* tests,
                             walk_stack* stack, int base) {
  __global const clrt_wide_node* nodes = scene->nodes;
#if defined(CLRT_LEAF_ALONE)
  const lone_ray lone = lone_ray_of(O, D SHEAR_PASS_PTR, self, j);
#endif
  int top = base, index = root;
  for (;;) {
    ray_push(nodes, index, r, tmin, BMIN(LANE_OF(*closest, j), tmax), stack, &top);
    index = -1;
    while (top > base) {
      --top;
      if (stack->enter[top] > LANE_OF(*closest, j)) continue;
      prefetch_next(scene, stack, top, base);
      int count;
      const int child = entry_child(nodes, stack, top, &count);
      if (count < 0) {
        index = child;
        break;
      }
#if defined(CLRT_LEAF_ALONE)
      closest_in_leaf_alone(child, count, &lone, O, D SHEAR_PASS_PTR, tmin, tmax, self, scene, closest, best, tests);
#else
      closest_in_leaf(child, count, O, D SHEAR_PASS_PTR, tmin, tmax, self, scene, closest, best, tests);
#endif
    }
    if (index < 0) return;
  }
}

/* Lane j's any-hit walk of the subtree under node `root`, on the stack
 * above `base`: it ends when lane j is blocked. */
CLRT_INLINE void ray_any(int root, int j, const slab_ray* r, const vec3* O, const vec3* D SHEAR_ARG, real tmin,
                         real tmax, lint self, const scene_data* scene, lint* blocked, lint* tests, walk_stack* stack,
                         int base) {
  __global const clrt_wide_node* nodes = scene->nodes;
#if defined(CLRT_LEAF_ALONE)
  const lone_ray lone = lone_ray_of(O, D SHEAR_PASS_PTR, self, j);
#endif
  int top = base, index = root;
  for (;;) {
    ray_push(nodes, index, r, tmin, tmax, stack, &top);
    index = -1;
    while (top > base) {
      --top;
      prefetch_next(scene, stack, top, base);
      int count;
      const int child = entry_child(nodes, stack, top, &count);
      if (count < 0) {
        index = child;
        break;
      }
#if defined(CLRT_LEAF_ALONE)
      if (any_in_leaf_alone(child, count, &lone, O, D SHEAR_PASS_PTR, tmin, tmax, self, scene, blocked, tests)) {
        *blocked |= LANE_IOTA == (lint)j;
        return;
      }
#else
      *blocked |= any_in_leaf(child, count, O, D SHEAR_PASS_PTR, tmin, tmax, self, scene, tests);
      if (LINT_LANE(*blocked, j)) return;
#endif
    }
    if (index < 0) return;
  }
}

#include "clrt_bvh_block.h"

/* Closest hit in (tmin, tmax) per lane of `active`: the primitive id or -1.
 * A block walks only their rays (an ended path keeps its last ray, which
 * made the block visit its nodes for nothing): the other lanes' closest
 * distance starts at -infinity, below every box and primitive. */
CLRT_INLINE lint closest_intersection(const vec3* O, const vec3* D, real tmin, real tmax, lint self, lint active,
                                      const scene_data* scene, lreal* t_out, lint* tests) {
  const vec3 inverse = inverse_direction(D);
  const box_origins origins = padded_origins(O, &inverse);
  lreal closest = active ? (lreal)REAL_INFINITY : (lreal)-REAL_INFINITY;
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
#if CLRT_LANES == 1
  const slab_ray r = slab_ray_of(&origins, &inverse, 0);
  ray_closest(0, 0, &r, O, D SHEAR_PASS, tmin, tmax, self, scene, &closest, &best, tests, &stack, 0);
#else
  __global const clrt_wide_node* nodes = scene->nodes;
  int top = 0, index = 0;
  lint lanes = active; /* those whose ray met node `index`'s box */
  for (;;) {
    block_push(scene, index, &origins, &inverse, tmin, BMIN(closest, (lreal)tmax), lanes, &stack, &top);
    /* the nearest child still worth a visit (beyond every lane's closest
     * hit, none is): leaves are tested on the way to it */
    index = -1;
    while (top > 0) {
      --top;
      if (!ANY(stack.enter[top] <= closest)) continue;
      int count;
      const int child = entry_child(nodes, &stack, top, &count);
      if (count > 0) {
        closest_in_leaf(child, count, O, D SHEAR_PASS, tmin, tmax, self, scene, &closest, &best, tests);
        continue;
      }
      int bits = stack.lanes[top];
      if (popcount(bits) <= CLRT_SOLO_LANES) {
        for (; bits != 0; bits &= bits - 1) { /* (each walk reuses the slot) */
          const int j = LOWEST_BIT(bits);
          const slab_ray r = slab_ray_of(&origins, &inverse, j);
          ray_closest(child, j, &r, O, D SHEAR_PASS, tmin, tmax, self, scene, &closest, &best, tests, &stack, top);
        }
        continue;
      }
      lanes = bits_lanes(bits);
      index = child;
      break;
    }
    if (index < 0) break;
  }
#endif
  *t_out = active ? closest : (lreal)REAL_INFINITY;
  return best;
}

/* Any hit in (tmin, tmax) per lane, for the lanes in `active`; the walk ends
 * when every one of them is blocked. */
CLRT_INLINE lint any_intersection(const vec3* O, const vec3* D, real tmin, real tmax, lint self, lint active,
                                  const scene_data* scene, lint* tests) {
  const vec3 inverse = inverse_direction(D);
  const box_origins origins = padded_origins(O, &inverse);
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
#if CLRT_LANES == 1
  if (active && !blocked) {
    const slab_ray r = slab_ray_of(&origins, &inverse, 0);
    ray_any(0, 0, &r, O, D SHEAR_PASS, tmin, tmax, self, scene, &blocked, tests, &stack, 0);
  }
#else
  __global const clrt_wide_node* nodes = scene->nodes;
  int top = 0, index = 0;
  lint lanes = MASK_TRUE; /* those whose ray met node `index`'s box */
  for (;;) {
    const lint open = active & !blocked & lanes;
    if (!ANY(open)) break;
    /* nearest first, as the closest-hit walk: a blocker near the surface
     * (the usual one) is found before the far subtrees are walked */
    block_push(scene, index, &origins, &inverse, tmin, (lreal)tmax, open, &stack, &top);
    index = -1;
    while (top > 0) {
      --top;
      int count;
      const int child = entry_child(nodes, &stack, top, &count);
      if (count > 0) {
        blocked |= any_in_leaf(child, count, O, D SHEAR_PASS, tmin, tmax, self, scene, tests);
        if (ALL(blocked | !active)) return blocked;
        continue;
      }
      int bits = stack.lanes[top] & lane_bits(active & !blocked);
      if (bits == 0) continue;
      if (popcount(bits) <= CLRT_SOLO_LANES) {
        for (; bits != 0; bits &= bits - 1) { /* (each walk reuses the slot) */
          const int j = LOWEST_BIT(bits);
          if (LINT_LANE(blocked, j)) continue;
          const slab_ray r = slab_ray_of(&origins, &inverse, j);
          ray_any(child, j, &r, O, D SHEAR_PASS, tmin, tmax, self, scene, &blocked, tests, &stack, top);
        }
        if (ALL(blocked | !active)) return blocked;
        continue;
      }
      lanes = bits_lanes(bits);
      index = child;
      break;
    }
    if (index < 0) break;
  }
#endif
  return blocked;
}

#endif /* CLRT_BVH */

#endif /* CLRT_BVH_H */
