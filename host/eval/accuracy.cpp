// accuracy.cpp - variants x scenes -> kernel time and error rows.
#include "eval/accuracy.hpp"

#include <memory>

#include "cl/device.hpp"
#include "cl/launch_timing.hpp"
#include "reference/reference.hpp"
#include "render/precision_support.hpp"
#include "render/renderer.hpp"
#include "util/error.hpp"
#include "util/stats.hpp"

namespace clrt {

namespace {
constexpr const char* kSubsampleInfix = "+subsample-";
}

std::string AccuracyVariant::name() const {
  return precision_name(precision) + (subsample != Subsample::Off ? kSubsampleInfix + subsample_name(subsample) : "");
}

AccuracyVariant parse_accuracy_variant(const std::string& name) {
  const size_t at = name.find(kSubsampleInfix);
  AccuracyVariant v;
  v.precision = parse_precision(name.substr(0, at));
  if (at == std::string::npos) return v;
  const std::string mode = name.substr(at + std::string(kSubsampleInfix).size());
  for (Subsample m : {Subsample::Shade, Subsample::Interpolate})
    if (mode == subsample_name(m)) v.subsample = m;
  if (v.subsample == Subsample::Off)
    throw UserError("unknown variant '" + name + "' (subsampling modes: shade, interpolate)");
  return v;
}

std::vector<AccuracyVariant> default_accuracy_variants() {
  std::vector<AccuracyVariant> variants;
  for (Precision p : all_precisions()) variants.push_back({p, Subsample::Off});
  variants.push_back({Precision::Robust, Subsample::Shade});
  variants.push_back({Precision::Robust, Subsample::Interpolate});
  return variants;
}

std::string AccuracyRow::time_source() const {
  return clrt::time_source(host_timed_launches, launches);
}

std::vector<AccuracyRow> measure_accuracy(const std::vector<NamedScene>& scenes, const DeviceInfo& dev,
                                          const AccuracySettings& s) {
  std::vector<AccuracyRow> rows;
  const int variants = int(s.variants.size());
  const int total = int(scenes.size()) * (1 + variants + s.repeat * variants);
  int done = 0;
  const auto step = [&](const std::string& what) {
    if (s.progress) s.progress(done++, total, what);
  };
  for (const auto& ns : scenes) {
    const int depth = s.depth >= 0 ? s.depth : ns.scene.recursion_depth;
    step(ns.name + ": reference");
    const Image ref = render_reference(ns.scene, s.width, s.height, depth, Sampling(s.spp, s.adaptive));
    const size_t first = rows.size();
    std::vector<std::unique_ptr<Renderer>> cls;  // per row; null = unsupported
    for (const AccuracyVariant& v : s.variants) {
      step(ns.name + ": " + v.name());
      AccuracyRow row;
      row.scene = ns.name;
      row.variant = v.name();
      row.depth = depth;
      row.note = unsupported_reason(v.precision, dev);
      if (row.note.empty() && v.subsample != Subsample::Off && s.spp != 1)
        row.note = "subsampling needs one sample per pixel (--spp 1)";
      row.supported = row.note.empty();
      if (row.supported) {
        RenderSettings settings;
        settings.kernel = s.base;
        settings.kernel.precision = v.precision;
        cls.push_back(std::make_unique<Renderer>(std::vector<DeviceInfo>{dev}, settings));
        // (the error of a subsampled variant is against the exact reference:
        // what the speed-up costs)
        cls.back()->prepare(ns.scene, s.width, s.height, depth, Sampling(s.spp, s.adaptive, v.subsample));
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
        step(ns.name + ": run " + std::to_string(i + 1) + " of " + rows[first + k].variant);
        if (!cls[k]) continue;
        (void)cls[k]->render();
        const FrameStats& t = cls[k]->stats();
        rows[first + k].kernel_ms.push_back(t.kernel_ms);
        rows[first + k].launches += t.launches;
        rows[first + k].host_timed_launches += t.host_timed_launches;
      }
    for (size_t k = first; k < rows.size(); ++k) rows[k].median_ms = median(rows[k].kernel_ms);
  }
  if (s.progress) s.progress(total, total, "done");
  return rows;
}

}  // namespace clrt
