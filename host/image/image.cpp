// image.cpp - frame buffers and 8-bit quantization with canvas semantics.
#include "image/image.hpp"

#include <cmath>

namespace clrt {

Image::Image(int w, int h, FrameContents c) : width(w), height(h), contents(c) {
  const size_t n = size_t(w) * h;
  if (c.pixels == PixelFormat::Float)
    rgb.assign(n * 3, 0.0);
  else if (c.pixels == PixelFormat::Unit)
    unit.assign(n * 3, 0.0f);
  else
    rgba8.assign(n * 4, 0);
  if (c.classes) {
    hit.assign(n, -1);
    shadowed.assign(n, 0);
  }
}

bool Image::holds(int w, int h, FrameContents c) const {
  const size_t n = size_t(w) * h;
  const bool is_float = c.pixels == PixelFormat::Float, is_unit = c.pixels == PixelFormat::Unit;
  return width == w && height == h && contents == c && rgb.size() == (is_float ? n * 3 : 0) &&
         unit.size() == (is_unit ? n * 3 : 0) && rgba8.size() == (c.pixels == PixelFormat::Rgba8 ? n * 4 : 0) &&
         hit.size() == (c.classes ? n : 0) &&
         shadowed.size() == (c.classes ? n : 0);
}

uint8_t to_u8(double v) {
  if (std::isnan(v)) return 0;
  double c = v < 0 ? 0 : (v > 255 ? 255 : v);
  return static_cast<uint8_t>(std::nearbyint(c));  // FE_TONEAREST: ties to even
}

std::vector<uint8_t> to_u8(const Image& img) {
  if (img.contents.pixels == PixelFormat::Rgba8) {
    std::vector<uint8_t> out(img.pixels() * 3);
    for (size_t p = 0; p < img.pixels(); ++p)
      for (int c = 0; c < 3; ++c) out[p * 3 + c] = img.rgba8[p * 4 + c];
    return out;
  }
  if (img.contents.pixels == PixelFormat::Unit) {
    std::vector<uint8_t> out(img.unit.size());
    for (size_t i = 0; i < out.size(); ++i) out[i] = to_u8(from_unit(img.unit[i]));
    return out;
  }
  std::vector<uint8_t> out(img.rgb.size());
  for (size_t i = 0; i < out.size(); ++i) out[i] = to_u8(img.rgb[i]);
  return out;
}

}  // namespace clrt
