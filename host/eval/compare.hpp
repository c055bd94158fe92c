// compare.hpp - error metrics between an image and the reference image.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "image/image.hpp"

namespace clrt {

struct Comparison {
  size_t pixels = 0;
  size_t differ = 0;                      // any 8-bit channel differs
  size_t off_by_gt1 = 0;                  // some 8-bit channel differs by more than 1 level
  int max_abs_8bit = 0;                   // largest 8-bit channel difference
  double rmse_8bit = 0, psnr_8bit = 0;    // over quantized 8-bit channels
  double max_abs_float = 0;               // over colours clamped to [0, 255]
  double rmse_float = 0, psnr_float = 0;  // same, before rounding
  size_t nan_inf = 0;                     // pixels of the tested image with a NaN/Inf channel
  size_t nan_inf_reference = 0;           // the same in the reference image (the oracle must be finite too)
  size_t hit_flips = 0;                   // primary ray hit a different sphere (or missed)
  size_t shadow_flips = 0;                // same sphere hit, but a light's visibility differs
  // The pixel with the largest 8-bit channel difference (the first such in
  // row order; (0, 0) when nothing differs): column, row from the top, and
  // both pixels' 8-bit values.
  int worst_x = 0, worst_y = 0;
  uint8_t worst_test[3] = {0, 0, 0}, worst_reference[3] = {0, 0, 0};
  double percent_off_by_gt1() const { return pixels ? 100.0 * off_by_gt1 / pixels : 0.0; }
};

Comparison compare_images(const Image& test, const Image& reference);

// The tolerance of `clrt stability` and `clrt devices --check`, in one place:
// an image passes when at most this share of its pixels is off by more than
// one 8-bit level and none is NaN/Inf. Float32 is never pixel-exact against
// the double reference (grazing rays and silhouettes round either way; the
// demo scene is at about 0.001%), so zero pixels would be too strict.
constexpr double kTolerancePercentOffByGt1 = 0.05;
constexpr size_t kToleranceNanInfPixels = 0;
bool within_tolerance(const Comparison& c);

// Pass/fail limits for `clrt compare` (like idiff's -fail): negative = not set.
struct Thresholds {
  double fail_percent = -1;  // most pixels off by more than one level, in percent
  int fail_max = -1;         // largest 8-bit channel difference
  bool any() const { return fail_percent >= 0 || fail_max >= 0; }
};

struct Verdict {
  bool pass = true;
  std::string reason;  // which limit failed, with the values; empty on a pass
};

// Fails when a set limit is exceeded, and - once any limit is set - on any
// NaN/Inf pixel.
Verdict judge(const Comparison& c, const Thresholds& t);

// Visual difference: black where equal, |difference| x16 elsewhere; hit flips
// magenta, shadow flips cyan.
std::vector<uint8_t> diff_image(const Image& test, const Image& reference);

}  // namespace clrt
