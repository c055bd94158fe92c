// image_file.cpp - image files through OpenImageIO: checked before the work,
// written atomically, read as untrusted input.
#include "image/image_file.hpp"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <cmath>
#include <filesystem>

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

// UserError unless OpenImageIO has an encoder for OUT (of this kind).
void check_image_format(const std::string& path, OutputKind kind) {
  const std::string ext = extension_of(path);
  if (ext.empty() && kind == OutputKind::File)
    throw UserError(path + ": output has no file extension (use .png, .ppm, .exr, ...)");
  if (!OIIO::ImageOutput::create(format_name(path, kind))) {
    (void)OIIO::geterror();
    throw UserError(path + ": unknown image format \"." + ext + "\" (use .png, .ppm, .exr, ...)");
  }
}

[[noreturn]] void encode_failed(const std::string& path, std::string err) {
  for (auto& c : err)
    if (c == '\n') c = ' ';
  throw UserError(path + ": cannot write output: " + (err.empty() ? std::string("unknown error") : err));
}

// Encodes `pixels` (float or uint8 RGB) in memory - or, for the few encoders
// that can only write to a path, in a private scratch file - and returns the
// file's bytes. Nothing is written to OUT here: write_output() does that.
std::string encode(const std::string& path, OutputKind kind, int w, int h, OIIO::TypeDesc type, const void* data) {
  const std::string name = format_name(path, kind);
  OIIO::ImageSpec spec(w, h, 3, type);
  std::vector<unsigned char> buf;
  OIIO::Filesystem::IOVecOutput memory(buf);
  auto out = OIIO::ImageOutput::create(name);
  if (!out) encode_failed(path, OIIO::geterror());
  if (out->supports("ioproxy")) {
    out = OIIO::ImageOutput::create(name, &memory);
    if (!out) encode_failed(path, OIIO::geterror());
    if (!(out->open(name, spec) && out->write_image(type, data) && out->close())) encode_failed(path, out->geterror());
    return std::string(buf.begin(), buf.end());
  }
  ScratchFile scratch("out" + std::filesystem::path(name).extension().string());
  if (!(out->open(scratch.path(), spec) && out->write_image(type, data) && out->close()))
    encode_failed(path, out->geterror());
  out.reset();
  return scratch.read();
}

// (Callers checked OUT before the work with check_output_format();
// write_output() meets any change since.)
void write_pixels(const std::string& path, int w, int h, OIIO::TypeDesc type, const void* data) {
  const OutputKind kind = resolve_output(path).kind;
  check_image_format(path, kind);
  write_output(path, encode(path, kind, w, h, type, data));
}

}  // namespace

OutputTarget check_output_format(const std::string& path) {
  const OutputTarget target = check_output(path);
  check_image_format(path, target.kind);
  return target;
}

void write_image(const Image& img, const std::string& path) {
  if (is_float_format(path)) {
    std::vector<float> f(img.rgb.begin(), img.rgb.end());
    write_pixels(path, img.width, img.height, OIIO::TypeDesc::FLOAT, f.data());
  } else {
    auto u8 = to_u8(img);
    write_pixels(path, img.width, img.height, OIIO::TypeDesc::UINT8, u8.data());
  }
}

Image read_image(const std::string& path, int max_edge, long long max_pixels) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) {
    std::string err = OIIO::geterror();
    throw UserError(path + ": cannot read image: " + (err.empty() ? std::string("unknown error") : err));
  }
  const OIIO::ImageSpec& spec = in->spec();
  const int w = spec.width, h = spec.height, nch = spec.nchannels;
  if (nch < 3) throw UserError(path + ": cannot read image: " + std::to_string(nch) + " channel(s), need RGB");
  if (w <= 0 || h <= 0 || w > max_edge || h > max_edge || (long long)w * h > max_pixels)
    throw UserError(path + ": image " + std::to_string(w) + "x" + std::to_string(h) + " is too large or empty");
  const bool floating = spec.format.is_floating_point();
  Image img(w, h);
  std::vector<float> f;
  std::vector<uint8_t> u8;
  bool ok;
  if (floating) {
    f.resize(img.rgb.size());
    ok = in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, f.data());
  } else {
    u8.resize(img.rgb.size());
    ok = in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, u8.data());
  }
  if (!ok) {
    std::string err = in->geterror();
    throw UserError(path + ": cannot read image: " + (err.empty() ? std::string("unknown error") : err));
  }
  for (size_t i = 0; i < img.rgb.size(); ++i) img.rgb[i] = floating ? double(f[i]) : double(u8[i]);
  return img;
}

void write_rgb8(const std::vector<uint8_t>& rgb, int width, int height, const std::string& path) {
  write_pixels(path, width, height, OIIO::TypeDesc::UINT8, rgb.data());
}

}  // namespace clrt
