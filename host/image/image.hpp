// image.hpp - a rendered frame: RGB colour (unclamped doubles on the 0..255
// scale, or 8-bit RGBA already quantized by the kernel) plus, where asked
// for, per-pixel classification (which sphere the primary ray hit, which
// lights were shadowed there); and the 8-bit quantization. Files:
// image_file.hpp.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace clrt {

// How a frame's colour is held: what the output needs, and no more.
enum class PixelFormat {
  Float,  // rgb: unclamped doubles (float outputs, comparisons with the reference)
  Rgba8,  // rgba8: the canvas rule of to_u8() applied, alpha 255 (8-bit outputs)
  Unit,   // unit: float32 on the float files' scale, to_unit() (the Python module's arrays)
};

// What a frame carries. The OpenCL kernel writes only these
// (render/build_options.hpp turns them into -D options): an 8-bit PNG needs
// neither float colour nor classification, `compare` needs both.
struct FrameContents {
  PixelFormat pixels = PixelFormat::Float;
  bool classes = true;  // hit and shadowed
  // AOV layers (image/layers.hpp: kLayer* bits; 0 none): the renderer
  // keeps them in a FrameLayers beside the image (Renderer::layers()).
  uint8_t layers = 0;
  bool operator==(const FrameContents& o) const {
    return pixels == o.pixels && classes == o.classes && layers == o.layers;
  }
  bool operator!=(const FrameContents& o) const { return !(*this == o); }
};

struct Image {
  int width = 0, height = 0;
  FrameContents contents;
  std::vector<double> rgb;        // Float: width*height*3, row 0 at the top, unclamped
  std::vector<uint8_t> rgba8;     // Rgba8: width*height*4, row 0 at the top
  std::vector<float> unit;        // Unit: width*height*3, row 0 at the top, to_unit(colour), unclamped
  std::vector<int32_t> hit;       // with classes: primary-ray sphere index, -1 = background
  std::vector<int32_t> shadowed;  // with classes: bit i: light i blocked at the primary hit

  Image() = default;
  Image(int w, int h) : Image(w, h, FrameContents{}) {}
  Image(int w, int h, FrameContents c);
  size_t pixels() const { return size_t(width) * height; }
  // Whether the image has this size and contents, with every buffer sized
  // for them (a frame can then be rendered into it without reallocation).
  bool holds(int w, int h, FrameContents c) const;
};

// Canvas semantics: clamp to [0, 255], round to nearest with ties to even;
// NaN becomes 0 (like a Uint8ClampedArray).
uint8_t to_u8(double v);
// The image's 8-bit RGB (width*height*3): quantized from Float or Unit
// colour (from_unit), or Rgba8's colour without its alpha.
std::vector<uint8_t> to_u8(const Image& img);

// The float files' scale (image_file.hpp: value / 255, 1.0 = white): a colour
// as they store it, and the colour a stored value stands for: the value
// times 255, rounded to float. A kernel's colour is a float c, and
// to_u8(from_unit(to_unit(c))) == to_u8(c) for every float c (checked once
// over all of them in [0, 256]; beyond, both clamp): from_unit gives c back,
// or a float beside it on the same side of every half level, so the stored
// value quantizes as the 8-bit file of the same frame does, bit for bit (the
// Python module's arrays are on this scale).
// (Inline: the renderer stores every channel of a Unit frame through it.)
inline float to_unit(double v) {
  return float(v * (1.0 / 255.0));
}
inline float from_unit(float unit) {
  return float(double(unit) * 255.0);
}

}  // namespace clrt
