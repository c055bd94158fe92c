/* clrt_bvh_block.h - the pieces of clrt_bvh.h's walk that only a block of
 * lanes (CLRT_LANES > 1) takes: reductions over the lanes, lane masks as
 * bits, the push of a node's children one after the other (block_push(),
 * which asks the cache for each child pushed: prefetch_child()),
 * and the threshold below which a block's lanes walk alone. Included by
 * clrt_bvh.h where they are used, after the slab tests and the stack. */
#ifndef CLRT_BVH_BLOCK_H
#define CLRT_BVH_BLOCK_H

#if CLRT_LANES > 1
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
  return lane_min4_real(h4);
}

/* A lane mask as bits (lane i, bit i) and back. */
CLRT_INLINE int lane_bits(lint lanes) {
  return LANE_OR(lanes & ((lint)1 << LANE_IOTA));
}
CLRT_INLINE lint bits_lanes(int bits) {
  return (((lint)bits >> LANE_IOTA) & 1) != 0;
}

/* A block of rays at node `index`, child after child: pushes each child
 * that lanes of `active` may meet within their interval, with those lanes'
 * bits and their smallest widened entry distance, keeping those pushed
 * since the call farthest first (insertion: at most CLRT_BVH_WIDTH). (Block
 * walks are float builds only.) */
CLRT_INLINE void block_push(const scene_data* scene, int index, const box_origins* O, const vec3* inverse, real tmin,
                            lreal limit, lint active, walk_stack* stack, int* top) {
  __global const clrt_wide_node* node = &scene->nodes[index];
  const int base = *top;
  for (int slot = 0; slot < CLRT_BVH_WIDTH; ++slot) {
    if (node->count[slot] == 0) continue;
    lreal enter;
    const lint lanes = active & child_overlap(node, slot, O, inverse, tmin, limit, &enter);
    if (!ANY(lanes)) continue;
    const real key =
        as_float(ENTRY_KEY(as_int(BMAX(lane_min_real(lanes ? enter : (lreal)REAL_INFINITY), 0.0f)), slot, 0));
    int k = (*top)++;
    while (k > base && stack->enter[k - 1] < key) {
      stack->node[k] = stack->node[k - 1];
      stack->enter[k] = stack->enter[k - 1];
      stack->lanes[k] = stack->lanes[k - 1];
      --k;
    }
    stack->node[k] = index;
    stack->enter[k] = key;
    stack->lanes[k] = lane_bits(lanes);
    prefetch_child(scene, node, slot);
  }
}

/* A block's rays part ways after a bounce: below a node that few of its
 * lanes' rays meet (CLRT_SOLO_LANES or fewer), a block walk would test each
 * box lane after lane (CLRT_BVH_WIDTH slab tests of the block) for one or
 * two rays. Those lanes walk that subtree alone instead (ray_closest(),
 * ray_any()), every child of a node in one test, as the one-ray walk does. */
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

/* The lowest set bit's index. */
#define LOWEST_BIT(bits) (31 - clz((bits) & -(bits)))
#endif

#endif /* CLRT_BVH_BLOCK_H */
