// cl_renderer.hpp - renders a scene with the OpenCL kernel on one device.
#pragma once
#include <cstdint>
#include <string>

#include "render/build_options.hpp"
#include "cl/cl.hpp"
#include "cl/device.hpp"
#include "image/image.hpp"
#include "cl/launch_timing.hpp"
#include "cl/program.hpp"
#include "scene/scene.hpp"
#include "render/scene_buffers.hpp"
#include "render/tile_scheduler.hpp"

namespace clrt {

struct RayCounts {
  uint64_t primary = 0, shadow = 0, reflection = 0, sphere_tests = 0;
  uint64_t total() const { return primary + shadow + reflection; }
};

struct RenderTimings {
  double build_ms = 0;     // program build (or cache load)
  bool build_cached = false;
  double upload_ms = 0;    // scene buffers to the device
  double kernel_ms = 0;    // sum of kernel times (profiling events, checked against the host clock)
  double download_ms = 0;  // image back to the host
  double total_ms = 0;     // wall time of render(), excluding build/upload
  int launches = 0;        // kernel launches (tiles)
  int host_timed_launches = 0;  // launches whose events were implausible (timed by the host, launch_timing.hpp)
};

class ClRenderer {
 public:
  ClRenderer(const DeviceInfo& device, KernelConfig config);

  // Builds the (scene-specialized) program and uploads the scene. Must be
  // called before render(); calling again with another scene/depth rebuilds.
  void prepare(const Scene& scene, int width, int height, int depth);

  // Renders the whole frame in bands (see tile_scheduler.hpp).
  Image render();
  // Resets ray counts and per-frame timings (render() does this itself;
  // callers driving render_tile() directly, like MultiRenderer, call it).
  void begin_frame();
  // Records a frame's totals from the scheduler (kernel ms, launches, wall).
  void end_frame(const DeviceShare& share, double wall_ms);
  // Renders one tile [x0, x0+w) x [y0, y0+h) into `dst` (a full-size image).
  // Returns the launch's kernel time (profiling event, or the host wall time
  // where the event is implausible: launch_timing.hpp).
  LaunchTime render_tile(int x0, int y0, int w, int h, Image& dst);

  const RenderTimings& timings() const { return timings_; }
  const RayCounts& ray_counts() const { return counts_; }
  const std::string& options() const { return options_; }
  const DeviceInfo& device() const { return dev_; }
  int width() const { return width_; }
  int height() const { return height_; }
  void set_tile_policy(const TilePolicy& p) { policy_ = p; }
  const TilePolicy& tile_policy() const { return policy_; }
  const DeviceShare& last_share() const { return share_; }
  // Local work size (0,0 = (preferred work-group size multiple, 1)).
  void set_local_size(int lx, int ly) { local_x_ = lx, local_y_ = ly; }

 private:
  void ensure_tile_buffers(size_t pixels);
  // UserError when the --local size does not fit the device and kernel.
  void check_local_size() const;

  DeviceInfo dev_;
  KernelConfig cfg_;
  cl::Context ctx_;
  cl::CommandQueue queue_;
  cl::Program program_;
  cl::Kernel kernel_;
  std::string options_, source_;
  cl::Buffer params_, spheres_, lights_, out_, aux_, counts_buf_;
  size_t tile_capacity_ = 0;
  int width_ = 0, height_ = 0;
  TilePolicy policy_;
  DeviceShare share_;
  int local_x_ = 0, local_y_ = 0;
  int default_local_x_ = 1;  // set when the kernel is built
  size_t max_work_group_ = 1;  // CL_KERNEL_WORK_GROUP_SIZE of the built kernel
  RenderTimings timings_;
  RayCounts counts_;
};

// Convenience: one device chosen by spec, whole frame.
Image render_opencl(const Scene& scene, int width, int height, int depth, const std::string& device_spec,
                    const KernelConfig& cfg, RenderTimings* timings = nullptr);

}  // namespace clrt
