// renderer.hpp - the one way to render a frame with OpenCL, on one device or
// several at once: one DeviceRenderer (context, queue, specialized program,
// scene buffers) per device, bands handed out dynamically by the band
// scheduler so faster devices take more of the frame.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "cl/device.hpp"
#include "image/image.hpp"
#include "render/band_scheduler.hpp"
#include "render/build_options.hpp"
#include "render/device_renderer.hpp"
#include "scene/sampling.hpp"
#include "scene/scene.hpp"

namespace clrt {

// How to render: the kernel build, the bands, the work-group size. Filled by
// the command line (app/) or by the evaluations (eval/).
struct RenderSettings {
  KernelConfig kernel;
  TilePolicy tiles;
  LocalSize local;
  // Map the results where the device works in host memory instead of reading
  // them into a copy (false: always read; tests compare both paths).
  bool map_results = true;
  // Where results are read (not mapped), read one band's while the next
  // band's kernel runs (false: one band at a time; bench compares both).
  bool overlap_downloads = true;
  // render(): called with 0 rows done of the frame's height ("rows"), then
  // as bands finish, from the devices' threads; empty: none.
  ProgressFn progress{};
  // render(): asked before each band is taken, from the devices' threads;
  // once true, no more bands are taken, those in flight finish, and render()
  // throws Cancelled (util/error.hpp). Set, bands are sized as for progress
  // (about 250 ms each), so that a stop comes soon. Empty: never (the CLI).
  CancelFn cancel{};
};

// The last prepare() and render(), over every device.
struct FrameStats {
  double build_ms = 0;        // longest program build or cache load (they run in parallel)
  bool build_cached = false;  // every device loaded its program from the cache
  double upload_ms = 0;       // longest scene upload
  bool bvh = false;           // the kernel walks a hierarchy (render/bvh.hpp)
  double bvh_build_ms = 0;    // its build on the host (once for every device)
  size_t bvh_bytes = 0;       // its size on each device
  int bvh_depth = 0;          // its deepest leaf
  double kernel_ms = 0;       // kernel time summed over launches and devices (launch_timing.hpp)
  double download_ms = 0;     // tiles back into host memory, summed over devices
  double wall_ms = 0;         // render(): every launch and download
  int launches = 0;
  int host_timed_launches = 0;      // of those, timed by the host clock (launch_timing.hpp)
  RayCounts rays;                   // with KernelConfig::count_rays
  std::vector<DeviceShare> shares;  // one per device, in order
};

class Renderer {
 public:
  // UserError when the settings do not suit a device (lanes, fp64, local size).
  Renderer(const std::vector<DeviceInfo>& devices, const RenderSettings& settings);

  // Builds every device's program (in parallel) and uploads the scene. spp:
  // N x N samples per pixel (supersampling, kernels/clrt_samples.h), a run-time
  // value like the depth: another spp rebuilds nothing.
  void prepare(const Scene& scene, int width, int height, int depth, Sampling sampling = {});
  // Renders the prepared scene: the whole frame, shared by every device.
  // Cancelled when settings.cancel asked for a stop (the image is then
  // incomplete).
  Image render();
  // The same into `out`, whose memory is reused when it has the frame's size
  // (frame after frame: no new pages for the image).
  void render_into(Image& out);
  // Rows [y_begin, y_end) of the frame only, into `out` (a full-size image
  // of the frame's contents, allocated when it is not one; other rows are
  // left as they are): a tile of a frame shared by several processes
  // (dist/frame_farm.hpp). The stats describe these rows.
  void render_rows(Image& out, int y_begin, int y_end);
  // The frame's size, as prepared.
  int width() const;
  int height() const;

  // The AOV layers of the last render() (settings.kernel.output.layers; an
  // empty FrameLayers without them): rows render_rows() rendered.
  const FrameLayers& layers() const { return layers_; }
  const FrameStats& stats() const { return stats_; }
  // "name" or "name + name + ...".
  std::string device_names() const;
  // The build options of the first device's program (logged, reported).
  const std::string& options() const;
  size_t device_count() const { return devices_.size(); }

 private:
  std::vector<std::unique_ptr<DeviceRenderer>> devices_;
  RenderSettings settings_;
  FrameStats stats_;
  FrameLayers layers_;
};

}  // namespace clrt
