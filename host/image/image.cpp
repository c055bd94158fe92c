// image.cpp - 8-bit quantization with canvas semantics.
#include "image/image.hpp"

#include <cmath>

namespace clrt {

uint8_t to_u8(double v) {
  if (std::isnan(v)) return 0;
  double c = v < 0 ? 0 : (v > 255 ? 255 : v);
  return static_cast<uint8_t>(std::nearbyint(c));  // FE_TONEAREST: ties to even
}

std::vector<uint8_t> to_u8(const Image& img) {
  std::vector<uint8_t> out(img.rgb.size());
  for (size_t i = 0; i < out.size(); ++i) out[i] = to_u8(img.rgb[i]);
  return out;
}

}  // namespace clrt
