// self_test.cpp - `clrt devices --check` for one device.
#include "eval/self_test.hpp"

#include "scene/builtin_scene.hpp"
#include "render/cl_renderer.hpp"
#include "util/error.hpp"
#include "reference/reference.hpp"

namespace clrt {

SelfTestResult self_test(const DeviceInfo& dev, const KernelConfig& cfg, int width, int height) {
  SelfTestResult r;
  Scene scene = builtin_demo_scene();
  try {
    ClRenderer cl(dev, cfg);
    cl.prepare(scene, width, height, scene.recursion_depth);
    Image img = cl.render();
    r.build_ms = cl.timings().build_ms;
    r.kernel_ms = cl.timings().kernel_ms;
    r.launches = cl.timings().launches;
    r.host_timed_launches = cl.timings().host_timed_launches;
    r.cmp = compare_images(img, render_reference(scene, width, height, scene.recursion_depth));
    r.pass = r.cmp.nan_inf == 0 && r.cmp.percent_off_by_gt1() <= 0.05;
  } catch (const cl::Error& e) {
    r.error = describe(e);
  } catch (const std::exception& e) {
    r.error = e.what();
  }
  return r;
}

}  // namespace clrt
