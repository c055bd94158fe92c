// compare_json.hpp - a Comparison as a JSON object (metric names as in `clrt compare --json`).
#pragma once
#include <nlohmann/json.hpp>

#include "eval/compare.hpp"

namespace clrt {

// pixels, pixels_differ, pixels_off_by_gt1, percent_off_by_gt1, max_abs_8bit,
// rmse_8bit, psnr_8bit (null = infinite), max_abs_float, rmse_float,
// psnr_float, nan_inf_pixels, hit_flips, shadow_flips.
nlohmann::json comparison_json(const Comparison& c);

}  // namespace clrt
