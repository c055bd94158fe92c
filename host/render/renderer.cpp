// renderer.cpp - one frame over one or more devices.
#include "render/renderer.hpp"

#include <algorithm>
#include <chrono>
#include <stdexcept>

#include "render/scene_buffers.hpp"
#include "util/doing.hpp"
#include "util/error.hpp"
#include "util/parallel.hpp"
#include "util/timer.hpp"

namespace clrt {

Renderer::Renderer(const std::vector<DeviceInfo>& devices, const RenderSettings& settings) : settings_(settings) {
  if (devices.empty()) throw std::logic_error("Renderer without devices");
  for (const auto& d : devices)
    devices_.push_back(std::make_unique<DeviceRenderer>(d, settings.kernel, settings.local, settings.map_results,
                                                        settings.overlap_downloads));
}

std::string Renderer::device_names() const {
  std::string names;
  for (size_t i = 0; i < devices_.size(); ++i) names += (i ? " + " : "") + devices_[i]->device().name;
  return names;
}

const std::string& Renderer::options() const {
  return devices_.front()->options();
}

void Renderer::prepare(const Scene& scene, int width, int height, int depth, Sampling sampling) {
  const int spp = sampling.spp;
  if (spp < 1 || spp > CLRT_MAX_SPP)
    throw UserError("--spp must be in [1, " + std::to_string(CLRT_MAX_SPP) + "] (got " + std::to_string(spp) + ")");
  if (!(sampling.adaptive_threshold <= 1e6))  // negative: off; NaN refused
    throw UserError("--adaptive must be at most 1e6 levels");
  const Doing doing("preparing a " + std::to_string(width) + "x" + std::to_string(height) + " frame of " +
                    std::to_string(scene.spheres.size() + scene.triangles.size()) + " primitives");
  FrameStats stats;
  std::unique_ptr<Bvh> bvh;
  if (uses_bvh(settings_.kernel.accel, bvh_primitive_count(scene), settings_.kernel.precision)) {
    const auto t0 = Clock::now();
    bvh = std::make_unique<Bvh>(
        build_bvh(scene, settings_.kernel.precision, packing_origin(scene, settings_.kernel.precision)));
    stats.bvh = true;
    stats.bvh_build_ms = ms_since(t0);
    stats.bvh_bytes = bvh->bytes();
    stats.bvh_depth = bvh->depth;
    // The devices get the wide form; the binary tree it was collapsed from
    // (bvh.hpp, read by the hierarchy's tests) would stay resident through
    // the upload: 77 MiB of the preparation's peak at 4 million triangles.
    std::vector<clrt_bvh_node>().swap(bvh->nodes);
  }
  // One host thread per device when there are several: builds take seconds.
  // (Not the calling thread for any of them: PoCL loads a library per
  // compiled kernel into the building thread's dynamic TLS, and with two
  // contexts LeakSanitizer's exit-time scan of the main thread's stale DTLS
  // crashes; docs/developer/sanitizers.md.)
  if (devices_.size() == 1)
    devices_[0]->prepare(scene, width, height, depth, sampling, bvh.get());
  else
    run_on_threads(devices_.size(),
                   [&](size_t i) { devices_[i]->prepare(scene, width, height, depth, sampling, bvh.get()); });

  stats_ = stats;
  stats_.build_cached = true;
  for (const auto& d : devices_) {
    stats_.build_ms = std::max(stats_.build_ms, d->timings().build_ms);
    stats_.upload_ms = std::max(stats_.upload_ms, d->timings().upload_ms);
    stats_.build_cached = stats_.build_cached && d->timings().build_cached;
  }
}

Image Renderer::render() {
  Image img;
  render_into(img);
  return img;
}

int Renderer::width() const {
  return devices_.front()->width();
}

int Renderer::height() const {
  return devices_.front()->height();
}

void Renderer::render_into(Image& img) {
  render_rows(img, 0, height());
}

void Renderer::render_rows(Image& img, int y_begin, int y_end) {
  const auto t0 = Clock::now();
  const unsigned layers = settings_.kernel.output.layers;
  const int width = devices_.front()->width(), height = devices_.front()->height();
  if (!layers)
    layers_ = FrameLayers();
  else if (!layers_.holds(width, height, layers))
    layers_ = FrameLayers(width, height, layers);
  std::vector<DeviceRenderer*> workers;
  for (auto& d : devices_) {
    if (d->width() == 0) throw std::logic_error("Renderer::render before prepare");
    d->begin_frame(layers ? &layers_ : nullptr);
    workers.push_back(d.get());
  }
  // Every device was prepared with the same scene and size; the bands cover
  // every pixel, so a reused image needs no clearing.
  if (!img.holds(width, height, settings_.kernel.output)) img = Image(width, height, settings_.kernel.output);
  stats_.shares = render_bands(workers, img, settings_.tiles, settings_.progress, y_begin, y_end, settings_.cancel);
  stats_.wall_ms = ms_since(t0);
  stats_.kernel_ms = stats_.download_ms = 0;
  stats_.launches = stats_.host_timed_launches = 0;
  stats_.rays = {};
  for (size_t i = 0; i < devices_.size(); ++i) {
    const DeviceShare& share = stats_.shares[i];
    stats_.kernel_ms += share.kernel_ms;
    stats_.launches += share.tiles;
    stats_.host_timed_launches += share.host_timed_launches;
    stats_.download_ms += devices_[i]->timings().download_ms;
    stats_.rays += devices_[i]->ray_counts();
  }
}

}  // namespace clrt
