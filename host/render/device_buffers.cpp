// device_buffers.cpp - mapping, huge pages and the triangles' upload.
#include "render/device_buffers.hpp"

#include "util/huge_pages.hpp"

namespace clrt {

MappedForWrite::MappedForWrite(const cl::CommandQueue& q, const cl::Buffer& b, size_t bytes)
    : queue_(q), buffer_(b), data_(q.enqueueMapBuffer(b, CL_TRUE, CL_MAP_WRITE_INVALIDATE_REGION, 0, bytes)) {}

MappedForWrite::~MappedForWrite() {
  if (!data_) return;
  try {
    unmap();
  } catch (...) {  // (an error is already on its way)
  }
}

void MappedForWrite::unmap() {
  void* p = data_;
  data_ = nullptr;
  queue_.enqueueUnmapMemObject(buffer_, p);
  queue_.finish();
}

cl::Buffer scene_buffer(const cl::Context& ctx, const cl::CommandQueue& q, size_t bytes, bool huge_pages) {
  if (!huge_pages || !worth_huge_pages(bytes)) return cl::Buffer(ctx, CL_MEM_READ_ONLY, bytes);
  cl::Buffer b(ctx, CL_MEM_READ_ONLY | CL_MEM_ALLOC_HOST_PTR, bytes);
  MappedForWrite mapped(q, b, bytes);
  place_on_huge_pages(mapped.data(), bytes);
  mapped.unmap();
  return b;
}

TriangleUpload::TriangleUpload(const cl::Context& ctx, const cl::CommandQueue& q, size_t count, bool with_lo,
                               bool unified_memory, bool huge_pages)
    : queue_(q), with_lo_(with_lo) {
  const size_t allocated = std::max<size_t>(1, count);
  const cl_mem_flags in_place = unified_memory ? CL_MEM_ALLOC_HOST_PTR : 0;
  triangles = cl::Buffer(ctx, CL_MEM_READ_ONLY | in_place, allocated * sizeof(clrt_triangle));
  triangles_lo = cl::Buffer(ctx, CL_MEM_READ_ONLY | in_place, (with_lo ? allocated : 1) * sizeof(clrt_triangle_lo));
  if (unified_memory && count > 0) {
    // mapped for the packing threads, on 2 MiB pages where asked and worth it
    auto map = [&](std::optional<MappedForWrite>& mapped, const cl::Buffer& buffer, size_t bytes) {
      mapped.emplace(q, buffer, bytes);
      if (huge_pages && worth_huge_pages(bytes)) advise_huge_pages(mapped->data(), bytes);
      return mapped->data();
    };
    output_.triangles = static_cast<clrt_triangle*>(map(mapped_, triangles, count * sizeof(clrt_triangle)));
    if (with_lo)
      output_.triangles_lo =
          static_cast<clrt_triangle_lo*>(map(mapped_lo_, triangles_lo, count * sizeof(clrt_triangle_lo)));
    return;
  }
  output_.sink = [this](const clrt_triangle* hi, const clrt_triangle_lo* lo, size_t n) {
    queue_.enqueueWriteBuffer(triangles, CL_TRUE, written_ * sizeof(clrt_triangle), n * sizeof(clrt_triangle), hi);
    if (with_lo_)
      queue_.enqueueWriteBuffer(triangles_lo, CL_TRUE, written_ * sizeof(clrt_triangle_lo),
                                n * sizeof(clrt_triangle_lo), lo);
    written_ += n;
  };
}

void TriangleUpload::finish() {
  if (mapped_) mapped_->unmap();
  if (mapped_lo_) mapped_lo_->unmap();
}

}  // namespace clrt
