// wide_bvh.hpp - the binary hierarchy (bvh.hpp) collapsed into the wide
// nodes the kernel walks (clrt_layout.h: clrt_wide_node, up to
// CLRT_BVH_WIDTH children each, boxes stored axis by axis so that a ray
// meets all of a node's children in one SIMD step; kernels/clrt_bvh.h).
//
// Each wide node takes the place of a binary inner node; its slots are
// binary nodes below it, chosen by a cost table over the whole tree (the
// surface-area heuristic, as in Ylitie, Karras and Laine's wide collapse,
// HPG 2017): for every binary node and every number of slots 1..8 it may
// take in its parent, the least expected cost of its subtree, a wide node's
// visit costing kWideNodeCost and a primitive test kWidePrimitiveCost per
// unit of half area. A subtree of at most kWideLeafMax primitives may
// become one leaf (its entries are one run of the list). Before, the
// collapse opened the inner slot of the largest area while there was room,
// and the small subtrees at the bottom became nodes of 2 or 3 slots: 3.84 of
// 8 slots used on the million-triangle mesh, 6.16 now, with 45% fewer nodes
// (docs/results/wide-hierarchy.md).
// Every box is a binary node's box, unchanged: the padding that keeps the
// hierarchy's images equal to brute force carries over as it is.
#pragma once
#include <vector>

#include "clrt_layout.h"

namespace clrt {

// The costs of the collapse's table (measured: a primitive cost of 0.25 to
// 2 moved no frame beyond the noise), and the largest leaf it makes of a
// subtree (the binary tree's own leaves stay, up to kBvhMaxLeafSize).
constexpr double kWideNodeCost = 1, kWidePrimitiveCost = 0.5;
constexpr int kWideLeafMax = 8;

// The wide nodes of `binary` (nodes[0] its root; a root that is a leaf
// becomes a node with one leaf child). The result's nodes[0] is the root;
// every other node is some node's child exactly once.
std::vector<clrt_wide_node> collapse_bvh(const std::vector<clrt_bvh_node>& binary);

}  // namespace clrt
