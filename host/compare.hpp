// compare.hpp - error metrics between an image and the reference image.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "image.hpp"

namespace clrt {

struct Comparison {
  size_t pixels = 0;
  size_t differ = 0;        // any 8-bit channel differs
  size_t off_by_gt1 = 0;    // some 8-bit channel differs by more than 1 level
  int max_abs_8bit = 0;     // largest 8-bit channel difference
  double rmse_8bit = 0, psnr_8bit = 0;    // over quantized 8-bit channels
  double max_abs_float = 0;               // over colours clamped to [0, 255]
  double rmse_float = 0, psnr_float = 0;  // same, before rounding
  size_t nan_inf = 0;       // pixels of the tested image with a NaN/Inf channel
  size_t hit_flips = 0;     // primary ray hit a different sphere (or missed)
  size_t shadow_flips = 0;  // same sphere hit, but a light's visibility differs
  double percent_off_by_gt1() const { return pixels ? 100.0 * off_by_gt1 / pixels : 0.0; }
};

Comparison compare_images(const Image& test, const Image& reference);

// Visual difference: black where equal, |difference| x16 elsewhere; hit flips
// magenta, shadow flips cyan.
std::vector<uint8_t> diff_image(const Image& test, const Image& reference);

// "inf" for an infinite PSNR, otherwise the number with 2 decimals.
std::string format_psnr(double psnr);

}  // namespace clrt
