// compare.cpp - pixel and float error metrics, classification flips.
#include "eval/compare.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace clrt {

namespace {
double psnr(double rmse) {
  return rmse > 0 ? 20.0 * std::log10(255.0 / rmse) : std::numeric_limits<double>::infinity();
}
double clamp255(double v) {
  return std::isnan(v) ? 0.0 : std::min(255.0, std::max(0.0, v));
}
}  // namespace

Comparison compare_images(const Image& test, const Image& ref) {
  if (test.width != ref.width || test.height != ref.height)
    throw std::invalid_argument("compare_images: size mismatch");
  if (test.rgb.size() != test.pixels() * 3 || ref.rgb.size() != ref.pixels() * 3)
    throw std::invalid_argument("compare_images: both images need float colour (PixelFormat::Float)");
  Comparison c;
  c.pixels = ref.pixels();
  double se8 = 0, sef = 0;
  for (size_t p = 0; p < c.pixels; ++p) {
    int maxd = 0;
    bool bad = false, bad_ref = false;
    for (int k = 0; k < 3; ++k) {
      double tv = test.rgb[p * 3 + k], rv = ref.rgb[p * 3 + k];
      bad |= !std::isfinite(tv);
      bad_ref |= !std::isfinite(rv);
      int d8 = std::abs(int(to_u8(tv)) - int(to_u8(rv)));
      maxd = std::max(maxd, d8);
      se8 += double(d8) * d8;
      double df = clamp255(tv) - clamp255(rv);
      sef += df * df;
      c.max_abs_float = std::max(c.max_abs_float, std::fabs(df));
    }
    c.nan_inf += bad;
    c.nan_inf_reference += bad_ref;
    if (maxd > c.max_abs_8bit) {
      c.worst_x = int(p % size_t(ref.width));
      c.worst_y = int(p / size_t(ref.width));
      for (int k = 0; k < 3; ++k) {
        c.worst_test[k] = to_u8(test.rgb[p * 3 + k]);
        c.worst_reference[k] = to_u8(ref.rgb[p * 3 + k]);
      }
    }
    c.differ += maxd > 0;
    c.off_by_gt1 += maxd > 1;
    c.max_abs_8bit = std::max(c.max_abs_8bit, maxd);
    if (test.hit[p] != ref.hit[p])
      ++c.hit_flips;
    else if (test.shadowed[p] != ref.shadowed[p])
      ++c.shadow_flips;
  }
  const double n = double(c.pixels) * 3;
  c.rmse_8bit = n > 0 ? std::sqrt(se8 / n) : 0;
  c.rmse_float = n > 0 ? std::sqrt(sef / n) : 0;
  c.psnr_8bit = psnr(c.rmse_8bit);
  c.psnr_float = psnr(c.rmse_float);
  return c;
}

bool within_tolerance(const Comparison& c) {
  return c.percent_off_by_gt1() <= kTolerancePercentOffByGt1 && c.nan_inf <= kToleranceNanInfPixels;
}

Verdict judge(const Comparison& c, const Thresholds& t) {
  Verdict v;
  auto fail = [&v](const std::string& why) {
    v.pass = false;
    v.reason += (v.reason.empty() ? "" : "; ") + why;
  };
  char buf[160];
  if (t.fail_percent >= 0 && c.percent_off_by_gt1() > t.fail_percent) {
    std::snprintf(buf, sizeof buf, "%zu pixels (%.4f%%) off by more than one level, limit %g%% (--fail-percent)",
                  c.off_by_gt1, c.percent_off_by_gt1(), t.fail_percent);
    fail(buf);
  }
  if (t.fail_max >= 0 && c.max_abs_8bit > t.fail_max) {
    std::snprintf(buf, sizeof buf, "largest error %d levels at (%d, %d), limit %d (--fail-max)", c.max_abs_8bit,
                  c.worst_x, c.worst_y, t.fail_max);
    fail(buf);
  }
  if (t.any() && c.nan_inf > 0) fail(std::to_string(c.nan_inf) + " NaN/Inf pixels");
  if (t.any() && c.nan_inf_reference > 0)
    fail(std::to_string(c.nan_inf_reference) + " NaN/Inf pixels in the reference");
  return v;
}

std::vector<uint8_t> diff_image(const Image& test, const Image& ref) {
  std::vector<uint8_t> out(ref.pixels() * 3, 0);
  for (size_t p = 0; p < ref.pixels(); ++p) {
    if (test.hit[p] != ref.hit[p]) {
      out[p * 3] = 255, out[p * 3 + 1] = 0, out[p * 3 + 2] = 255;
      continue;
    }
    if (test.shadowed[p] != ref.shadowed[p]) {
      out[p * 3] = 0, out[p * 3 + 1] = 255, out[p * 3 + 2] = 255;
      continue;
    }
    for (int k = 0; k < 3; ++k) {
      int d = std::abs(int(to_u8(test.rgb[p * 3 + k])) - int(to_u8(ref.rgb[p * 3 + k])));
      out[p * 3 + k] = uint8_t(std::min(255, d * 16));
    }
  }
  return out;
}

}  // namespace clrt
