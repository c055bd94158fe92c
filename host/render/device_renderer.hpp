// device_renderer.hpp - the OpenCL kernel on one device: its context, queue,
// scene-specialized program and scene buffers, and the launch of one tile.
// It renders tiles only; whole frames, on one device or several, are
// renderer.hpp's (the band scheduler hands tiles to each DeviceRenderer).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "cl/cl.hpp"
#include "cl/device.hpp"
#include "cl/launch_timing.hpp"
#include "clrt_layout.h"
#include "image/image.hpp"
#include "image/layers.hpp"
#include "render/build_options.hpp"
#include "render/bvh.hpp"
#include "render/scene_buffers.hpp"
#include "scene/sampling.hpp"
#include "scene/scene.hpp"

namespace clrt {

// Rays traced, by kind, as counted by the kernel (KernelConfig::count_rays).
struct RayCounts {
  uint64_t primary = 0, shadow = 0, reflection = 0, sphere_tests = 0, refraction = 0;
  uint64_t total() const { return primary + shadow + reflection + refraction; }
  RayCounts& operator+=(const RayCounts& o) {
    primary += o.primary, shadow += o.shadow, reflection += o.reflection, sphere_tests += o.sphere_tests;
    refraction += o.refraction;
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
  double probe_ms = 0;     // the lanes probe (choose_lanes()), 0 when none ran
  double download_ms = 0;  // tiles back into the host image
};

class DeviceRenderer {
 public:
  // map_results: map the result buffers where the device has host unified
  // memory (else they are read into staging vectors); overlap: where they
  // are read, let two tiles be in flight (tiles_in_flight()).
  DeviceRenderer(const DeviceInfo& device, KernelConfig config, LocalSize local = {}, bool map_results = true,
                 bool overlap = true);
  // Waits for tiles still in flight (their reads write into this object).
  ~DeviceRenderer();
  DeviceRenderer(const DeviceRenderer&) = delete;
  DeviceRenderer& operator=(const DeviceRenderer&) = delete;

  // Builds the (scene-specialized) program and uploads the scene, and its
  // hierarchy when the configuration uses one (`bvh`: build_bvh(scene), made
  // once for every device by the Renderer). Must be called before
  // render_tile(); calling again with another scene or depth rebuilds where
  // the build options differ, else reuses the program; another spp (N x N
  // samples per pixel, read at run time) never rebuilds.
  void prepare(const Scene& scene, int width, int height, int depth, Sampling sampling, const Bvh* bvh);

  // Resets the ray counts and download time of a frame; `layers`: where its
  // tiles store their AOV layers (a FrameLayers of the frame's size and the
  // config's output.layers; null when it has none), until the next call.
  void begin_frame(FrameLayers* layers = nullptr);
  // Renders the tile [x0, x0+w) x [y0, y0+h) into `dst` (a full-size image
  // of the configured contents). Returns the launch's kernel time (profiling
  // event, or the host wall time where the event is implausible:
  // launch_timing.hpp). The same as submit_tile() then finish_tile().
  LaunchTime render_tile(int x0, int y0, int w, int h, Image& dst);

  // The same in two steps, so that one tile's results travel and are
  // converted while the next tile's kernel runs: submit_tile() enqueues the
  // kernel and, where results are read, their read (on a second queue),
  // without waiting; finish_tile() waits for the oldest submitted tile and
  // stores it into `dst`. At most tiles_in_flight() tiles may be submitted
  // and not finished; `dst` must stay the same image until they are.
  void submit_tile(int x0, int y0, int w, int h, Image& dst);
  LaunchTime finish_tile(Image& dst);
  // 2 where results are read over a bus (discrete devices), unless overlap
  // was turned off; 1 where they are
  // mapped (the device works in host memory: there is no transfer to hide,
  // and the host's copy would take cores from the kernel) and once a launch's
  // profiling events proved implausible (the host clock that then times
  // launches would count the overlap).
  int tiles_in_flight() const { return map_results_ || !overlap_ || !events_plausible_ ? 1 : 2; }

  // The mean kernel time per row of this device's share of the last frame
  // since prepare() (0: none yet), set by the band scheduler, which sizes a
  // later frame's first band from it (band_scheduler.hpp).
  double ms_per_row() const { return ms_per_row_; }
  void set_ms_per_row(double ms) { ms_per_row_ = ms; }

