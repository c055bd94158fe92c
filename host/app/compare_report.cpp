// compare_report.cpp - Comparison -> JSON and PSNR text.
#include "app/compare_report.hpp"

#include <cmath>
#include <cstdio>

namespace clrt {

nlohmann::json comparison_json(const Comparison& c) {
  auto num = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); };
  return {{"pixels", c.pixels},
          {"pixels_differ", c.differ},
          {"pixels_off_by_gt1", c.off_by_gt1},
          {"percent_off_by_gt1", c.percent_off_by_gt1()},
          {"max_abs_8bit", c.max_abs_8bit},
          {"rmse_8bit", c.rmse_8bit},
          {"psnr_8bit", num(c.psnr_8bit)},
          {"max_abs_float", c.max_abs_float},
          {"rmse_float", c.rmse_float},
          {"psnr_float", num(c.psnr_float)},
          {"nan_inf_pixels", c.nan_inf},
          {"nan_inf_pixels_reference", c.nan_inf_reference},
          {"hit_flips", c.hit_flips},
          {"shadow_flips", c.shadow_flips}};
}

std::string format_psnr(double psnr) {
  if (std::isinf(psnr)) return "inf";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", psnr);
  return buf;
}

}  // namespace clrt
