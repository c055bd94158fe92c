// image.hpp - an RGB float image (unclamped, 0..255 scale) plus per-pixel
// classification (which sphere the primary ray hit, which lights were
// shadowed there), and its 8-bit quantization. Files: image_file.hpp.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace clrt {

struct Image {
  int width = 0, height = 0;
  std::vector<double> rgb;        // width*height*3, row 0 at the top, unclamped
  std::vector<int32_t> hit;       // primary-ray sphere index, -1 = background
  std::vector<int32_t> shadowed;  // bit i: light i blocked at the primary hit

  Image() = default;
  Image(int w, int h)
      : width(w), height(h), rgb(size_t(w) * h * 3, 0.0), hit(size_t(w) * h, -1), shadowed(size_t(w) * h, 0) {}
  size_t pixels() const { return size_t(width) * height; }
};

// Canvas semantics: clamp to [0, 255], round to nearest with ties to even;
// NaN becomes 0 (like a Uint8ClampedArray).
uint8_t to_u8(double v);
std::vector<uint8_t> to_u8(const Image& img);

}  // namespace clrt