  const DeviceTimings& timings() const { return timings_; }
  const RayCounts& ray_counts() const { return counts_; }
  const std::string& options() const { return built_.options; }
  const DeviceInfo& device() const { return device_; }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  // The result buffers of one tile in flight, and the host memory its
  // results are read into (kept from tile to tile: no new pages per tile).
  struct ResultSlot {
    cl::Buffer colors, classes, counters, layers;
    cl::Buffer status;       // the device status word (CLRT_STATUS_*, kernels/clrt_layout.h)
    cl_int status_word = 0;  // read back with the tile's results
    size_t capacity = 0;     // pixels
    std::vector<float> rgb;
    std::vector<float> layer_values;  // kLayerFloats per pixel (kernels/clrt_layers.h)
    std::vector<uint8_t> rgba8;
    std::vector<cl_int> aux;
    std::vector<clrt_ray_counts> counts;
  };
  // A submitted tile.
  struct PendingTile {
    int x0 = 0, y0 = 0, w = 0, h = 0, slot = 0;
    TimedLaunch launch;
    std::vector<cl::Event> reads;  // read path: the reads of its results
    bool colour_in_place = false;  // read path: 8-bit rows read straight into the image
  };

  void ensure_slot(ResultSlot& slot, size_t pixels);
  // The error for a tile whose work-items found their loops ended early.
  std::string loop_limit_message() const;
  // submit_tile() without the cleanup after an error.
  void enqueue_tile(int x0, int y0, int w, int h, Image& dst);
  // Sets every argument of one of the tile's kernels: the scene's buffers,
  // the slot's and the tile's place (x0, y0, w x h).
  void set_tile_args(cl::Kernel& kernel, const ResultSlot& slot, int x0, int y0, int w, int h);
  void enqueue_reads(PendingTile& tile, ResultSlot& slot, Image& dst);
  // Bytes of colour the kernel writes per pixel (config_.output).
  size_t colour_bytes_per_pixel() const;
  // Stores a finished tile's results (mapped or read into its slot) into `dst`.
  void store_tile(const PendingTile& tile, Image& dst);
  // Stores a tile's AOV layers (kLayerFloats per pixel) into layers_out_.
  void store_layers(const float* values, const PendingTile& tile) const;
  // Floats per pixel of the kernel's layers buffer (kernels/clrt_layout.h).
  static constexpr size_t kLayerFloats = CLRT_LAYER_FLOATS;
  // Waits for every enqueued command (after an error, and before the slots die).
  void drain() noexcept;
  // UserError when the local size does not fit the device and kernel.
  void check_local_size() const;
  // A built program and what the launches need to know of it.
  struct BuiltProgram {
    cl::Program program;
    std::vector<cl::Kernel> kernels;  // a tile's launches, in order (render_kernel_names())
    std::string options;
    int lanes = 0;              // config_.lanes it was built for
    int default_local_x = 1;    // the preferred work-group size multiple (blocks on CPUs: 1), within max_work_group
    size_t max_work_group = 1;  // CL_KERNEL_WORK_GROUP_SIZE, the least of the kernels'
  };
  // Makes the program of `options` (config_.lanes as built) the one
  // launched, building it unless it already is; adds to timings_.
  void use_program(const std::string& options);
  // Where no --lanes is forced and several lane counts are candidates
  // (render/lane_choice.hpp): the one the process found fastest for this
  // work before, else the fastest in a timed probe of a few bands of rows.
  // The scene's buffers must be uploaded and width_/height_ set.
  void choose_lanes(const SceneData& data, const Bvh* bvh);
  // The build options of config_ for the prepared scene (its features_).
  std::string scene_options() const;
  // The kernel time of rendering the probe's bands into `scratch`.
  double probe_ms(Image& scratch);

  DeviceInfo device_;
  KernelConfig config_;      // lanes resolved: the device's default, or per scene (prepare())
  int requested_lanes_;      // config.lanes as given (0: chosen per scene, choose_lanes())
  KernelFeatures features_;  // the prepared scene's, found once (a pass over every primitive)
  LocalSize local_;
  cl::Context context_;
  cl::CommandQueue queue_;
  cl::CommandQueue transfer_queue_;  // read path: results read here while the next kernel runs
  BuiltProgram built_;
  std::string source_;
  cl::Buffer params_, spheres_, lights_, nodes_, primitives_, leaf_spheres_, planes_, triangles_, triangles_lo_,
      triangle_slots_, materials_;
  bool unified_memory_ = false;  // CL_DEVICE_HOST_UNIFIED_MEMORY: triangles packed into mapped buffers
  bool map_results_ = false;     // asked for and CL_DEVICE_HOST_UNIFIED_MEMORY: mapped, not read
  bool huge_pages_ = false;      // a CPU device with CL_DEVICE_HOST_UNIFIED_MEMORY: large scene buffers on 2 MiB pages
  bool overlap_ = true;
  bool events_plausible_ = true;
  ResultSlot slots_[2];
  std::vector<PendingTile> pending_;  // oldest first
  int next_slot_ = 0;
  int width_ = 0, height_ = 0;
  DeviceTimings timings_;
  FrameLayers* layers_out_ = nullptr;  // begin_frame()'s
  RayCounts counts_;
  double ms_per_row_ = 0;
};

}  // namespace clrt
