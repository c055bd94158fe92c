// compare_report.hpp - how a Comparison is shown: the metric names of `clrt
// compare --json` (shared by every command's JSON) and the PSNR as text.
#pragma once
#include <nlohmann/json.hpp>
#include <string>

#include "eval/compare.hpp"

namespace clrt {

// pixels, pixels_differ, pixels_off_by_gt1, percent_off_by_gt1, max_abs_8bit,
// rmse_8bit, psnr_8bit (null = infinite), max_abs_float, rmse_float,
// psnr_float, nan_inf_pixels, nan_inf_pixels_reference, hit_flips,
// shadow_flips.
nlohmann::json comparison_json(const Comparison& c);

// "inf" for an infinite PSNR, otherwise the number with 2 decimals.
std::string format_psnr(double psnr);

}  // namespace clrt
