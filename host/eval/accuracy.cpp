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

int accuracy_depth(const Scene& scene, const AccuracySettings& s) {
  return s.depth >= 0 ? s.depth : scene.recursion_depth;
}

Image accuracy_reference(const Scene& scene, const AccuracySettings& s) {
  return render_reference(scene, s.width, s.height, accuracy_depth(scene, s), Sampling(s.spp, s.adaptive));
}

AccuracyRow accuracy_row(const NamedScene& ns, const AccuracyVariant& v, const DeviceInfo& dev,
                         const AccuracySettings& s) {
  AccuracyRow row;
  row.scene = ns.name;
  row.variant = v.name();
  row.depth = accuracy_depth(ns.scene, s);
  row.note = unsupported_reason(v.precision, dev);
  if (row.note.empty() && v.subsample != Subsample::Off && s.spp != 1)
    row.note = "subsampling needs one sample per pixel (--spp 1)";
  row.supported = row.note.empty();
  return row;
}

namespace {

// A prepared renderer of variant `v` (its first render() is the warm-up).
std::unique_ptr<Renderer> variant_renderer(const NamedScene& ns, const AccuracyVariant& v, const DeviceInfo& dev,
                                           const AccuracySettings& s) {
  RenderSettings settings;
  settings.kernel = s.base;
  settings.kernel.precision = v.precision;
  auto r = std::make_unique<Renderer>(std::vector<DeviceInfo>{dev}, settings);
  // (the error of a subsampled variant is against the exact reference:
  // what the speed-up costs)
  r->prepare(ns.scene, s.width, s.height, accuracy_depth(ns.scene, s), Sampling(s.spp, s.adaptive, v.subsample));
  return r;
}

// One timed run of `r` into `row`.
void timed_run(Renderer& r, AccuracyRow& row) {
  (void)r.render();
  const FrameStats& t = r.stats();
  row.kernel_ms.push_back(t.kernel_ms);
  row.launches += t.launches;
  row.host_timed_launches += t.host_timed_launches;
}

}  // namespace

AccuracyRow measure_accuracy_variant(const NamedScene& ns, const AccuracyVariant& v, const DeviceInfo& dev,
                                     const AccuracySettings& s, Image& image) {
  AccuracyRow row = accuracy_row(ns, v, dev, s);
  image = Image();
  if (!row.supported) return row;
  auto r = variant_renderer(ns, v, dev, s);
  image = r->render();  // also the warm-up
  for (int i = 0; i < s.repeat; ++i) timed_run(*r, row);
  row.median_ms = median(row.kernel_ms);
  return row;
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
    step(ns.name + ": reference");
    const Image ref = accuracy_reference(ns.scene, s);
    const size_t first = rows.size();
    std::vector<std::unique_ptr<Renderer>> cls;  // per row; null = unsupported
    for (const AccuracyVariant& v : s.variants) {
      step(ns.name + ": " + v.name());
      AccuracyRow row = accuracy_row(ns, v, dev, s);
      if (row.supported) {
        cls.push_back(variant_renderer(ns, v, dev, s));
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
        if (cls[k]) timed_run(*cls[k], rows[first + k]);
      }
    for (size_t k = first; k < rows.size(); ++k) rows[k].median_ms = median(rows[k].kernel_ms);
  }
  if (s.progress) s.progress(total, total, "done");
  return rows;
}

}  // namespace clrt
