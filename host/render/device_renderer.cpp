// device_renderer.cpp - buffers, kernel launches (tiles), profiling, download.
#include "render/device_renderer.hpp"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <limits>

#include "cl/kernel_source.hpp"
#include "cl/program.hpp"
#include "render/device_buffers.hpp"
#include "render/kernel_args.hpp"
#include "render/lane_choice.hpp"
#include "render/scene_buffers.hpp"
#include "util/error.hpp"
#include "util/log.hpp"
#include "util/timer.hpp"

namespace clrt {

DeviceRenderer::DeviceRenderer(const DeviceInfo& device, KernelConfig config, LocalSize local, bool map_results,
                               bool overlap)
    : device_(device), config_(std::move(config)), requested_lanes_(config_.lanes), local_(local), overlap_(overlap) {
  if (config_.lanes == 0) config_.lanes = default_lanes(config_, device_);  // until prepare() chooses
  config_.loop_limit_probe = config_.loop_limit_probe || ends_long_loops(device_);
  if (!config_.fast_fma) config_.fast_fma = fuses_multiply_add(device_);
  unified_memory_ = device_.device.getInfo<CL_DEVICE_HOST_UNIFIED_MEMORY>() == CL_TRUE;
  map_results_ = map_results && unified_memory_;
  huge_pages_ = is_cpu_type(device_.type) && unified_memory_;
  context_ = cl::Context(device_.device);
  queue_ = cl::CommandQueue(context_, device_.device, CL_QUEUE_PROFILING_ENABLE);
  if (!map_results_) transfer_queue_ = cl::CommandQueue(context_, device_.device);
  source_ = load_kernel_source("trace.cl", config_.kernel_dir);
}

void DeviceRenderer::prepare(const Scene& scene, int width, int height, int depth, Sampling sampling, const Bvh* bvh) {
  ms_per_row_ = 0;  // another scene, size or depth: another rate
  if (sampling.subsample != Subsample::Off && sampling.spp != 1)
    throw UserError("subsampling needs one sample per pixel (--spp 1)");
  if (sampling.subsample != config_.subsample) {
    drain();
    for (ResultSlot& slot : slots_) slot.capacity = 0;  // the hit-id buffers' sizes change
    config_.subsample = sampling.subsample;
  }
  timings_.build_ms = 0;
  timings_.build_cached = true;
  timings_.probe_ms = 0;
  KernelConfig requested = config_;
  requested.lanes = requested_lanes_;
  const std::vector<int> candidates = lane_candidates(requested, device_, bvh != nullptr);
  // (the first candidate's options also check them: fp64, lanes, before any upload)
  config_.lanes = candidates.front();
  features_ = kernel_features(scene, depth);
  const std::string first_options = scene_options();
  if (candidates.size() == 1) {
    use_program(first_options);
    check_local_size();
  }
  auto t0 = std::chrono::steady_clock::now();
  TriangleUpload triangles(context_, queue_, scene.triangles.size(),
                           CLRT_READS_TRIANGLE_LO(kernel_code(config_.precision)), unified_memory_, huge_pages_);
  // (in the hierarchy's order where the kernel walks one: clrt_layout.h)
  const bool walks = uses_bvh(config_.accel, bvh_primitive_count(scene), config_.precision);
  const std::vector<clrt_i32>* order = walks && bvh && !scene.triangles.empty() ? &bvh->triangle_order : nullptr;
  triangle_slots_ = upload(context_, queue_, order ? triangle_slots(*bvh) : std::vector<clrt_i32>{});
  SceneData data = pack_scene(scene, config_.precision, width, height, depth, sampling, triangles.output(), order);
  triangles.finish();
  triangles_ = triangles.triangles;
  triangles_lo_ = triangles.triangles_lo;
  params_ = upload(context_, queue_, std::vector<clrt_params>{data.params});
  spheres_ = upload(context_, queue_, data.spheres);
  lights_ = upload(context_, queue_, data.lights);
  if (walks && !bvh) throw std::logic_error("BVH build without its hierarchy");
  // (one-element stand-ins when the kernel does not walk a hierarchy; both
  // branches lvalues, so the hierarchy is uploaded without a copy)
  const std::vector<clrt_wide_node> no_nodes;
  const std::vector<clrt_i32> no_primitives;
  nodes_ = upload(context_, queue_, bvh ? bvh->wide : no_nodes, huge_pages_);
  primitives_ = upload(context_, queue_, bvh ? bvh->primitives : no_primitives, huge_pages_);
  leaf_spheres_ =
      upload(context_, queue_, bvh ? pack_leaf_spheres(bvh->primitives, data.spheres) : std::vector<clrt_leaf_sphere>{},
             huge_pages_);
  planes_ = upload(context_, queue_, data.planes);
  materials_ = upload(context_, queue_, data.materials);
  timings_.upload_ms = ms_since(t0);
  width_ = width;
  height_ = height;
  if (candidates.size() > 1) choose_lanes(data, bvh);
}

void DeviceRenderer::use_program(const std::string& opts) {
  if (opts == built_.options && !built_.kernels.empty()) return;
  BuildStats bs;
  BuiltProgram built;
  built.program = build_program(context_, device_, source_, opts, &bs, BuildFlags{config_.use_cache, config_.verbose});
  for (const std::string& name : render_kernel_names(config_.subsample == Subsample::Shade)) {
    cl::Kernel kernel(built.program, name.c_str());
    // The kernels' parameters and the host's RenderArg come from one list
    // (kernels/clrt_kernel_args.h); a kernel file from elsewhere
    // (--kernel-dir) may not follow it.
    const cl_uint arguments = kernel.getInfo<CL_KERNEL_NUM_ARGS>();
    if (arguments != render_arg_count(config_.output.layers))
      throw UserError("the kernel " + name + " takes " + std::to_string(arguments) + " arguments, this clrt passes " +
                      std::to_string(render_arg_count(config_.output.layers)) +
                      " (kernels/clrt_kernel_args.h; a --kernel-dir from another version?)");
    built.kernels.push_back(kernel);
  }
  // Default local size: (preferred multiple, 1), within every kernel's limit
  // (a tile's launches share it); (1, 1) for a block of lanes on a CPU. A
  // block work-item already fills the SIMD lanes with its 16 pixels (the
  // preferred multiple is for packing work-items into them), and a group of
  // 16 blocks, 256 pixels, left PoCL's threads waiting on each other at the
  // end of every launch: frames in 24-row bands took 1.3x one launch's time
  // on the million-triangle mesh, and the lanes probe, which times bands of
  // 8 rows, chose one ray per work-item there where blocks render the frame
  // 1.2x faster (docs/results/wide-hierarchy.md).
  const cl::Kernel& first = built.kernels.front();
  const size_t pm = config_.lanes > 1 && is_cpu_type(device_.type)
                        ? 1
                        : first.getWorkGroupInfo<CL_KERNEL_PREFERRED_WORK_GROUP_SIZE_MULTIPLE>(device_.device);
  built.max_work_group = std::numeric_limits<size_t>::max();
  for (const cl::Kernel& kernel : built.kernels)
    built.max_work_group =
        std::min(built.max_work_group, kernel.getWorkGroupInfo<CL_KERNEL_WORK_GROUP_SIZE>(device_.device));
  built.default_local_x = int(std::max<size_t>(1, std::min(pm, built.max_work_group)));
  built.options = opts;
  built.lanes = config_.lanes;
  built_ = built;
  timings_.build_ms += bs.ms;
  timings_.build_cached = timings_.build_cached && bs.cached;
}

std::string DeviceRenderer::scene_options() const {
  return build_options(config_, features_, device_.fp64);
}

void DeviceRenderer::choose_lanes(const SceneData& data, const Bvh* bvh) {
  KernelConfig requested = config_;
  requested.lanes = requested_lanes_;
  const std::vector<int> candidates = lane_candidates(requested, device_, bvh != nullptr);
  const std::string key = lane_choice_key(device_, scene_options(), data, bvh ? &bvh->wide : nullptr);
  const int remembered = recall_lanes(key);
  if (remembered != 0) {
    config_.lanes = remembered;
    use_program(scene_options());
    check_local_size();
    return;
  }
  const auto t0 = Clock::now();
  std::vector<BuiltProgram> programs;
  Image scratch(width_, height_, config_.output);
  // The probe's tiles store their layers too (programs with -DCLRT_OUT_LAYERS
  // write them): into scratch layers, not the frame's, which begin_frame()
  // has not named yet.
  FrameLayers scratch_layers;
  struct Restore {  // (also when the probe throws: no pointer to scratch_layers outlives it)
    FrameLayers*& slot;
    FrameLayers* value;
    ~Restore() { slot = value; }
  } restore{layers_out_, layers_out_};
  if (config_.output.layers) {
    scratch_layers = FrameLayers(width_, height_, config_.output.layers);
    layers_out_ = &scratch_layers;
  }
  for (int lanes : candidates) {
    config_.lanes = lanes;
    use_program(scene_options());
    check_local_size();
    programs.push_back(built_);
    render_tile(0, 0, std::min(width_, 16), std::min(height_, 4), scratch);  // untimed first launch
  }
  const double build_ms = timings_.build_ms;
  std::vector<double> best(programs.size(), std::numeric_limits<double>::infinity());
  for (int round = 0; round < kProbeRounds; ++round)
    for (size_t i = 0; i < programs.size(); ++i) {
      built_ = programs[i];
      config_.lanes = built_.lanes;
      best[i] = std::min(best[i], probe_ms(scratch));
    }
  const size_t fastest = size_t(std::min_element(best.begin(), best.end()) - best.begin());
  built_ = programs[fastest];
  config_.lanes = built_.lanes;
  remember_lanes(key, config_.lanes);
  timings_.probe_ms = ms_since(t0) - build_ms;
  if (config_.verbose) {
    std::string times;
    for (size_t i = 0; i < programs.size(); ++i)
      times += (i ? ", " : "") + std::to_string(programs[i].lanes) + " lanes " + std::to_string(best[i]) + " ms";
    log_message(LogLevel::Info, "lanes: " + std::to_string(config_.lanes) + " (probe: " + times + ")");
  }
}

double DeviceRenderer::probe_ms(Image& scratch) {
  double total = 0;
  for (const RowBand& band : probe_bands(height_)) total += render_tile(0, band.y0, width_, band.rows, scratch).ms;
  return total;
}

void DeviceRenderer::check_local_size() const {
  if (local_.x <= 0 && local_.y <= 0) return;
  const size_t lx = size_t(std::max(1, local_.x)), ly = size_t(std::max(1, local_.y));
  const auto item_sizes = device_.device.getInfo<CL_DEVICE_MAX_WORK_ITEM_SIZES>();
  const bool fits = lx <= built_.max_work_group && ly <= built_.max_work_group && lx * ly <= built_.max_work_group &&
                    (item_sizes.size() < 2 || (lx <= item_sizes[0] && ly <= item_sizes[1]));
  if (!fits)
    throw UserError("--local " + std::to_string(lx) + "x" + std::to_string(ly) + ": exceeds what " + device_.name +
                    " allows for this kernel (at most " + std::to_string(built_.max_work_group) +
                    " work-items per group" +
                    (item_sizes.size() >= 2 ? ", " + std::to_string(item_sizes[0]) + "x" + std::to_string(item_sizes[1])
                                            : std::string()) +
                    " per dimension)");
}

DeviceRenderer::~DeviceRenderer() {
  drain();
}

void DeviceRenderer::drain() noexcept {
  try {
    if (queue_()) queue_.finish();
    if (transfer_queue_()) transfer_queue_.finish();
  } catch (...) {  // a lost device: nothing left to wait for
  }
  pending_.clear();
}

void DeviceRenderer::ensure_slot(ResultSlot& slot, size_t pixels) {
  if (!slot.status()) slot.status = cl::Buffer(context_, CL_MEM_READ_WRITE, sizeof(cl_int));
  if (pixels <= slot.capacity) return;
  // Where the device works in host memory, the results are allocated there
  // and mapped after each tile (no copy); elsewhere they are read into the
  // slot's host vectors. Buffers the kernel does not write (classification,
  // counters) get one element.
  // (subsampling's second launch reads what its first stored: hit ids, and
  // colours when it interpolates)
  const bool subsample = config_.subsample != Subsample::Off;
  const cl_mem_flags flags =
      (subsample ? CL_MEM_READ_WRITE : CL_MEM_WRITE_ONLY) | (map_results_ ? CL_MEM_ALLOC_HOST_PTR : 0);
  slot.colors = cl::Buffer(context_, flags, pixels * colour_bytes_per_pixel());
  slot.classes = cl::Buffer(context_, flags, (config_.output.classes || subsample ? pixels : 1) * 2 * sizeof(cl_int));
  slot.layers = cl::Buffer(context_, flags, (config_.output.layers ? pixels * kLayerFloats : 1) * sizeof(float));
  slot.counters = cl::Buffer(context_, subsample ? CL_MEM_READ_WRITE : CL_MEM_WRITE_ONLY,
                             (config_.count_rays ? pixels : 1) * sizeof(clrt_ray_counts));
  slot.capacity = pixels;
}

size_t DeviceRenderer::colour_bytes_per_pixel() const {
  return config_.output.pixels == PixelFormat::Rgba8 ? 4 : 3 * sizeof(float);
}

LaunchTime DeviceRenderer::render_tile(int x0, int y0, int w, int h, Image& dst) {
  submit_tile(x0, y0, w, h, dst);
  return finish_tile(dst);
}

void DeviceRenderer::submit_tile(int x0, int y0, int w, int h, Image& dst) {
  if (int(pending_.size()) >= tiles_in_flight()) throw std::logic_error("submit_tile: too many tiles in flight");
  try {
    enqueue_tile(x0, y0, w, h, dst);
  } catch (...) {
    drain();  // a read enqueued before the error must not land after it
    throw;
  }
}

void DeviceRenderer::set_tile_args(cl::Kernel& kernel, const ResultSlot& slot, int x0, int y0, int w, int h) {
  set_arg<RenderArg::params>(kernel, params_);
  set_arg<RenderArg::spheres>(kernel, spheres_);
  set_arg<RenderArg::lights>(kernel, lights_);
  set_arg<RenderArg::colors>(kernel, slot.colors);
  set_arg<RenderArg::classes>(kernel, slot.classes);
  set_arg<RenderArg::counters>(kernel, slot.counters);
  set_arg<RenderArg::x0>(kernel, cl_int(x0));
  set_arg<RenderArg::y0>(kernel, cl_int(y0));
  set_arg<RenderArg::tile_w>(kernel, cl_int(w));
  set_arg<RenderArg::tile_h>(kernel, cl_int(h));
  set_arg<RenderArg::nodes>(kernel, nodes_);
  set_arg<RenderArg::primitives>(kernel, primitives_);
  set_arg<RenderArg::leaf_spheres>(kernel, leaf_spheres_);
  set_arg<RenderArg::planes>(kernel, planes_);
  set_arg<RenderArg::triangles>(kernel, triangles_);
  set_arg<RenderArg::triangles_lo>(kernel, triangles_lo_);
  set_arg<RenderArg::triangle_slots>(kernel, triangle_slots_);
  set_arg<RenderArg::materials>(kernel, materials_);
  set_arg<RenderArg::status>(kernel, slot.status);
  if (config_.output.layers) set_arg<RenderArg::layers>(kernel, slot.layers);  // (an argument of layer builds only)
}

void DeviceRenderer::enqueue_tile(int x0, int y0, int w, int h, Image& dst) {
  if (!dst.holds(width_, height_, config_.output)) throw std::logic_error("submit_tile: image of another frame");
  const size_t n = size_t(w) * h;
  PendingTile tile;
  tile.x0 = x0, tile.y0 = y0, tile.w = w, tile.h = h;
  tile.slot = next_slot_;
  next_slot_ = (next_slot_ + 1) % 2;
  ResultSlot& slot = slots_[tile.slot];  // free: its last tile was finished
  ensure_slot(slot, n);
  for (cl::Kernel& kernel : built_.kernels) set_tile_args(kernel, slot, x0, y0, w, h);
  if (config_.loop_limit_probe) queue_.enqueueFillBuffer(slot.status, cl_int(0), 0, sizeof(cl_int));
  // Each work-item shades a block of kernel_lanes(config_) pixels,
  // packet_rows(config_) of them high.
  const size_t rows = size_t(packet_rows(config_)), cols = size_t(kernel_lanes(config_)) / rows;
  // Always an explicit local size: with NullRange the implementation picks
  // one from the global size, which changes with every band height, and
  // PoCL compiles a new work-group function for each (measured: 1.2 s per
  // 640x480 frame of 5 ms bands instead of 20 ms; docs/results/archive.md).
  // (check_local_size() bounded both by the device's limits.)
  const size_t lx = size_t(local_.x > 0 ? local_.x : built_.default_local_x), ly = size_t(local_.y > 0 ? local_.y : 1);
  const cl::NDRange local(lx, ly);
  // The global size for `columns` columns of the tile, padded to a multiple
  // of the local size, in size_t (no overflow for any tile and local size
  // the checks let through); the kernel ignores work-items outside the
  // tile. Every pixel must be covered.
  auto global_for = [&](size_t columns) {
    const size_t gw = (columns + cols - 1) / cols, gh = (size_t(h) + rows - 1) / rows;
    const size_t global_x = (gw + lx - 1) / lx * lx, global_y = (gh + ly - 1) / ly * ly;
    if (global_x < gw || global_y < gh) throw std::logic_error("launch does not cover the tile");
    return cl::NDRange(global_x, global_y);
  };
  // The launches: render over every column, or subsampling's two
  // (kernels/clrt_subsample.h), each over one parity of the image's columns
  // (a tile column c is image column x0 + c) but shade's second, which
  // shades them all. The second runs after the first (an in-order queue);
  // the tile is timed from the first's start to the last's end.
  struct Launch {
    cl::Kernel* kernel;
    int first_column, column_step;
  };
  const int even = x0 & 1, odd = (x0 + 1) & 1;        // the first tile columns of even and odd image columns
  std::vector<cl::Kernel>& kernels = built_.kernels;  // render_kernel_names()
  const std::vector<Launch> launches = [&]() -> std::vector<Launch> {
    switch (config_.subsample) {
      case Subsample::Shade:
        return {{&kernels[0], even, 2}, {&kernels[1], 0, 1}};
      case Subsample::Interpolate:
        return {{&kernels[0], even, 2}, {&kernels[0], odd, 2}};
      case Subsample::Off:
        break;
    }
    return {{&kernels[0], 0, 1}};
  }();
  for (size_t k = 0; k < launches.size(); ++k) {
    const Launch& launch = launches[k];
    set_arg<RenderArg::first_column>(*launch.kernel, cl_int(launch.first_column));
    set_arg<RenderArg::column_step>(*launch.kernel, cl_int(launch.column_step));
    // Every other column: at most (w + 1) / 2, one global size for both
    // parities (the kernel leaves out the work-items past the tile).
    const size_t columns = (size_t(w) + size_t(launch.column_step) - 1) / size_t(launch.column_step);
    tile.launch = k == 0 ? start_timed(queue_, *launch.kernel, global_for(columns), local)
                         : start_timed_after(tile.launch, queue_, *launch.kernel, global_for(columns), local);
  }

  if (!map_results_) enqueue_reads(tile, slot, dst);
  queue_.flush();
  pending_.push_back(std::move(tile));
}

// The tile's reads, on the second queue after the kernel: the next tile's
// kernel (on queue_, into the other slot) runs while they travel.
void DeviceRenderer::enqueue_reads(PendingTile& tile, ResultSlot& slot, Image& dst) {
  const size_t n = size_t(tile.w) * tile.h;
  const int x0 = tile.x0, y0 = tile.y0, w = tile.w;
  const std::vector<cl::Event> after{tile.launch.event};
  const bool rgba8 = config_.output.pixels == PixelFormat::Rgba8;
  const size_t colour_bytes = n * colour_bytes_per_pixel();
  void* colour_target;
  if (rgba8 && x0 == 0 && w == dst.width) {
    // 8-bit rows are already the image's bytes: read them in place.
    tile.colour_in_place = true;
    colour_target = &dst.rgba8[size_t(y0) * dst.width * 4];
  } else if (rgba8) {
    if (slot.rgba8.size() < n * 4) slot.rgba8.resize(n * 4);
    colour_target = slot.rgba8.data();
  } else {
    if (slot.rgb.size() < n * 3) slot.rgb.resize(n * 3);
    colour_target = slot.rgb.data();
  }
  cl::Event ev;
  transfer_queue_.enqueueReadBuffer(slot.colors, CL_FALSE, 0, colour_bytes, colour_target, &after, &ev);
  tile.reads.push_back(ev);
  if (config_.output.classes) {
    if (slot.aux.size() < n * 2) slot.aux.resize(n * 2);
    transfer_queue_.enqueueReadBuffer(slot.classes, CL_FALSE, 0, n * 2 * sizeof(cl_int), slot.aux.data(), &after, &ev);
    tile.reads.push_back(ev);
  }
  if (config_.output.layers) {
    if (slot.layer_values.size() < n * kLayerFloats) slot.layer_values.resize(n * kLayerFloats);
    transfer_queue_.enqueueReadBuffer(slot.layers, CL_FALSE, 0, n * kLayerFloats * sizeof(float),
                                      slot.layer_values.data(), &after, &ev);
    tile.reads.push_back(ev);
  }
  if (config_.count_rays) {
    if (slot.counts.size() < n) slot.counts.resize(n);
    transfer_queue_.enqueueReadBuffer(slot.counters, CL_FALSE, 0, n * sizeof(clrt_ray_counts), slot.counts.data(),
                                      &after, &ev);
    tile.reads.push_back(ev);
  }
  if (config_.loop_limit_probe) {
    transfer_queue_.enqueueReadBuffer(slot.status, CL_FALSE, 0, sizeof(cl_int), &slot.status_word, &after, &ev);
    tile.reads.push_back(ev);
  }
  transfer_queue_.flush();
}

LaunchTime DeviceRenderer::finish_tile(Image& dst) {
  if (pending_.empty()) throw std::logic_error("finish_tile: no tile in flight");
  try {
    const PendingTile& tile = pending_.front();
    const LaunchTime time = finish_timed(tile.launch);
    events_plausible_ = events_plausible_ && time.from_events;
    const auto t0 = Clock::now();
    if (!tile.reads.empty()) cl::Event::waitForEvents(tile.reads);
    store_tile(tile, dst);
    timings_.download_ms += ms_since(t0);
    pending_.erase(pending_.begin());
    return time;
  } catch (...) {
    drain();  // no read may land in memory after the error has unwound
    throw;
  }
}

void DeviceRenderer::store_tile(const PendingTile& tile, Image& dst) {
  const int x0 = tile.x0, y0 = tile.y0, w = tile.w, h = tile.h;
  const size_t n = size_t(w) * h;
  ResultSlot& slot = slots_[tile.slot];
  const bool rgba8 = config_.output.pixels == PixelFormat::Rgba8, classes = config_.output.classes;
  const void* colour = nullptr;
  const cl_int* aux = nullptr;
  const clrt_ray_counts* counts = nullptr;
  void* mapped_colour = nullptr;
  void* mapped_aux = nullptr;
  const float* layers = nullptr;
  void* mapped_layers = nullptr;
  if (map_results_) {
    mapped_colour = queue_.enqueueMapBuffer(slot.colors, CL_TRUE, CL_MAP_READ, 0, n * colour_bytes_per_pixel());
    colour = mapped_colour;
    if (classes) {
      mapped_aux = queue_.enqueueMapBuffer(slot.classes, CL_TRUE, CL_MAP_READ, 0, n * 2 * sizeof(cl_int));
      aux = static_cast<const cl_int*>(mapped_aux);
    }
    if (config_.output.layers) {
      mapped_layers = queue_.enqueueMapBuffer(slot.layers, CL_TRUE, CL_MAP_READ, 0, n * kLayerFloats * sizeof(float));
      layers = static_cast<const float*>(mapped_layers);
    }
    if (config_.count_rays) {
      if (slot.counts.size() < n) slot.counts.resize(n);
      queue_.enqueueReadBuffer(slot.counters, CL_TRUE, 0, n * sizeof(clrt_ray_counts), slot.counts.data());
      counts = slot.counts.data();
    }
    if (config_.loop_limit_probe) queue_.enqueueReadBuffer(slot.status, CL_TRUE, 0, sizeof(cl_int), &slot.status_word);
  } else {
    if (!tile.colour_in_place) colour = rgba8 ? static_cast<const void*>(slot.rgba8.data()) : slot.rgb.data();
    if (classes) aux = slot.aux.data();
    if (config_.count_rays) counts = slot.counts.data();
    if (config_.output.layers) layers = slot.layer_values.data();
  }
  if (config_.loop_limit_probe && (slot.status_word & CLRT_STATUS_LOOP_LIMIT)) {
    if (map_results_) {
      if (mapped_colour) queue_.enqueueUnmapMemObject(slot.colors, mapped_colour);
      if (mapped_layers) queue_.enqueueUnmapMemObject(slot.layers, mapped_layers);
      if (mapped_aux) queue_.enqueueUnmapMemObject(slot.classes, mapped_aux);
    }
    throw DeviceError(loop_limit_message());
  }
  if (counts)
    for (size_t i = 0; i < n; ++i)  // the kernel counts in 32-bit words; they wrap past 2^31 as unsigned
      counts_ += RayCounts{uint32_t(counts[i].primary), uint32_t(counts[i].shadow), uint32_t(counts[i].reflection),
                           uint32_t(counts[i].sphere_tests), uint32_t(counts[i].refraction)};
  if (colour && rgba8) {
    const auto* bytes = static_cast<const uint8_t*>(colour);
    if (x0 == 0 && w == dst.width)  // a band of whole rows: one contiguous run of the image
      std::memcpy(&dst.rgba8[size_t(y0) * dst.width * 4], bytes, n * 4);
    else
      for (int ty = 0; ty < h; ++ty)
        std::memcpy(&dst.rgba8[(size_t(y0 + ty) * dst.width + x0) * 4], bytes + size_t(ty) * w * 4, size_t(w) * 4);
  } else if (colour && config_.output.pixels == PixelFormat::Unit) {
    const auto* rgb = static_cast<const float*>(colour);
    for (int ty = 0; ty < h; ++ty) {
      float* d = &dst.unit[(size_t(y0 + ty) * dst.width + x0) * 3];
      const float* s = rgb + size_t(ty) * w * 3;
      for (size_t i = 0; i < size_t(w) * 3; ++i) d[i] = to_unit(s[i]);
    }
  } else if (colour) {
    const auto* rgb = static_cast<const float*>(colour);
    for (int ty = 0; ty < h; ++ty) {
      double* d = &dst.rgb[(size_t(y0 + ty) * dst.width + x0) * 3];
      const float* s = rgb + size_t(ty) * w * 3;
      for (size_t i = 0; i < size_t(w) * 3; ++i) d[i] = s[i];
    }
  }
  if (aux) {
    for (int ty = 0; ty < h; ++ty) {
      const size_t d = size_t(y0 + ty) * dst.width + x0;
      const cl_int* s = aux + size_t(ty) * w * 2;
      for (int tx = 0; tx < w; ++tx) {
        dst.hit[d + tx] = s[tx * 2];
        dst.shadowed[d + tx] = s[tx * 2 + 1];
      }
    }
  }
  if (layers) store_layers(layers, tile);
  if (map_results_) {
    queue_.enqueueUnmapMemObject(slot.colors, mapped_colour);
    if (mapped_layers) queue_.enqueueUnmapMemObject(slot.layers, mapped_layers);
    if (mapped_aux) queue_.enqueueUnmapMemObject(slot.classes, mapped_aux);
    queue_.finish();  // (the next tile's kernel writes them again)
  }
}

std::string DeviceRenderer::loop_limit_message() const {
  return device_.name +
         ": the driver ended the kernel's loops early (llvmpipe stops a work-item after 65 535 loop iterations in "
         "all), so some pixels of this frame would be wrong; render it on another device (clrt devices), or with "
         "less work per pixel (a lower --depth, the ray cut on, fewer primitives per ray)";
}

void DeviceRenderer::store_layers(const float* values, const PendingTile& tile) const {
  const unsigned asked = config_.output.layers;
  if (!layers_out_ || !layers_out_->holds(width_, height_, asked))
    throw std::logic_error("store_layers: no layers of this frame (begin_frame)");
  FrameLayers& dst = *layers_out_;
  constexpr float kMissDistance = std::numeric_limits<float>::infinity();
  for (int ty = 0; ty < tile.h; ++ty)
    for (int tx = 0; tx < tile.w; ++tx) {
      const float* v = values + (size_t(ty) * tile.w + tx) * kLayerFloats;
      const size_t p = size_t(tile.y0 + ty) * dst.width + tile.x0 + tx;
      int32_t id;
      std::memcpy(&id, &v[CLRT_LAYER_ID], sizeof id);  // (the kernel stores the id's bits)
      const bool hit = id >= 0;
      if (asked & kLayerDepth) dst.depth[p] = hit ? v[CLRT_LAYER_DISTANCE] : kMissDistance;
      for (int c = 0; c < 3; ++c) {
        if (asked & kLayerNormal) dst.normal[p * 3 + c] = hit ? v[CLRT_LAYER_NORMAL + c] : 0.0f;
        if (asked & kLayerAlbedo) dst.albedo[p * 3 + c] = hit ? v[CLRT_LAYER_ALBEDO + c] : 0.0f;
      }
      if (asked & kLayerId) dst.id[p] = hit ? id : -1;
    }
}

void DeviceRenderer::begin_frame(FrameLayers* layers) {
  if (!pending_.empty()) drain();  // tiles of an abandoned frame
  layers_out_ = layers;
  counts_ = {};
  timings_.download_ms = 0;
}

}  // namespace clrt
