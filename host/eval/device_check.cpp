// device_check.cpp - `clrt devices --check` for one device.
#include "eval/device_check.hpp"

#include "reference/reference.hpp"
#include "render/renderer.hpp"
#include "scene/builtin_scene.hpp"
#include "util/error.hpp"

namespace clrt {

DeviceCheckResult check_device(const DeviceInfo& dev, const KernelConfig& cfg, int width, int height) {
  DeviceCheckResult r;
  Scene scene = builtin_demo_scene();
  try {
    RenderSettings settings;
    settings.kernel = cfg;
    Renderer renderer({dev}, settings);
    renderer.prepare(scene, width, height, scene.recursion_depth);
    Image img = renderer.render();
    const FrameStats& stats = renderer.stats();
    r.build_ms = stats.build_ms;
    r.kernel_ms = stats.kernel_ms;
    r.launches = stats.launches;
    r.host_timed_launches = stats.host_timed_launches;
    r.cmp = compare_images(img, render_reference(scene, width, height, scene.recursion_depth));
    r.pass = within_tolerance(r.cmp);
  } catch (const cl::Error& e) {
    r.error = describe(e);
  } catch (const std::exception& e) {
    r.error = e.what();
  }
  return r;
}

}  // namespace clrt
