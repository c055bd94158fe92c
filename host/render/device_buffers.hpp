// device_buffers.hpp - the scene's read-only buffers on an OpenCL device:
// written from host vectors (upload()), the hierarchy's on 2 MiB pages on a
// CPU, and the triangles packed straight into theirs (TriangleUpload).
#pragma once
#include <algorithm>
#include <cstddef>
#include <optional>
#include <vector>

#include "cl/cl.hpp"
#include "render/scene_buffers.hpp"

namespace clrt {

// A buffer mapped for writing, its old contents dropped, until unmap() (or
// the end of its scope, where an exception passes).
class MappedForWrite {
 public:
  MappedForWrite(const cl::CommandQueue& q, const cl::Buffer& b, size_t bytes);
  MappedForWrite(const MappedForWrite&) = delete;
  MappedForWrite& operator=(const MappedForWrite&) = delete;
  ~MappedForWrite();
  void* data() const { return data_; }
  void unmap();

 private:
  cl::CommandQueue queue_;
  cl::Buffer buffer_;
  void* data_;
};

// A read-only scene buffer of `bytes`. On a CPU device that shares the
// host's memory (PoCL, llvmpipe), the hierarchy's buffers of 8 MiB or more
// (worth_huge_pages()) are asked for on 2 MiB pages before anything is
// written to them: a walk reads a node at every step, all over tens of MiB,
// and with 4 KiB pages
// nearly every read that misses the caches also misses the TLB (Embree asks
// the same for its hierarchy). The buffer is mapped, its storage advised
// and touched once per 2 MiB page by every core (a huge page's first touch
// clears it: on this project's KVM machine ~1 ms each, so one thread would
// add ~270 ms to the upload of 4 million triangles' buffers), and unmapped;
// where the mapped pointer is not the device's storage the hint changes
// nothing. (The triangles are packed straight into theirs: TriangleUpload.)
cl::Buffer scene_buffer(const cl::Context& ctx, const cl::CommandQueue& q, size_t bytes, bool huge_pages);

// The vector's contents in a new read-only buffer (one element at least:
// zero-sized buffers are invalid), on 2 MiB pages as scene_buffer() says.
template <class T>
cl::Buffer upload(const cl::Context& ctx, const cl::CommandQueue& q, const std::vector<T>& v, bool huge_pages = false) {
  // Zero-sized buffers are invalid in OpenCL: keep at least one element.
  const T stand_in{};
  const size_t bytes = std::max<size_t>(1, v.size()) * sizeof(T);
  cl::Buffer b = scene_buffer(ctx, q, bytes, huge_pages);
  q.enqueueWriteBuffer(b, CL_TRUE, 0, bytes, v.empty() ? &stand_in : v.data());
  return b;
}

// The triangles' two buffers (clrt_triangle, and clrt_triangle_lo where the
// variant reads them, else one element), and where pack_scene() puts them:
// where the device shares the host's memory, straight into the mapped
// buffers, packed on every core (on 2 MiB pages on a CPU from the same
// size as the hierarchy's: the packing threads' writes are the pages' first
// touch, so their clearing is shared out as place_on_huge_pages() does; 4 million
// triangles' frame -7%, docs/results/wide-hierarchy.md); else a chunk at a
// time through a write.
class TriangleUpload {
 public:
  TriangleUpload(const cl::Context& ctx, const cl::CommandQueue& q, size_t count, bool with_lo, bool unified_memory,
                 bool huge_pages);
  const TriangleOutput& output() const { return output_; }
  // After pack_scene(): the buffers are the device's.
  void finish();

  cl::Buffer triangles, triangles_lo;

 private:
  cl::CommandQueue queue_;
  bool with_lo_;
  size_t written_ = 0;
  std::optional<MappedForWrite> mapped_, mapped_lo_;
  TriangleOutput output_;
};

}  // namespace clrt
