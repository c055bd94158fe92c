// image.hpp - an RGB float image (unclamped, 0..255 scale) plus per-pixel
// classification (which sphere the primary ray hit, which lights were
// shadowed there) and 8-bit quantization / file output through OpenImageIO.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "util/output_file.hpp"

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

// Checks, before rendering, that OUT can be written: a non-empty path whose
// extension OpenImageIO can write, in an existing directory that accepts new
// files, and not itself a directory (output_file.hpp: check_output). Throws
// UserError naming OUT otherwise; returns what OUT is (file, device, stdout).
OutputTarget check_output_format(const std::string& path);
// Writes via a temporary file in the same directory and an atomic rename, so
// a failed write never leaves a half-written OUT. EXR (and other float
// formats) get the unclamped float colour; the rest get 8-bit sRGB values.
void write_image(const Image& img, const std::string& path);
// Reads the first three channels of an image file (untrusted input): float
// formats as stored, integer formats as 8-bit values 0..255. hit/shadowed are
// unknown (-1 / 0). UserError naming the file when it cannot be read, has
// fewer than 3 channels, or is larger than max_edge per edge or max_pixels.
Image read_image(const std::string& path, int max_edge, long long max_pixels);
// Writes an 8-bit RGB buffer the same way.
void write_rgb8(const std::vector<uint8_t>& rgb, int width, int height, const std::string& path);

}  // namespace clrt
