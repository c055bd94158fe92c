// device_renderer.hpp - the OpenCL kernel on one device: its context, queue,
// scene-specialized program and scene buffers, and the launch of one tile.
// It renders tiles only; whole frames, on one device or several, are
// renderer.hpp's (the band scheduler hands tiles to each DeviceRenderer).
#pragma once
#include <cstdint>
#include <string>

#include "cl/cl.hpp"
#include "cl/device.hpp"
#include "cl/launch_timing.hpp"
#include "image/image.hpp"
#include "render/build_options.hpp"
#include "render/bvh.hpp"
#include "scene/scene.hpp"

namespace clrt {

// Rays traced, by kind, as counted by the kernel (KernelConfig::count_rays).
struct RayCounts {
  uint64_t primary = 0, shadow = 0, reflection = 0, sphere_tests = 0;
  uint64_t total() const { return primary + shadow + reflection; }
  RayCounts& operator+=(const RayCounts& o) {
    primary += o.primary, shadow += o.shadow, reflection += o.reflection, sphere_tests += o.sphere_tests;
    return *this;
  }
};

// Work-items per work-group in x and y; 0 = the default ((the kernel's
// preferred work-group size multiple, 1)).
struct LocalSize {
  int x = 0, y = 0;
};

// Times of one device's prepare() and tiles since begin_frame().
struct DeviceTimings {
  double build_ms = 0;  // program build (or cache load)
  bool build_cached = false;
  double upload_ms = 0;    // scene buffers to the device
  double download_ms = 0;  // tiles back into the host image
};

class DeviceRenderer {
 public:
  // map_results: map the result buffers where the device has host unified
  // memory (else they are read into staging vectors).
  DeviceRenderer(const DeviceInfo& device, KernelConfig config, LocalSize local = {}, bool map_results = true);

  // Builds the (scene-specialized) program and uploads the scene, and its
  // hierarchy when the configuration uses one (`bvh`: build_bvh(scene), made
  // once for every device by the Renderer). Must be called before
  // render_tile(); calling again with another scene or depth rebuilds, with
  // the same one reuses the program.
  void prepare(const Scene& scene, int width, int height, int depth, const Bvh* bvh);

  // Resets the ray counts and download time of a frame.
  void begin_frame();
  // Renders the tile [x0, x0+w) x [y0, y0+h) into `dst` (a full-size image).
  // Returns the launch's kernel time (profiling event, or the host wall time
  // where the event is implausible: launch_timing.hpp).
  LaunchTime render_tile(int x0, int y0, int w, int h, Image& dst);

  const DeviceTimings& timings() const { return timings_; }
  const RayCounts& ray_counts() const { return counts_; }
  const std::string& options() const { return options_; }
  const DeviceInfo& device() const { return device_; }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  void ensure_tile_buffers(size_t pixels);
  // UserError when the local size does not fit the device and kernel.
  void check_local_size() const;

  DeviceInfo device_;
  KernelConfig config_;  // lanes resolved: the device's default, or per scene (prepare())
  int requested_lanes_;  // config.lanes as given (0: chosen per scene, scene_lanes())
  LocalSize local_;
  cl::Context context_;
  cl::CommandQueue queue_;
  cl::Program program_;
  cl::Kernel kernel_;
  std::string options_, source_;
  cl::Buffer params_, spheres_, lights_, colors_, classes_, ray_counters_, nodes_, primitives_;
  size_t tile_capacity_ = 0;
  bool map_results_ = false;        // asked for and CL_DEVICE_HOST_UNIFIED_MEMORY: mapped, not read
  std::vector<float> staging_rgb_;  // otherwise read here (kept from tile to tile)
  std::vector<cl_int> staging_aux_;
  int width_ = 0, height_ = 0;
  int default_local_x_ = 1;    // set when the kernel is built
  size_t max_work_group_ = 1;  // CL_KERNEL_WORK_GROUP_SIZE of the built kernel
  DeviceTimings timings_;
  RayCounts counts_;
};

}  // namespace clrt
