// compare_report.cpp - Comparison -> metric table, JSON, CSV and PSNR text.
#include "app/compare_report.hpp"

#include <cmath>
#include <cstdio>

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

}  // namespace clrt
