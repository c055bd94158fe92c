// wide_bvh.cpp - collapsing the binary hierarchy into wide nodes.
#include "render/wide_bvh.hpp"

#include <array>
#include <cstdint>
#include <limits>
#include <stdexcept>

namespace clrt {

namespace {

constexpr double kNever = std::numeric_limits<double>::infinity();

// Half the surface area of a binary node's box: the chance, up to a common
// factor, that a ray meets it (the surface-area heuristic).
double half_area(const clrt_bvh_node& n) {
  const double x = double(n.upper[0]) - n.lower[0], y = double(n.upper[1]) - n.lower[1],
               z = double(n.upper[2]) - n.lower[2];
  return x * y + y * z + z * x;
}

// A binary subtree's primitive entries: [first, first + count) when they
// are one run of the list (the builder appends them depth first, so they
// are), first = -1 otherwise (then it never becomes one leaf).
struct Entries {
  clrt_i32 first = 0;
  std::uint32_t count = 0;
};

// What the cost table chose for a binary node, packed in 32 bits (the
// table itself lives only on the recursion's stack):
//  - bit 0: with one slot, the subtree is one leaf (else one wide node);
//  - bits 1-3 + 3(j - 2), j = 2..8: with j slots, how many of them the
//    left child takes (0: fewer than j slots cost no more);
//  - bits 22-24: with a whole wide node (8 slots, none spared), the left
//    child's share.
using Choice = std::uint32_t;
constexpr int kSpreadShift = 22;

class Collapser {
 public:
  Collapser(const std::vector<clrt_bvh_node>& binary, std::vector<clrt_wide_node>& out)
      : binary_(binary), out_(out), choice_(binary.size()), entries_(binary.size()) {}

  // The cost of binary subtree `node` for each number of slots it may take
  // in its parent, 1..CLRT_BVH_WIDTH (cost[j - 1]), its choices in choice_.
  std::array<double, CLRT_BVH_WIDTH> cost(size_t node, int depth) {
    if (depth > CLRT_BVH_MAX_DEPTH) throw std::logic_error("collapse_bvh: deeper than CLRT_BVH_MAX_DEPTH");
    const clrt_bvh_node& n = at(node);
    const double area = half_area(n);
    std::array<double, CLRT_BVH_WIDTH> out{};
    if (n.count >= 0) {  // a leaf stays one, whatever the slots
      entries_[node] = {n.first, std::uint32_t(n.count)};
      choice_[node] = 1;
      out.fill(area * double(n.count) * kWidePrimitiveCost);
      return out;
    }
    const size_t left = size_t(n.first), right = left + 1;
    const std::array<double, CLRT_BVH_WIDTH> a = cost(left, depth + 1), b = cost(right, depth + 1);
    // The children's entries: one run if the left's ends where the right's begins.
    const Entries& l = entries_[left];
    const Entries& r = entries_[right];
    Entries& e = entries_[node];
    e.count = l.count + r.count;
    if (l.count == 0)
      e.first = r.first;
    else if (r.count == 0 || (l.first >= 0 && size_t(l.first) + l.count == size_t(r.first)))
      e.first = l.first;
    else
      e.first = -1;
    // spread[j - 1]: the least cost of j slots shared by the two children.
    std::array<double, CLRT_BVH_WIDTH> spread;
    std::array<int, CLRT_BVH_WIDTH> share{};
    spread.fill(kNever);
    for (int j = 2; j <= CLRT_BVH_WIDTH; ++j)
      for (int k = 1; k < j; ++k)
        if (a[size_t(k - 1)] + b[size_t(j - k - 1)] < spread[size_t(j - 1)])
          spread[size_t(j - 1)] = a[size_t(k - 1)] + b[size_t(j - k - 1)], share[size_t(j - 1)] = k;
    Choice choice = Choice(share[CLRT_BVH_WIDTH - 1]) << kSpreadShift;
    // One slot: a leaf of the whole subtree (small enough, one run of
    // entries), or a wide node of its own over CLRT_BVH_WIDTH slots.
    const double as_node = area * kWideNodeCost + spread[CLRT_BVH_WIDTH - 1];
    const double as_leaf =
        e.first >= 0 && e.count <= std::uint32_t(kWideLeafMax) ? area * double(e.count) * kWidePrimitiveCost : kNever;
    out[0] = as_leaf <= as_node ? as_leaf : as_node;
    if (as_leaf <= as_node) choice |= 1;
    for (int j = 2; j <= CLRT_BVH_WIDTH; ++j) {
      out[size_t(j - 1)] = out[size_t(j - 2)];
      if (spread[size_t(j - 1)] < out[size_t(j - 1)]) {
        out[size_t(j - 1)] = spread[size_t(j - 1)];
        choice |= Choice(share[size_t(j - 1)]) << (1 + 3 * (j - 2));
      }
    }
    choice_[node] = choice;
    return out;
  }

