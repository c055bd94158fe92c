// accuracy.cpp - variants x scenes -> kernel time and error rows.
#include "eval/accuracy.hpp"

#include <memory>

#include "cl/device.hpp"
#include "cl/launch_timing.hpp"
#include "reference/reference.hpp"
#include "render/precision_support.hpp"
#include "render/renderer.hpp"
#include "util/stats.hpp"

namespace clrt {

std::string AccuracyRow::time_source() const {
  return clrt::time_source(host_timed_launches, launches);
}

std::vector<AccuracyRow> measure_accuracy(const std::vector<NamedScene>& scenes, const DeviceInfo& dev,
                                          const AccuracySettings& s) {
  std::vector<AccuracyRow> rows;
  for (const auto& ns : scenes) {
    const int depth = s.depth >= 0 ? s.depth : ns.scene.recursion_depth;
    const Image ref = render_reference(ns.scene, s.width, s.height, depth, Sampling(s.spp, s.adaptive));
    const size_t first = rows.size();
    std::vector<std::unique_ptr<Renderer>> cls;  // per row; null = unsupported
    for (Precision p : s.variants) {
      AccuracyRow row;
      row.scene = ns.name;
      row.variant = precision_name(p);
      row.depth = depth;
      row.note = unsupported_reason(p, dev);
      row.supported = row.note.empty();
      if (row.supported) {
        RenderSettings settings;
        settings.kernel = s.base;
        settings.kernel.precision = p;
        cls.push_back(std::make_unique<Renderer>(std::vector<DeviceInfo>{dev}, settings));
        cls.back()->prepare(ns.scene, s.width, s.height, depth, Sampling(s.spp, s.adaptive));
        row.error = compare_images(cls.back()->render(), ref);  // also the warm-up
      } else {
        cls.push_back(nullptr);
      }
      rows.push_back(row);
    }
    // Timed runs round-robin over the variants, so load from other processes
    // on a shared machine falls on all of them alike.
    for (int i = 0; i < s.repeat; ++i)
      for (size_t k = 0; k < cls.size(); ++k) {
        if (!cls[k]) continue;
        (void)cls[k]->render();
        const FrameStats& t = cls[k]->stats();
        rows[first + k].kernel_ms.push_back(t.kernel_ms);
        rows[first + k].launches += t.launches;
        rows[first + k].host_timed_launches += t.host_timed_launches;
      }
    for (size_t k = first; k < rows.size(); ++k) rows[k].median_ms = median(rows[k].kernel_ms);
  }
  return rows;
}

}  // namespace clrt
