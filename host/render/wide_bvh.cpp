// wide_bvh.cpp - collapsing the binary hierarchy into wide nodes.
#include "render/wide_bvh.hpp"

#include <array>
#include <stdexcept>

namespace clrt {

namespace {

// Half the surface area of a binary node's box (only compared).
double half_area(const clrt_bvh_node& n) {
  const double x = double(n.upper[0]) - n.lower[0], y = double(n.upper[1]) - n.lower[1],
               z = double(n.upper[2]) - n.lower[2];
  return x * y + y * z + z * x;
}

class Collapser {
 public:
  Collapser(const std::vector<clrt_bvh_node>& binary, std::vector<clrt_wide_node>& out) : binary_(binary), out_(out) {}

  // Fills out_[wide] with the children of binary node `node`, appending
  // (depth first) the wide nodes of its inner children.
  void build(size_t wide, size_t node) {
    std::array<size_t, CLRT_BVH_WIDTH> slots{};
    int used = 0;
    const clrt_bvh_node& top = at(node);
    if (top.count >= 0) {
      slots[used++] = node;
    } else {
      slots[used++] = size_t(top.first);
      slots[used++] = size_t(top.first) + 1;
    }
    while (used < CLRT_BVH_WIDTH) {
      int widest = -1;
      double widest_area = -1;
      for (int k = 0; k < used; ++k)
        if (at(slots[k]).count < 0 && half_area(at(slots[k])) > widest_area)
          widest = k, widest_area = half_area(at(slots[k]));
      if (widest < 0) break;  // every slot a leaf
      const size_t first = size_t(at(slots[widest]).first);
      slots[widest] = first;
      slots[used++] = first + 1;
    }
    clrt_wide_node filled{};  // empty slots: count 0, never entered
    std::array<size_t, CLRT_BVH_WIDTH> inner_wide{};
    for (int k = 0; k < used; ++k) {
      const clrt_bvh_node& n = at(slots[k]);
      for (int a = 0; a < 3; ++a) {
        filled.lower[a][k] = n.lower[a];
        filled.upper[a][k] = n.upper[a];
      }
      if (n.count >= 0) {  // a leaf (an empty one stays an empty slot)
        filled.child[k] = n.first;
        filled.count[k] = n.count;
        continue;
      }
      inner_wide[k] = out_.size();
      filled.child[k] = static_cast<clrt_i32>(out_.size());
      filled.count[k] = -1;
      out_.emplace_back();
    }
    out_[wide] = filled;
    for (int k = 0; k < used; ++k)
      if (filled.count[k] < 0) build(inner_wide[k], slots[k]);
  }

 private:
  const clrt_bvh_node& at(size_t node) const {
    if (node >= binary_.size()) throw std::logic_error("collapse_bvh: child outside the hierarchy");
    return binary_[node];
  }

  const std::vector<clrt_bvh_node>& binary_;
  std::vector<clrt_wide_node>& out_;
};

}  // namespace

std::vector<clrt_wide_node> collapse_bvh(const std::vector<clrt_bvh_node>& binary) {
  std::vector<clrt_wide_node> out;
  if (binary.empty()) throw std::logic_error("collapse_bvh: no root");
  out.reserve(binary.size() / 2 + 1);
  out.emplace_back();
  Collapser(binary, out).build(0, 0);
  out.shrink_to_fit();
  return out;
}

}  // namespace clrt
