// bvh.cpp - binned-SAH build of the sphere hierarchy, flattened depth-first
// with each node's two children side by side.
#include "render/bvh.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <future>
#include <limits>
#include <stdexcept>
#include <thread>
#include <utility>

#include "render/wide_bvh.hpp"
#include "util/doing.hpp"
#include "util/error.hpp"

namespace clrt {

namespace {

// Each mode and its --accel name.
constexpr std::pair<Accel, const char*> kAccelNames[] = {
    {Accel::Auto, "auto"}, {Accel::None, "none"}, {Accel::Bvh, "bvh"}};

}  // namespace

Accel parse_accel(const std::string& name) {
  for (const auto& [accel, accel_text] : kAccelNames)
    if (name == accel_text) return accel;
  throw UserError("--accel: expected auto, bvh or none (got \"" + name.substr(0, 64) + "\")");
}

std::string accel_name(Accel accel) {
  for (const auto& [mode, text] : kAccelNames)
    if (mode == accel) return text;
  return "auto";  // unreachable: every Accel is listed above
}

size_t bvh_primitive_count(const Scene& scene) {
  return scene.spheres.size() + scene.triangles.size();
}

bool uses_bvh(Accel accel, size_t primitive_count, Precision precision) {
  if (accel == Accel::Auto) return primitive_count >= kBvhMinSpheres && precision != Precision::Naive;
  return accel == Accel::Bvh;
}

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

struct Box {
  std::array<double, 3> lower{kInfinity, kInfinity, kInfinity};
  std::array<double, 3> upper{-kInfinity, -kInfinity, -kInfinity};

