// wide_bvh.hpp - the binary hierarchy (bvh.hpp) collapsed into the wide
// nodes the kernel walks (clrt_layout.h: clrt_wide_node, up to
// CLRT_BVH_WIDTH children each, boxes stored axis by axis so that a ray
// meets all of a node's children in one SIMD step; kernels/clrt_bvh.h).
//
// Each wide node takes the place of a binary inner node: its children are
// that node's two children, and then, while there is room, the inner child
// of the largest surface area is replaced by its own two children (the
// usual collapse: the big boxes, which most rays meet, are opened first).
// Boxes and leaves are the binary tree's, unchanged: the padding that keeps
// the hierarchy's images equal to brute force carries over as it is.
#pragma once
#include <vector>

#include "clrt_layout.h"

namespace clrt {

// The wide nodes of `binary` (nodes[0] its root; a root that is a leaf
// becomes a node with one leaf child). The result's nodes[0] is the root;
// every other node is some node's child exactly once.
std::vector<clrt_wide_node> collapse_bvh(const std::vector<clrt_bvh_node>& binary);

}  // namespace clrt
