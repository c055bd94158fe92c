// multi_renderer.cpp - several devices on one frame.
#include "render/multi_renderer.hpp"
#include "util/timer.hpp"

#include <algorithm>
#include <chrono>
#include <exception>
#include <thread>

namespace clrt {

MultiRenderer::MultiRenderer(const std::vector<DeviceInfo>& devices, const KernelConfig& cfg) {
  for (const auto& d : devices) renderers_.push_back(std::make_unique<ClRenderer>(d, cfg));
}

void MultiRenderer::set_local_size(int lx, int ly) {
  for (auto& r : renderers_) r->set_local_size(lx, ly);
}

void MultiRenderer::prepare(const Scene& scene, int width, int height, int depth) {
  if (renderers_.size() == 1) {
    renderers_[0]->prepare(scene, width, height, depth);
    return;
  }
  std::vector<std::exception_ptr> errors(renderers_.size());
  std::vector<std::thread> threads;
  for (size_t i = 0; i < renderers_.size(); ++i)
    threads.emplace_back([&, i] {
      try {
        renderers_[i]->prepare(scene, width, height, depth);
      } catch (...) {
        errors[i] = std::current_exception();
      }
    });
  for (auto& t : threads) t.join();
  for (auto& e : errors)
    if (e) std::rethrow_exception(e);
}

Image MultiRenderer::render() {
  auto t0 = std::chrono::steady_clock::now();
  std::vector<ClRenderer*> workers;
  for (auto& r : renderers_) {
    r->begin_frame();
    workers.push_back(r.get());
  }
  // All renderers were prepared with the same scene and size.
  Image img(renderers_.front()->width(), renderers_.front()->height());
  shares_ = render_bands(workers, img, policy_);
  wall_ms_ = ms_since(t0);
  for (size_t i = 0; i < renderers_.size(); ++i) renderers_[i]->end_frame(shares_[i], wall_ms_);
  return img;
}

RayCounts MultiRenderer::ray_counts() const {
  RayCounts sum;
  for (const auto& r : renderers_) {
    const RayCounts& c = r->ray_counts();
    sum.primary += c.primary;
    sum.shadow += c.shadow;
    sum.reflection += c.reflection;
    sum.sphere_tests += c.sphere_tests;
  }
  return sum;
}

double MultiRenderer::kernel_ms() const {
  double s = 0;
  for (const auto& sh : shares_) s += sh.kernel_ms;
  return s;
}

int MultiRenderer::launches() const {
  int n = 0;
  for (const auto& sh : shares_) n += sh.tiles;
  return n;
}

int MultiRenderer::host_timed_launches() const {
  int n = 0;
  for (const auto& sh : shares_) n += sh.host_timed_launches;
  return n;
}

double MultiRenderer::build_ms() const {
  double m = 0;
  for (const auto& r : renderers_) m = std::max(m, r->timings().build_ms);
  return m;
}

double MultiRenderer::upload_ms() const {
  double m = 0;
  for (const auto& r : renderers_) m = std::max(m, r->timings().upload_ms);
  return m;
}

}  // namespace clrt
