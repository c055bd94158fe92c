// pack_triangles.cpp - triangles packed and their materials numbered in
// blocks, each block on one thread, so that the result is the same on any
// number of threads.
#include "render/pack_triangles.hpp"

#include <algorithm>
#include <map>
#include <stdexcept>
#include <tuple>

#include "render/scene_buffers.hpp"
#include "util/content_hash.hpp"
#include "util/parallel.hpp"

namespace clrt {
namespace {

// Triangles per block of the materials' numbering.
constexpr size_t kMaterialBlock = size_t(1) << 16;

static_assert(kTriangleChunk % kTriangleHashBlock == 0, "a chunk is whole hash blocks");

}  // namespace

MaterialKey material_key(const Material& m) {
  return std::make_tuple(m.color.x, m.color.y, m.color.z, m.specular, m.reflective);
}

std::vector<clrt_i32> triangle_material_entries(const Scene& scene,
                                                const std::function<clrt_i32(const Material&)>& entry_of) {
  const size_t count = scene.triangles.size();
  const size_t blocks = (count + kMaterialBlock - 1) / kMaterialBlock;
  std::vector<clrt_i32> entries(count);
  // Each block: its distinct materials in order of first use, and each
  // triangle's place in that list.
  std::vector<std::vector<const Material*>> distinct(blocks);
  parallel_chunks(blocks, 1, [&](size_t begin, size_t end) {
    for (size_t block = begin; block < end; ++block) {
      std::map<MaterialKey, clrt_i32> seen;
      const Material* previous = nullptr;
      clrt_i32 previous_place = -1;
      for (size_t k = block * kMaterialBlock; k < std::min(count, (block + 1) * kMaterialBlock); ++k) {
        const Material& m = scene.triangles[k].material;
        if (!previous || material_key(*previous) != material_key(m)) {
          const auto [at, added] = seen.emplace(material_key(m), clrt_i32(distinct[block].size()));
          if (added) distinct[block].push_back(&m);
          previous = &m, previous_place = at->second;
        }
        entries[k] = previous_place;
      }
    }
  });
  // The entries, in the order of first use over the whole scene.
  std::vector<std::vector<clrt_i32>> block_entries(blocks);
  for (size_t block = 0; block < blocks; ++block)
    for (const Material* m : distinct[block]) block_entries[block].push_back(entry_of(*m));
  parallel_chunks(count, kMaterialBlock, [&](size_t begin, size_t end) {
    for (size_t k = begin; k < end; ++k) entries[k] = block_entries[k / kMaterialBlock][size_t(entries[k])];
  });
  return entries;
}

void pack_triangles(const Scene& scene, const Vec3& shift, const std::vector<clrt_i32>* order,
                    const std::vector<clrt_i32>& material_entries, size_t first, size_t count, clrt_triangle* out,
                    clrt_triangle_lo* out_lo, std::vector<uint64_t>& hashes) {
  if (first % kTriangleHashBlock != 0 || first > scene.triangles.size() || count > scene.triangles.size() - first)
    throw std::logic_error("pack_triangles: a range outside the scene's triangles");
  if (order && order->size() != scene.triangles.size())
    throw std::logic_error("pack_triangles: a triangle order of another scene");
  const size_t blocks = (count + kTriangleHashBlock - 1) / kTriangleHashBlock;
  const size_t hashed = hashes.size();
  hashes.resize(hashed + blocks);
  parallel_chunks(blocks, 1, [&](size_t begin, size_t end) {
    std::vector<clrt_triangle_lo> scratch(out_lo ? 0 : kTriangleHashBlock);  // lo parts not kept: hashed all the same
    for (size_t block = begin; block < end; ++block) {
      const size_t b0 = block * kTriangleHashBlock, n = std::min(kTriangleHashBlock, count - b0);
      clrt_triangle* hi = out + b0;
      clrt_triangle_lo* lo = out_lo ? out_lo + b0 : scratch.data();
      for (size_t i = 0; i < n; ++i) {
        const size_t index = order ? size_t(order->at(first + b0 + i)) : first + b0 + i;
        const Triangle& t = scene.triangles.at(index);
        hi[i] = clrt_triangle{};
        lo[i] = clrt_triangle_lo{};
        hi[i].index = static_cast<clrt_i32>(index);
        split3(t.v0 - shift, hi[i].v0, lo[i].v0_lo);
        split3(t.v1 - shift, hi[i].v1, lo[i].v1_lo);
        split3(t.v2 - shift, hi[i].v2, lo[i].v2_lo);
        hi[i].material = material_entries.at(index);
      }
      ContentHash hash;
      hash.add(hi, n * sizeof(clrt_triangle));
      hash.add(lo, n * sizeof(clrt_triangle_lo));
      hashes[hashed + block] = hash.value;
    }
  });
}

}  // namespace clrt