  // Fills out_[wide] with the slots of binary inner node `node` (or, for a
  // root that is a leaf, that leaf), appending (depth first) the wide nodes
  // of the slots that are nodes.
  void build(size_t wide, size_t node) {
    Slots slots;
    const clrt_bvh_node& top = at(node);
    if (top.count >= 0) {
      slots.add(node);
    } else {
      const int k = int(choice_[node] >> kSpreadShift & 7);
      gather(size_t(top.first), k, slots);
      gather(size_t(top.first) + 1, CLRT_BVH_WIDTH - k, slots);
    }
    clrt_wide_node filled{};  // empty slots: count 0, never entered
    std::array<size_t, CLRT_BVH_WIDTH> inner_wide{};
    for (int k = 0; k < slots.used; ++k) {
      const clrt_bvh_node& n = at(slots[k]);
      for (int a = 0; a < 3; ++a) {
        filled.lower[a][k] = n.lower[a];
        filled.upper[a][k] = n.upper[a];
      }
      if (n.count >= 0 || (choice_[slots[k]] & 1)) {  // a leaf (an empty one stays an empty slot)
        filled.child[k] = entries_[slots[k]].first;
        filled.count[k] = static_cast<clrt_i32>(entries_[slots[k]].count);
        continue;
      }
      inner_wide[k] = out_.size();
      filled.child[k] = static_cast<clrt_i32>(out_.size());
      filled.count[k] = -1;
      out_.emplace_back();
    }
    out_[wide] = filled;
    for (int k = 0; k < slots.used; ++k)
      if (filled.count[k] < 0) build(inner_wide[k], slots[k]);
  }

 private:
  // A wide node's slots: the binary nodes they hold, in order.
  struct Slots {
    std::array<size_t, CLRT_BVH_WIDTH> node{};
    int used = 0;
    void add(size_t binary) {
      if (used == CLRT_BVH_WIDTH) throw std::logic_error("collapse_bvh: more slots than a node has");
      node[size_t(used++)] = binary;
    }
    size_t operator[](int k) const { return node[size_t(k)]; }
  };

  // The slots subtree `node` takes when given `j`, in the children's order.
  void gather(size_t node, int j, Slots& slots) const {
    for (; j > 1; --j) {
      const int k = int(choice_[node] >> (1 + 3 * (j - 2)) & 7);
      if (k == 0) continue;  // fewer slots cost no more
      gather(size_t(at(node).first), k, slots);
      gather(size_t(at(node).first) + 1, j - k, slots);
      return;
    }
    slots.add(node);
  }

  const clrt_bvh_node& at(size_t node) const {
    if (node >= binary_.size()) throw std::logic_error("collapse_bvh: child outside the hierarchy");
    return binary_[node];
  }

  const std::vector<clrt_bvh_node>& binary_;
  std::vector<clrt_wide_node>& out_;
  std::vector<Choice> choice_;
  std::vector<Entries> entries_;
};

}  // namespace

std::vector<clrt_wide_node> collapse_bvh(const std::vector<clrt_bvh_node>& binary) {
  std::vector<clrt_wide_node> out;
  if (binary.empty()) throw std::logic_error("collapse_bvh: no root");
  Collapser collapser(binary, out);
  collapser.cost(0, 0);
  out.reserve(binary.size() / 4 + 1);
  out.emplace_back();
  collapser.build(0, 0);
  out.shrink_to_fit();
  return out;
}

}  // namespace clrt
