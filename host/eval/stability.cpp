// stability.cpp - running the stiff/extreme suite: every case's reference,
// then every case on every variant, with the verdicts and how far
// supersampling moves the reference (the cases: stability_cases.cpp).
#include "eval/stability.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>

#include "cl/device.hpp"
#include "reference/reference.hpp"
#include "render/precision_support.hpp"
#include "render/renderer.hpp"

namespace clrt {

SamplingConvergence sampling_change(const Image& supersampled, const Image& single) {
  SamplingConvergence out;
  out.change = compare_images(supersampled, single);
  const std::vector<uint8_t> a = to_u8(supersampled), b = to_u8(single);
  double sum = 0;
  for (size_t k = 0; k < a.size(); ++k) sum += std::abs(int(a[k]) - int(b[k]));
  out.mean_abs_8bit = a.empty() ? 0 : sum / double(a.size());
  const int w = single.width, h = single.height;
  auto off_by_gt1 = [](const uint8_t* p, const uint8_t* q) {
    return std::abs(p[0] - q[0]) > 1 || std::abs(p[1] - q[1]) > 1 || std::abs(p[2] - q[2]) > 1;
  };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t p = size_t(y) * w + x;
      if (!off_by_gt1(&a[3 * p], &b[3 * p])) continue;
      bool flat = true;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = x + dx, ny = y + dy;
          if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
          const size_t q = size_t(ny) * w + nx;
          flat &= single.hit[q] == single.hit[p] && single.shadowed[q] == single.shadowed[p] &&
                  !off_by_gt1(&b[3 * q], &b[3 * p]);
        }
      out.changed_off_edges += flat;
    }
  return out;
}

StabilityRun run_stability(const std::vector<StabilityCase>& cases, const std::vector<Precision>& variants, int width,
                           int height, const DeviceInfo& dev, const KernelConfig& base, const ProgressFn& progress) {
  StabilityRun run;
  const int total = int(cases.size() * (1 + variants.size()));
  int done = 0;
  const auto step = [&](const std::string& what) {
    if (progress) progress(done++, total, what);
  };
  std::vector<Image> refs;
  for (const auto& c : cases) {
    step("reference " + c.name());
    refs.push_back(render_reference(c.scene, width, height, c.depth, c.sampling));
  }
  for (size_t i = 0; i < cases.size(); ++i) {
    const auto& c = cases[i];
    if (c.baseline.empty()) continue;
    // The twin's reference when it is among the cases, else the same scene
    // rendered at 1 sample here.
    auto twin = std::find_if(cases.begin(), cases.end(),
                             [&](const StabilityCase& t) { return t.name() == c.baseline && t.sampling.spp == 1; });
    SamplingConvergence sc =
        sampling_change(refs[i], twin != cases.end() ? refs[size_t(twin - cases.begin())]
                                                     : render_reference(c.scene, width, height, c.depth));
    sc.case_index = i;
    sc.baseline = c.baseline;
    run.convergence.push_back(sc);
  }
  for (Precision p : variants) {
    RenderSettings settings;
    settings.kernel = base;
    settings.kernel.precision = p;
    settings.kernel.specialize = false;  // one program per variant for the whole suite
    const bool supported = unsupported_reason(p, dev).empty();
    std::unique_ptr<Renderer> cl;
    if (supported) cl = std::make_unique<Renderer>(std::vector<DeviceInfo>{dev}, settings);
    for (size_t i = 0; i < cases.size(); ++i) {
      step(precision_name(p) + " " + cases[i].name());
      StabilityResult r;
      r.case_index = i;
      r.variant = p;
      r.supported = supported;
      r.expected = cases[i].expectation(p);
      if (supported) {
        cl->prepare(cases[i].scene, width, height, cases[i].depth, cases[i].sampling);
        r.error = compare_images(cl->render(), refs[i]);
        r.pass = within_tolerance(r.error);
      }
      run.results.push_back(r);
    }
  }
  if (progress) progress(total, total, "done");
  return run;
}

}  // namespace clrt
