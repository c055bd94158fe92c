// image.cpp - quantization and atomic image output through OpenImageIO.
#include "image.hpp"

#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "error.hpp"

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

// Writes `pixels` (either float or uint8 RGB) through a temp file + rename.
void write_pixels(const std::string& path, int w, int h, OIIO::TypeDesc type, const void* data) {
  check_output_format(path);
  namespace fs = std::filesystem;
  fs::path target(path);
  fs::path dir = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw UserError(path + ": cannot write output: directory " + dir.string() + " does not exist");
  // Same directory (same filesystem) so rename() is atomic; keep the extension
  // so OpenImageIO picks the same format.
  fs::path tmp = dir / ("." + target.stem().string() + ".tmp" + std::to_string(::getpid()) + target.extension().string());
  auto out = OIIO::ImageOutput::create(tmp.string());
  if (!out) throw UserError(path + ": cannot write output: " + OIIO::geterror());
  OIIO::ImageSpec spec(w, h, 3, type);
  bool ok = out->open(tmp.string(), spec) && out->write_image(type, data) && out->close();
  if (!ok) {
    std::string err = out->geterror();
    out.reset();
    fs::remove(tmp, ec);
    throw UserError(path + ": cannot write output: " + (err.empty() ? std::string("unknown error") : err));
  }
  out.reset();
  fs::rename(tmp, target, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw UserError(path + ": cannot write output: rename failed");
  }
}

}  // namespace

void check_output_format(const std::string& path) {
  auto out = OIIO::ImageOutput::create(path);
  if (!out) {
    (void)OIIO::geterror();
    throw UserError(path + ": unknown image format \"." + extension_of(path) + "\" (use .png, .ppm, .exr, ...)");
  }
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

void write_rgb8(const std::vector<uint8_t>& rgb, int width, int height, const std::string& path) {
  write_pixels(path, width, height, OIIO::TypeDesc::UINT8, rgb.data());
}

}  // namespace clrt
