// image_file.cpp - image files through the imaging module (OpenImageIO,
// loaded on first use: image_io.hpp): checked before the work, written
// atomically, read as untrusted input.
#include "image/image_file.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "image/image_io.hpp"
#include "util/error.hpp"
#include "util/output_file.hpp"

namespace clrt {

namespace {

std::string extension_of(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  return ext.empty() ? ext : ext.substr(1);
}

bool is_float_format(const std::string& path) {
  std::string ext = extension_of(path);
  for (auto& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return ext == "exr" || ext == "hdr" || ext == "pfm";
}

// The name whose extension picks the encoder: OUT itself, or "out.png" for
// standard output and devices named without an extension (/dev/stdout).
std::string format_name(const std::string& path, OutputKind kind) {
  return extension_of(path).empty() && kind != OutputKind::File ? std::string("out.png") : path;
}

[[noreturn]] void unknown_format(const std::string& path) {
  throw UserError(path + ": unknown image format \"." + extension_of(path) + "\" (use .png, .ppm, .exr, ...)");
}

// UserError unless there is an encoder for OUT (of this kind). The formats
// of written_without_asking() are known without loading the imaging module
// (only its file must be there); any other extension is asked of
// OpenImageIO, which loads it.
void check_image_format(const std::string& path, OutputKind kind) {
  if (extension_of(path).empty() && kind == OutputKind::File)
    throw UserError(path + ": output has no file extension (use .png, .ppm, .exr, ...)");
  const std::string name = format_name(path, kind);
  std::string ext = extension_of(name);
  for (auto& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  const auto& known = written_without_asking();
  if (std::find(known.begin(), known.end(), ext) != known.end()) {
    imageio::check_module_present();
    return;
  }
  if (!imageio::module().can_write(name)) unknown_format(path);
}

[[noreturn]] void encode_failed(const std::string& path, std::string err) {
  for (auto& c : err)
    if (c == '\n') c = ' ';
  throw UserError(path + ": cannot write output: " + (err.empty() ? std::string("unknown error") : err));
}

// Encodes `pixels` (float or uint8 RGB) in memory - or, for the few encoders
// that can only write to a path, in a private scratch file - and returns the
// file's bytes. Nothing is written to OUT here: write_output() does that.
std::string encode(const std::string& path, OutputKind kind, int w, int h, imageio::PixelType type, const void* data) {
  imageio::Module& io = imageio::module();
  const std::string name = format_name(path, kind);
  std::string bytes;
  if (io.in_memory(name)) {
    const std::string err = io.encode(name, "", w, h, type, data, &bytes);
    if (!err.empty()) encode_failed(path, err);
    return bytes;
  }
  ScratchFile scratch("out" + std::filesystem::path(name).extension().string());
  const std::string err = io.encode(name, scratch.path(), w, h, type, data, nullptr);
  if (!err.empty()) encode_failed(path, err);
  return scratch.read();
}

// (Callers checked OUT before the work with check_output_format();
// write_output() meets any change since.)
void write_pixels(const std::string& path, int w, int h, imageio::PixelType type, const void* data) {
  const OutputKind kind = resolve_output(path).kind;
  check_image_format(path, kind);
  write_output(path, encode(path, kind, w, h, type, data));
}

}  // namespace

const std::vector<std::string>& written_without_asking() {
  static const std::vector<std::string> known{"png",  "ppm", "pnm",  "exr", "hdr", "jpg",
                                              "jpeg", "tif", "tiff", "bmp", "tga"};
  return known;
}

OutputTarget check_output_format(const std::string& path) {
  const OutputTarget target = check_output(path);
  check_image_format(path, target.kind);
  return target;
}

PixelFormat output_pixel_format(const std::string& path) {
  return is_float_format(path) ? PixelFormat::Float : PixelFormat::Rgba8;
}

void write_image(const Image& img, const std::string& path) {
  if (is_float_format(path)) {
    if (img.contents.pixels != PixelFormat::Float)
      throw std::logic_error("write_image: " + path + " needs float colour, the frame holds 8-bit");
    std::vector<float> f(img.rgb.begin(), img.rgb.end());
    write_pixels(path, img.width, img.height, imageio::PixelType::Float, f.data());
  } else {
    auto u8 = to_u8(img);
    write_pixels(path, img.width, img.height, imageio::PixelType::UInt8, u8.data());
  }
}

Image read_image(const std::string& path, int max_edge, long long max_pixels) {
  std::string err;
  auto in = imageio::module().open(path, &err);
  if (!in) throw UserError(path + ": cannot read image: " + err);
  const int w = in->width(), h = in->height(), nch = in->channels();
  if (nch < 3) throw UserError(path + ": cannot read image: " + std::to_string(nch) + " channel(s), need RGB");
  if (w <= 0 || h <= 0 || w > max_edge || h > max_edge || (long long)w * h > max_pixels)
    throw UserError(path + ": image " + std::to_string(w) + "x" + std::to_string(h) + " is too large or empty");
  const bool floating = in->floating();
  Image img(w, h);
  std::vector<float> f;
  std::vector<uint8_t> u8;
  if (floating) {
    f.resize(img.rgb.size());
    err = in->read_rgb(imageio::PixelType::Float, f.data());
  } else {
    u8.resize(img.rgb.size());
    err = in->read_rgb(imageio::PixelType::UInt8, u8.data());
  }
  if (!err.empty()) throw UserError(path + ": cannot read image: " + err);
  for (size_t i = 0; i < img.rgb.size(); ++i) img.rgb[i] = floating ? double(f[i]) : double(u8[i]);
  return img;
}

void write_rgb8(const std::vector<uint8_t>& rgb, int width, int height, const std::string& path) {
  write_pixels(path, width, height, imageio::PixelType::UInt8, rgb.data());
}

}  // namespace clrt