  void grow(const Box& other) {
    for (int a = 0; a < 3; ++a) {
      lower[a] = std::min(lower[a], other.lower[a]);
      upper[a] = std::max(upper[a], other.upper[a]);
    }
  }
  bool empty() const { return lower[0] > upper[0]; }
  // Half the surface area (the heuristic compares ratios only).
  double half_area() const {
    if (empty()) return 0;
    const double x = upper[0] - lower[0], y = upper[1] - lower[1], z = upper[2] - lower[2];
    return x * y + y * z + z * x;
  }
};

// Outward rounding to float: the float box contains the double one.
float round_down(double v) {
  float f = static_cast<float>(v);
  if (static_cast<double>(f) > v) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
  return f;
}
float round_up(double v) {
  float f = static_cast<float>(v);
  if (static_cast<double>(f) < v) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

// A primitive as the build sorts it, in float: 40 bytes instead of 80 in
// double, which at 4 million triangles was the preparation's peak once the
// triangles went to the device in chunks (docs/results/meshes.md). The box
// is rounded outward, so it holds the padded double box, and the nodes'
// boxes are float anyway; the centroid only picks bins.
struct Item {
  std::array<float, 3> lower, upper;  // the padded box, rounded outward
  std::array<float, 3> centroid;      // its centre
  clrt_i32 entry;                     // kind << shift | index

  void set_box(const Box& box) {
    for (int a = 0; a < 3; ++a) {
      lower[a] = round_down(box.lower[a]);
      upper[a] = round_up(box.upper[a]);
    }
  }
  Box box() const {
    Box b;
    for (int a = 0; a < 3; ++a) b.lower[a] = lower[a], b.upper[a] = upper[a];
    return b;
  }
  Box centre_point() const {
    Box b;
    for (int a = 0; a < 3; ++a) b.lower[a] = b.upper[a] = centroid[a];
    return b;
  }
};

// Subtrees of at least this many spheres may be built on another thread (a
// thread costs ~20 us; a subtree of 8 192 spheres ~2 ms).
constexpr size_t kParallelMinItems = 8192;

// Threads the whole build may use at once, the calling one included.
class ThreadBudget {
 public:
  explicit ThreadBudget(int threads) : free_(threads - 1) {}
  bool take() {
    int n = free_.load();
    while (n > 0)
      if (free_.compare_exchange_weak(n, n - 1)) return true;
    return false;
  }
  void give_back() { ++free_; }

 private:
  std::atomic<int> free_;
};

class Builder {
 public:
  Builder(std::vector<Item>& items, Bvh& out, ThreadBudget& threads) : items_(items), out_(out), threads_(threads) {}

  // Builds node `node` of out_ over items_[begin, end). The layout does not
  // depend on which subtrees run on other threads: a subtree built apart
  // lands where the one-thread build would have put it (splice()).
  void build(size_t node, size_t begin, size_t end, int depth) {
    Box bounds, centroids;
    for (size_t i = begin; i < end; ++i) {
      bounds.grow(items_[i].box());
      centroids.grow(items_[i].centre_point());
    }
    set_box(node, bounds);
    out_.depth = std::max(out_.depth, depth);
    const size_t count = end - begin;
    int axis = -1;
    size_t middle = begin;
    if (count > size_t(kBvhLeafSize) && depth < CLRT_BVH_MAX_DEPTH - 1)
      choose_split(begin, end, bounds, centroids, axis, middle);
    if (axis < 0) {
      make_leaf(node, begin, end);
      return;
    }
    const size_t children = out_.nodes.size();
    out_.nodes.resize(children + 2);
    out_.nodes[node].first = static_cast<clrt_i32>(children);
    out_.nodes[node].count = -(axis + 1);
    if (std::min(middle - begin, end - middle) >= kParallelMinItems && threads_.take()) {
      // The second child on another thread, into a hierarchy of its own.
      Bvh part;
      part.nodes.resize(1);
      auto done = std::async(std::launch::async, [&, middle, end, depth] {
        Builder(items_, part, threads_).build(0, middle, end, depth + 1);
      });
      try {
        build(children, begin, middle, depth + 1);
      } catch (...) {
        done.wait();
        threads_.give_back();
        throw;
      }
      done.wait();
      threads_.give_back();
      done.get();  // rethrows the other thread's exception (bad_alloc)
      splice(children + 1, part);
      return;
    }
    build(children, begin, middle, depth + 1);
    build(children + 1, middle, end, depth + 1);
  }

 private:
  // The binned SAH split of [begin, end): sets axis (-1 = a leaf is cheaper
  // or nothing separates the centroids) and partitions items around middle.
  void choose_split(size_t begin, size_t end, const Box& bounds, const Box& centroids, int& axis, size_t& middle) {
    const size_t count = end - begin;
    double best_cost = kInfinity;
    int best_axis = -1, best_bin = 0;
    for (int a = 0; a < 3; ++a) {
      const double low = centroids.lower[a], extent = centroids.upper[a] - low;
      if (!(extent > 0)) continue;
      std::array<Box, kBvhBins> boxes;
      std::array<size_t, kBvhBins> counts{};
      for (size_t i = begin; i < end; ++i) {
        const int b = bin(items_[i].centroid[a], low, extent);
        boxes[b].grow(items_[i].box());
        ++counts[b];
      }
      // Costs of splitting after bin b: left [0, b], right [b + 1, bins).
      std::array<double, kBvhBins> right_cost{};
      Box right;
      size_t right_count = 0;
      for (int b = kBvhBins - 1; b > 0; --b) {
        right.grow(boxes[b]);
        right_count += counts[b];
        right_cost[b - 1] = right.half_area() * double(right_count);
      }
      Box left;
      size_t left_count = 0;
      for (int b = 0; b < kBvhBins - 1; ++b) {
        left.grow(boxes[b]);
        left_count += counts[b];
        if (left_count == 0 || left_count == count) continue;
        const double cost = left.half_area() * double(left_count) + right_cost[b];
        if (cost < best_cost) best_cost = cost, best_axis = a, best_bin = b;
      }
    }
    if (best_axis < 0) {
      // Every centroid in one place (coincident or identical primitives):
      // no plane separates them, but a leaf of millions would make every
      // ray that meets it test them all, and keep a shadow ray from stopping
      // early. Halve by count instead, so leaves stay at most
      // kBvhMaxLeafSize; both halves keep one box (the same order as given).
      if (count > size_t(kBvhMaxLeafSize)) {
        axis = 0;
        for (int a = 1; a < 3; ++a)
          if (bounds.upper[a] - bounds.lower[a] > bounds.upper[axis] - bounds.lower[axis]) axis = a;
        middle = begin + count / 2;
      }
      return;
    }
    // A leaf costs a test of each primitive for every ray that meets the box;
    // a split, one box test more and the children's tests.
    const double leaf_cost = bounds.half_area() * double(count);
    if (best_cost >= leaf_cost && count <= size_t(kBvhMaxLeafSize)) return;
    const double low = centroids.lower[best_axis], extent = centroids.upper[best_axis] - low;
    auto split =
        std::partition(items_.begin() + std::ptrdiff_t(begin), items_.begin() + std::ptrdiff_t(end),
                       [&](const Item& item) { return bin(item.centroid[best_axis], low, extent) <= best_bin; });
    axis = best_axis;
    middle = size_t(split - items_.begin());
  }

  static int bin(double value, double low, double extent) {
    const int b = static_cast<int>(double(kBvhBins) * (value - low) / extent);
    return std::clamp(b, 0, kBvhBins - 1);
  }

  void set_box(size_t node, const Box& box) {
    clrt_bvh_node& n = out_.nodes[node];
    for (int a = 0; a < 3; ++a) {
      n.lower[a] = box.empty() ? 0.0f : round_down(box.lower[a]);
      n.upper[a] = box.empty() ? 0.0f : round_up(box.upper[a]);
    }
  }

  void make_leaf(size_t node, size_t begin, size_t end) {
    out_.nodes[node].first = static_cast<clrt_i32>(out_.primitives.size());
    out_.nodes[node].count = static_cast<clrt_i32>(end - begin);
    for (size_t i = begin; i < end; ++i) out_.primitives.push_back(items_[i].entry);
  }

  // Puts `part` (a subtree built apart, its root part.nodes[0]) at `node`,
  // its other nodes and its entries at the ends of out_'s lists, as the
  // one-thread build would have appended them.
  void splice(size_t node, const Bvh& part) {
    const clrt_i32 node_base = static_cast<clrt_i32>(out_.nodes.size()) - 1;  // part's node 1 goes here + 1
    const clrt_i32 entry_base = static_cast<clrt_i32>(out_.primitives.size());
    auto moved = [&](clrt_bvh_node n) {
      n.first += n.count < 0 ? node_base : entry_base;
      return n;
    };
    out_.nodes[node] = moved(part.nodes[0]);
    for (size_t i = 1; i < part.nodes.size(); ++i) out_.nodes.push_back(moved(part.nodes[i]));
    out_.primitives.insert(out_.primitives.end(), part.primitives.begin(), part.primitives.end());
    out_.depth = std::max(out_.depth, part.depth);
  }

  std::vector<Item>& items_;
  Bvh& out_;
  ThreadBudget& threads_;
};

}  // namespace

namespace {

// The scene's extent relative to `origin`, camera included: the largest
// coordinate of any point a ray may start from or reach.
double scene_extent(const Scene& scene, Vec3 origin) {
  const Vec3 eye = scene.camera.position - origin;
  double extent = std::max({std::fabs(eye.x), std::fabs(eye.y), std::fabs(eye.z)});
  for (const Sphere& s : scene.spheres) {
    const Vec3 c = s.center - origin;
    extent = std::max({extent, std::fabs(c.x) + s.radius, std::fabs(c.y) + s.radius, std::fabs(c.z) + s.radius});
  }
  for (const Triangle& t : scene.triangles)
    for (const Vec3& v : {t.v0, t.v1, t.v2}) {
      const Vec3 c = v - origin;
      extent = std::max({extent, std::fabs(c.x), std::fabs(c.y), std::fabs(c.z)});
    }
  return extent;
}

}  // namespace

double bvh_padding_scale(Precision precision, bool spheres) {
  return CLRT_BVH_PAD(kernel_code(precision), spheres);
}

Bvh build_bvh(const Scene& scene, Precision precision, Vec3 origin, int threads) {
  const Doing doing("building the hierarchy of " + std::to_string(scene.spheres.size()) + " spheres and " +
                    std::to_string(scene.triangles.size()) + " triangles");
  if (scene.spheres.size() > size_t(CLRT_PRIMITIVE_INDEX_MASK))
    throw UserError("scene has " + std::to_string(scene.spheres.size()) + " spheres; the hierarchy holds at most " +
                    std::to_string(CLRT_PRIMITIVE_INDEX_MASK));
  if (scene.triangles.size() > size_t(CLRT_PRIMITIVE_INDEX_MASK))
    throw UserError("scene has " + std::to_string(scene.triangles.size()) + " triangles; the hierarchy holds at most " +
                    std::to_string(CLRT_PRIMITIVE_INDEX_MASK));
  // (naive's grazing hits scale with the extent, bvh.hpp)
  const double extent = precision == Precision::Naive ? scene_extent(scene, origin) : 0;
  Bvh bvh;
  bvh.padding_scale = bvh_padding_scale(precision, !scene.spheres.empty());
  std::vector<Item> items(scene.spheres.size() + scene.triangles.size());
  for (size_t i = 0; i < scene.spheres.size(); ++i) {
    const Sphere& s = scene.spheres[i];
    const Vec3 relative = s.center - origin;  // as pack_scene() computes it
    const std::array<double, 3> c{relative.x, relative.y, relative.z};
    // The naive variant's grazing hits, ~2^-22 E^2 / r from the sphere.
    const double own = bvh.padding_scale * (std::max({std::fabs(c[0]), std::fabs(c[1]), std::fabs(c[2])}) + s.radius);
    const double pad = precision == Precision::Naive ? own + std::ldexp(extent * extent / s.radius, -22) : own;
    // (each step rounded outward: the box holds the exact one)
    Box box;
    for (int a = 0; a < 3; ++a) {
      box.lower[a] = std::nextafter(std::nextafter(c[a] - s.radius, -kInfinity) - pad, -kInfinity);
      box.upper[a] = std::nextafter(std::nextafter(c[a] + s.radius, kInfinity) + pad, kInfinity);
      items[i].centroid[a] = static_cast<float>(c[a]);
    }
    items[i].set_box(box);
    items[i].entry =
        static_cast<clrt_i32>(CLRT_PRIMITIVE_SPHERE << CLRT_PRIMITIVE_KIND_SHIFT) | static_cast<clrt_i32>(i);
  }
  // Triangles: the box of the vertices as the kernel sees them (float hi
  // parts, or the double for fp64), padded like a sphere's: the watertight
  // test reports a hit only for rays through the triangle or within its
  // edge functions' rounding of it.
  for (size_t k = 0; k < scene.triangles.size(); ++k) {
    const Triangle& t = scene.triangles[k];
    Item& item = items[scene.spheres.size() + k];
    std::array<double, 3> sum{0, 0, 0};
    Box box;
    const std::array<Vec3, 3> vertices{t.v0 - origin, t.v1 - origin, t.v2 - origin};
    double largest = 0;
    for (const Vec3& c : vertices) largest = std::max({largest, std::fabs(c.x), std::fabs(c.y), std::fabs(c.z)});
    const double pad = bvh.padding_scale * largest;
    for (const Vec3& relative : vertices) {
      const std::array<double, 3> c{relative.x, relative.y, relative.z};
      for (int a = 0; a < 3; ++a) {
        box.lower[a] = std::min(box.lower[a], std::nextafter(c[a] - pad, -kInfinity));
        box.upper[a] = std::max(box.upper[a], std::nextafter(c[a] + pad, kInfinity));
        sum[a] += c[a];
      }
    }
    item.set_box(box);
    for (int a = 0; a < 3; ++a) item.centroid[a] = static_cast<float>(sum[a] / 3);
    item.entry = static_cast<clrt_i32>(CLRT_PRIMITIVE_TRIANGLE << CLRT_PRIMITIVE_KIND_SHIFT) | static_cast<clrt_i32>(k);
  }
  bvh.nodes.reserve(2 * items.size() + 1);
  bvh.nodes.resize(1);
  if (threads <= 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  ThreadBudget budget(threads);
  Builder(items, bvh, budget).build(0, 0, items.size(), 0);
  std::vector<Item>().swap(items);
  bvh.wide = collapse_bvh(bvh.nodes);
  // triangle entries renamed to their place in the leaves' order
  bvh.triangle_order.reserve(scene.triangles.size());
  for (clrt_i32& entry : bvh.primitives)
    if ((entry >> CLRT_PRIMITIVE_KIND_SHIFT) == CLRT_PRIMITIVE_TRIANGLE) {
      bvh.triangle_order.push_back(entry & CLRT_PRIMITIVE_INDEX_MASK);
      entry = static_cast<clrt_i32>(CLRT_PRIMITIVE_TRIANGLE << CLRT_PRIMITIVE_KIND_SHIFT) |
              static_cast<clrt_i32>(bvh.triangle_order.size() - 1);
    }
  return bvh;
}

std::vector<clrt_i32> triangle_slots(const Bvh& bvh) {
  std::vector<clrt_i32> slots(bvh.triangle_order.size(), -1);
  for (size_t k = 0; k < bvh.triangle_order.size(); ++k) {
    const size_t index = size_t(bvh.triangle_order[k]);
    if (index >= slots.size() || slots[index] >= 0) throw std::logic_error("triangle_order is not a permutation");
    slots[index] = static_cast<clrt_i32>(k);
  }
  return slots;
}

}  // namespace clrt
