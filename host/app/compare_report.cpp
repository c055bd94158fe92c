// compare_report.cpp - Comparison -> metric table, JSON, CSV and PSNR text.
#include "app/compare_report.hpp"

#include <cmath>
#include <cstdio>

#include "app/report_header.hpp"
#include "cl/launch_timing.hpp"

namespace clrt {

std::vector<std::pair<std::string, nlohmann::ordered_json>> comparison_metrics(const Comparison& c) {
  auto num = [](double v) { return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(); };
  return {{"pixels", c.pixels},
          {"pixels_differ", c.differ},
          {"pixels_off_by_gt1", c.off_by_gt1},
          {"pixels_off_by_gt1_percent", c.percent_off_by_gt1()},
          {"max_abs_8bit", c.max_abs_8bit},
          {"rmse_8bit", c.rmse_8bit},
          {"psnr_8bit_db", num(c.psnr_8bit)},
          {"max_abs_float", c.max_abs_float},
          {"rmse_float", c.rmse_float},
          {"psnr_float_db", num(c.psnr_float)},
          {"nan_inf_pixels", c.nan_inf},
          {"nan_inf_pixels_reference", c.nan_inf_reference},
          {"hit_flip_pixels", c.hit_flips},
          {"shadow_flip_pixels", c.shadow_flips}};
}

nlohmann::ordered_json comparison_json(const Comparison& c) {
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  for (auto& [k, v] : comparison_metrics(c)) j[k] = v;
  return j;
}

void comparison_csv(CsvTable& t, const Comparison& c, const std::string& prefix) {
  for (auto& [k, v] : comparison_metrics(c)) {
    if (v.is_null())
      t.set(prefix + k, "");
    else if (v.is_number_float())
      t.set_number(prefix + k, v.get<double>());
    else
      t.set(prefix + k, v.dump());
  }
}

std::string format_psnr(double psnr) {
  if (std::isinf(psnr)) return "inf";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", psnr);
  return buf;
}

nlohmann::ordered_json layer_comparison_json(const LayerComparison& c) {
  nlohmann::ordered_json j{{"layers", layer_list(c.layers)},
                           {"same_hit_pixels", c.same_hit},
                           {"id_differ_pixels", c.id_differ},
                           {"id_differ_percent", c.percent(c.id_differ)},
                           {"id_differ_silhouette_pixels", c.id_differ_silhouette},
                           {"id_differ_inside_pixels", c.id_differ_inside},
                           {"silhouette_pixels", c.silhouette_pixels}};
  if (!c.ids_compared)
    for (const char* key : {"id_differ_pixels", "id_differ_percent", "id_differ_silhouette_pixels",
                            "id_differ_inside_pixels"})
      j[key] = nullptr;  // (an image without an id layer)
  if (c.layers & kLayerDepth) {
    j["depth_max_relative_error"] = c.depth_max_relative;
    j["depth_over_pixels"] = c.depth_over;
    j["depth_tolerance_relative"] = kDepthRelative;
  }
  if (c.layers & kLayerNormal) {
    j["normal_max_error"] = c.normal_max_error;
    j["normal_over_pixels"] = c.normal_over;
    j["normal_tolerance"] = kNormalAbsolute;
  }
  if (c.layers & kLayerAlbedo) j["albedo_differ_pixels"] = c.albedo_differ;
  j["non_finite_pixels"] = c.non_finite;
  j["pass"] = c.pass();
  return j;
}

void print_layer_comparison(const LayerComparison& c, std::FILE* out) {
  const char* ok = "within tolerance";
  if (!c.ids_compared)
    std::fprintf(out, "layer id       n/a (the image has no id layer: the others are compared where the reference's "
                 "id says)\n");
  else
    std::fprintf(out,
                 "layer id       %zu pixels differ (%.4f%%): %zu on the reference's silhouettes (%zu pixels), %zu "
                 "elsewhere (allowed: 0)\n",
                 c.id_differ, c.percent(c.id_differ), c.id_differ_silhouette, c.silhouette_pixels, c.id_differ_inside);
  if (c.layers & kLayerDepth)
    std::fprintf(out, "layer depth    max relative error x cos %.3g over %zu pixels of the same hit (limit %g): %s\n",
                 c.depth_max_relative, c.same_hit, kDepthRelative,
                 c.depth_over ? (std::to_string(c.depth_over) + " pixels over").c_str() : ok);
  if (c.layers & kLayerNormal)
    std::fprintf(out, "layer normal   max component error x cos %.3g over %zu pixels of the same hit (limit %g): %s\n",
                 c.normal_max_error, c.same_hit, kNormalAbsolute,
                 c.normal_over ? (std::to_string(c.normal_over) + " pixels over").c_str() : ok);
  if (c.layers & kLayerAlbedo)
    std::fprintf(out, "layer albedo   %zu of %zu pixels of the same hit differ at the 8-bit level (limit 0)\n",
                 c.albedo_differ, c.same_hit);
  if (c.non_finite) std::fprintf(out, "layer values   %zu pixels with a NaN, or a finite depth on a miss\n", c.non_finite);
}

nlohmann::ordered_json compare_json(const CompareRun& r, const RenderOptions& o) {
  const Comparison& c = r.comparison;
  const bool classified = r.classified();
  nlohmann::ordered_json j = header_json(report_header(classified ? r.opencl.device : std::string()));
  j.update(nlohmann::ordered_json{
      {"scene", o.scene_path},
      {"overrides", overrides_json(o.image.overrides)},
      {"width", o.image.width},
      {"height", o.image.height},
      {"depth", r.depth},
      {"spp", o.image.spp},
      {"subsample", subsample_name(o.image.subsample)},
      {"reference_ms", r.reference.wall_ms},
      {"worst_pixel",
       {{"x", c.worst_x},
        {"y", c.worst_y},
        {"value", {c.worst_test[0], c.worst_test[1], c.worst_test[2]}},
        {"reference", {c.worst_reference[0], c.worst_reference[1], c.worst_reference[2]}}}}});
  if (classified)
    j.update(nlohmann::ordered_json{
        {"precision", o.kernel.precision},
        {"device", r.opencl.device},
        {"build_options", r.opencl.options},
        {"opencl_kernel_ms", r.opencl.frame.kernel_ms},
        {"opencl_kernel_time_source", time_source(r.opencl.frame.host_timed_launches, r.opencl.frame.launches)},
        {"opencl_build_ms", r.opencl.frame.build_ms},
        {"opencl_build_cached", r.opencl.frame.build_cached},
        {"opencl_total_ms", r.opencl.wall_ms}});
  else
    j["image"] = r.image;
  j.update(comparison_json(c));
  if (!classified) j["hit_flip_pixels"] = j["shadow_flip_pixels"] = nullptr;
  if (r.layers) {
    j["aov"] = layer_comparison_json(r.layer_comparison);
    j["verdict"] = r.verdict.pass ? "pass" : "fail";
  }
  if (r.limits.any()) {
    j["fail_percent"] =
        r.limits.fail_percent >= 0 ? nlohmann::ordered_json(r.limits.fail_percent) : nlohmann::ordered_json();
    j["fail_max_8bit"] = r.limits.fail_max >= 0 ? nlohmann::ordered_json(r.limits.fail_max) : nlohmann::ordered_json();
    j["verdict"] = r.verdict.pass ? "pass" : "fail";
  }
  return j;
}

}  // namespace clrt
