// device_renderer.cpp - buffers, kernel launches (tiles), profiling, download.
#include "render/device_renderer.hpp"

#include <algorithm>
#include <chrono>

#include "cl/kernel_source.hpp"
#include "cl/program.hpp"
#include "render/scene_buffers.hpp"
#include "util/error.hpp"
#include "util/log.hpp"
#include "util/timer.hpp"

namespace clrt {
namespace {

template <class T>
cl::Buffer upload(const cl::Context& ctx, const cl::CommandQueue& q, const std::vector<T>& v) {
  // Zero-sized buffers are invalid in OpenCL: keep at least one element.
  const T stand_in{};
  const size_t bytes = std::max<size_t>(1, v.size()) * sizeof(T);
  cl::Buffer b(ctx, CL_MEM_READ_ONLY, bytes);
  q.enqueueWriteBuffer(b, CL_TRUE, 0, bytes, v.empty() ? &stand_in : v.data());
  return b;
}

}  // namespace

DeviceRenderer::DeviceRenderer(const DeviceInfo& device, KernelConfig config, LocalSize local, bool map_results)
    : device_(device), config_(std::move(config)), requested_lanes_(config_.lanes), local_(local) {
  if (config_.lanes == 0) config_.lanes = default_lanes(config_, device_);
  map_results_ = map_results && device_.device.getInfo<CL_DEVICE_HOST_UNIFIED_MEMORY>() == CL_TRUE;
  context_ = cl::Context(device_.device);
  queue_ = cl::CommandQueue(context_, device_.device, CL_QUEUE_PROFILING_ENABLE);
  source_ = load_kernel_source("trace.cl", config_.kernel_dir);
}

void DeviceRenderer::prepare(const Scene& scene, int width, int height, int depth, const Bvh* bvh) {
  if (requested_lanes_ == 0) {
    KernelConfig requested = config_;
    requested.lanes = 0;
    config_.lanes = scene_lanes(requested, device_, scene, width, bvh != nullptr);
    if (config_.verbose && bvh)
      log_message(LogLevel::Info, "lanes: " + std::to_string(config_.lanes) + " (" +
                                      std::to_string(scene.spheres.size()) + " spheres, median " +
                                      std::to_string(median_sphere_pixels(scene, width)) + " px on the image)");
  }
  std::string opts = build_options(config_, scene, depth, device_.fp64);
  if (opts != options_ || !kernel_()) {
    BuildStats bs;
    program_ = build_program(context_, device_, source_, opts, &bs, BuildFlags{config_.use_cache, config_.verbose});
    kernel_ = cl::Kernel(program_, "render");
    // Default local size: (preferred multiple, 1), within the kernel's limit.
    size_t pm = kernel_.getWorkGroupInfo<CL_KERNEL_PREFERRED_WORK_GROUP_SIZE_MULTIPLE>(device_.device);
    size_t max_wg = kernel_.getWorkGroupInfo<CL_KERNEL_WORK_GROUP_SIZE>(device_.device);
    default_local_x_ = int(std::max<size_t>(1, std::min(pm, max_wg)));
    max_work_group_ = max_wg;
    options_ = opts;
    timings_.build_ms = bs.ms;
    timings_.build_cached = bs.cached;
  } else {
    timings_.build_ms = 0;
    timings_.build_cached = true;
  }
  check_local_size();
  auto t0 = std::chrono::steady_clock::now();
  SceneData data = pack_scene(scene, config_.precision, width, height, depth);
  params_ = upload(context_, queue_, std::vector<clrt_params>{data.params});
  spheres_ = upload(context_, queue_, data.spheres);
  lights_ = upload(context_, queue_, data.lights);
  if (uses_bvh(config_.accel, scene.spheres.size(), config_.precision) && !bvh)
    throw std::logic_error("BVH build without its hierarchy");
  // (one-element stand-ins when the kernel does not walk a hierarchy; both
  // branches lvalues, so the hierarchy is uploaded without a copy)
  const std::vector<clrt_bvh_node> no_nodes;
  const std::vector<clrt_i32> no_primitives;
  nodes_ = upload(context_, queue_, bvh ? bvh->nodes : no_nodes);
  primitives_ = upload(context_, queue_, bvh ? bvh->primitives : no_primitives);
  timings_.upload_ms = ms_since(t0);
  width_ = width;
  height_ = height;
}

void DeviceRenderer::check_local_size() const {
  if (local_.x <= 0 && local_.y <= 0) return;
  const size_t lx = size_t(std::max(1, local_.x)), ly = size_t(std::max(1, local_.y));
  const auto item_sizes = device_.device.getInfo<CL_DEVICE_MAX_WORK_ITEM_SIZES>();
  const bool fits = lx <= max_work_group_ && ly <= max_work_group_ && lx * ly <= max_work_group_ &&
                    (item_sizes.size() < 2 || (lx <= item_sizes[0] && ly <= item_sizes[1]));
  if (!fits)
    throw UserError("--local " + std::to_string(lx) + "x" + std::to_string(ly) + ": exceeds what " + device_.name +
                    " allows for this kernel (at most " + std::to_string(max_work_group_) + " work-items per group" +
                    (item_sizes.size() >= 2 ? ", " + std::to_string(item_sizes[0]) + "x" + std::to_string(item_sizes[1])
                                            : std::string()) +
                    " per dimension)");
}

void DeviceRenderer::ensure_tile_buffers(size_t pixels) {
  if (pixels <= tile_capacity_) return;
  // Where the device works in host memory, the results are allocated there
  // and mapped after each tile (no copy); elsewhere they are read into
  // staging vectors kept from tile to tile (no new pages per tile).
  const cl_mem_flags flags = CL_MEM_WRITE_ONLY | (map_results_ ? CL_MEM_ALLOC_HOST_PTR : 0);
  colors_ = cl::Buffer(context_, flags, pixels * 3 * sizeof(float));
  classes_ = cl::Buffer(context_, flags, pixels * 2 * sizeof(cl_int));
  ray_counters_ = cl::Buffer(context_, CL_MEM_WRITE_ONLY, (config_.count_rays ? pixels : 1) * sizeof(clrt_ray_counts));
  tile_capacity_ = pixels;
}

LaunchTime DeviceRenderer::render_tile(int x0, int y0, int w, int h, Image& dst) {
  const size_t n = size_t(w) * h;
  ensure_tile_buffers(n);
  kernel_.setArg(0, params_);
  kernel_.setArg(1, spheres_);
  kernel_.setArg(2, lights_);
  kernel_.setArg(3, colors_);
  kernel_.setArg(4, classes_);
  kernel_.setArg(5, ray_counters_);
  kernel_.setArg(6, cl_int(x0));
  kernel_.setArg(7, cl_int(y0));
  kernel_.setArg(8, cl_int(w));
  kernel_.setArg(9, cl_int(h));
  kernel_.setArg(10, nodes_);
  kernel_.setArg(11, primitives_);
  // Each work-item shades a block of kernel_lanes(config_) pixels,
  // packet_rows(config_) of them high.
  const size_t rows = size_t(packet_rows(config_)), cols = size_t(kernel_lanes(config_)) / rows;
  const size_t gw = (size_t(w) + cols - 1) / cols, gh = (size_t(h) + rows - 1) / rows;
  // Always an explicit local size: with NullRange the implementation picks
  // one from the global size, which changes with every band height, and
  // PoCL compiles a new work-group function for each (measured: 1.2 s per
  // 640x480 frame of 5 ms bands instead of 20 ms; docs/performance.md).
  // (check_local_size() bounded both by the device's limits.)
  const size_t lx = size_t(local_.x > 0 ? local_.x : default_local_x_), ly = size_t(local_.y > 0 ? local_.y : 1);
  // Pad the global size to a multiple of the local size, in size_t (no
  // overflow for any tile and local size the checks let through); the
  // kernel ignores work-items outside the tile. Every pixel must be covered.
  const size_t global_x = (gw + lx - 1) / lx * lx, global_y = (gh + ly - 1) / ly * ly;
  if (global_x < gw || global_y < gh) throw std::logic_error("launch does not cover the tile");
  cl::NDRange global(global_x, global_y), local(lx, ly);
  const LaunchTime time = run_timed(queue_, kernel_, global, local);

  auto t0 = std::chrono::steady_clock::now();
  const float* rgb = nullptr;
  const cl_int* aux = nullptr;
  if (map_results_) {
    rgb = static_cast<const float*>(queue_.enqueueMapBuffer(colors_, CL_TRUE, CL_MAP_READ, 0, n * 3 * sizeof(float)));
    aux =
        static_cast<const cl_int*>(queue_.enqueueMapBuffer(classes_, CL_TRUE, CL_MAP_READ, 0, n * 2 * sizeof(cl_int)));
  } else {
    if (staging_rgb_.size() < n * 3) staging_rgb_.resize(n * 3);
    if (staging_aux_.size() < n * 2) staging_aux_.resize(n * 2);
    queue_.enqueueReadBuffer(colors_, CL_TRUE, 0, n * 3 * sizeof(float), staging_rgb_.data());
    queue_.enqueueReadBuffer(classes_, CL_TRUE, 0, n * 2 * sizeof(cl_int), staging_aux_.data());
    rgb = staging_rgb_.data();
    aux = staging_aux_.data();
  }
  if (config_.count_rays) {
    std::vector<clrt_ray_counts> rc(n);
    queue_.enqueueReadBuffer(ray_counters_, CL_TRUE, 0, rc.size() * sizeof(clrt_ray_counts), rc.data());
    for (const auto& c : rc)  // the kernel counts in 32-bit words; they wrap past 2^31 as unsigned
      counts_ += RayCounts{uint32_t(c.primary), uint32_t(c.shadow), uint32_t(c.reflection), uint32_t(c.sphere_tests)};
  }
  for (int ty = 0; ty < h; ++ty) {
    for (int tx = 0; tx < w; ++tx) {
      size_t s = size_t(ty) * w + tx;
      size_t d = size_t(y0 + ty) * dst.width + (x0 + tx);
      for (int c = 0; c < 3; ++c) dst.rgb[d * 3 + c] = rgb[s * 3 + c];
      dst.hit[d] = aux[s * 2];
      dst.shadowed[d] = aux[s * 2 + 1];
    }
  }
  if (map_results_) {
    queue_.enqueueUnmapMemObject(colors_, const_cast<float*>(rgb));
    queue_.enqueueUnmapMemObject(classes_, const_cast<cl_int*>(aux));
    queue_.finish();  // (the next tile's kernel writes them again)
  }
  timings_.download_ms += ms_since(t0);
  return time;
}

void DeviceRenderer::begin_frame() {
  counts_ = {};
  timings_.download_ms = 0;
}

}  // namespace clrt
