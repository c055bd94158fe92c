// multi_renderer.hpp - one frame across several OpenCL devices at once: one
// ClRenderer (context, queue, specialized program, scene buffers) per device,
// bands handed out dynamically by tile_scheduler.
#pragma once
#include <memory>
#include <vector>

#include "render/cl_renderer.hpp"
#include "render/tile_scheduler.hpp"

namespace clrt {

class MultiRenderer {
 public:
  MultiRenderer(const std::vector<DeviceInfo>& devices, const KernelConfig& cfg);

  // Builds every device's program (in parallel) and uploads the scene.
  void prepare(const Scene& scene, int width, int height, int depth);
  Image render();

  void set_tile_policy(const TilePolicy& p) { policy_ = p; }
  void set_local_size(int lx, int ly);

  const std::vector<DeviceShare>& shares() const { return shares_; }
  size_t size() const { return renderers_.size(); }
  ClRenderer& renderer(size_t i) { return *renderers_[i]; }
  RayCounts ray_counts() const;
  double kernel_ms() const;         // summed over devices
  int launches() const;             // summed over devices
  int host_timed_launches() const;  // of those, timed by the host clock (launch_timing.hpp)
  double build_ms() const;          // longest build (they run in parallel)
  double upload_ms() const;
  double wall_ms() const { return wall_ms_; }

 private:
  std::vector<std::unique_ptr<ClRenderer>> renderers_;
  TilePolicy policy_;
  std::vector<DeviceShare> shares_;
  double wall_ms_ = 0;
};

}  // namespace clrt
