// image_io_builtin.cpp - the imaging module of a lean build (CLRT_LEAN=ON;
// CMakeLists.txt builds this file instead of image_io.cpp and no
// clrt_imageio.so): no OpenImageIO and no dlopen, clrt's own PPM writer and
// PPM/PFM reader behind the interface of image_io.hpp. PPM: binary P6,
// 8-bit (a maxval up to 65535 is read, scaled to 8 bits). PFM: "PF" (RGB)
// float32 of either byte order, rows bottom to top (image_file.cpp writes
// it in both builds). Files read are untrusted: the header is parsed and
// the file's size checked before any pixel is read or memory sized by it.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>

#include "image/image_file.hpp"
#include "image/image_io.hpp"
#include "image/pnm_header.hpp"
#include "util/build_features.hpp"
#include "util/error.hpp"

namespace clrt {
namespace imageio {

namespace {

static_assert(kLeanBuild, "image_io_builtin.cpp is the imaging module of a lean build (CLRT_LEAN=ON) only");

// A PPM (P6) or PFM (PF / Pf) file whose header has been parsed.
class PnmReader final : public Reader {
 public:
  PnmReader(std::string path, bool pfm, int width, int height, int channels, long maxval_or_order,
            std::streamoff data_offset)
      : path_(std::move(path)),
        pfm_(pfm),
        width_(width),
        height_(height),
        channels_(channels),
        maxval_or_order_(maxval_or_order),
        data_offset_(data_offset) {}

  int width() const override { return width_; }
  int height() const override { return height_; }
  int channels() const override { return channels_; }
  bool floating() const override { return pfm_; }
  std::string attribute(const std::string&) const override { return ""; }  // (PPM comments: image_file.cpp)

  std::vector<std::string> channel_names() const override {
    return channels_ == 1 ? std::vector<std::string>{"Y"} : std::vector<std::string>{"R", "G", "B"};
  }
  std::string read_channels(int begin, int end, float* data) override {
    if (begin != 0 || end != 3) return "PPM and PFM files hold R, G, B only";
    return read_rgb(PixelType::Float, data);
  }
  std::string read_rgb(PixelType type, void* data) override {
    if (channels_ < 3) return "fewer than 3 channels";
    const size_t pixels = size_t(width_) * size_t(height_);
    std::ifstream in(path_, std::ios::binary);
    if (!in || !in.seekg(data_offset_)) return "cannot read the pixels";
    std::vector<float> f(pixels * 3);  // floats: PFM as stored, PPM as value / maxval
    if (pfm_) {
      const size_t row = size_t(width_) * 3 * 4;
      std::vector<unsigned char> bytes(row);
      const bool swap = maxval_or_order_ > 0;  // a positive scale: big-endian (this host is little-endian)
      for (int y = 0; y < height_; ++y) {
        if (!in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(row))) return "file is truncated";
        if (swap)
          for (size_t i = 0; i < row; i += 4) {
            std::swap(bytes[i], bytes[i + 3]);
            std::swap(bytes[i + 1], bytes[i + 2]);
          }
        std::memcpy(&f[size_t(height_ - 1 - y) * width_ * 3], bytes.data(), row);  // bottom row first
      }
    } else {
      const size_t sample = maxval_or_order_ > 255 ? 2 : 1;
      std::vector<unsigned char> bytes(pixels * 3 * sample);
      if (!in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(bytes.size()))) return "file is truncated";
      const bool eight_bit = type == PixelType::UInt8 && maxval_or_order_ == 255;
      if (eight_bit) {
        std::memcpy(data, bytes.data(), bytes.size());
        return "";
      }
      for (size_t i = 0; i < f.size(); ++i) {
        const unsigned v = sample == 2 ? (unsigned(bytes[2 * i]) << 8) | bytes[2 * i + 1] : bytes[i];
        f[i] = float(double(std::min<unsigned>(v, unsigned(maxval_or_order_))) / double(maxval_or_order_));
      }
    }
    if (type == PixelType::Float) {
      std::memcpy(data, f.data(), f.size() * sizeof(float));
    } else {
      auto* out = static_cast<uint8_t*>(data);
      for (size_t i = 0; i < f.size(); ++i) {
        const float v = std::isfinite(f[i]) ? f[i] : 0.f;
        out[i] = uint8_t(std::lround(std::min(1.f, std::max(0.f, v)) * 255.f));
      }
    }
    return "";
  }

 private:
  std::string path_;
  bool pfm_;
  int width_, height_, channels_;
  long maxval_or_order_;  // PPM: maxval; PFM: the scale line's sign (< 0: little-endian)
  std::streamoff data_offset_;
};

std::unique_ptr<Reader> open_pnm(const std::string& path, std::string* error) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    *error = "cannot open the file";
    return nullptr;
  }
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  in.seekg(0);
  PnmHeader header;
  char magic[2] = {0, 0};
  in.read(magic, 2);
  in.seekg(0);
  if (!(magic[0] == 'P' && (magic[1] == '6' || magic[1] == 'F' || magic[1] == 'f'))) {
    *error = std::string("not a binary PPM (P6) or PFM file; ") + kLeanBuildNote + ": it reads .ppm and .pfm only";
    return nullptr;
  }
  if (!parse_pnm_header(in, header, *error)) return nullptr;
  const long w = header.width, h = header.height;
  const int channels = header.channels;
  const size_t sample = header.sample;
  const long third = header.pfm ? (header.scale < 0 ? -1 : 1) : header.maxval;
  const bool pfm = header.pfm;
  const std::streamoff offset = header.pixels;
  // (w, h < 2^27: no overflow in 64 bits.)
  const unsigned long long need = (unsigned long long)w * (unsigned long long)h * unsigned(channels) * sample;
  if ((unsigned long long)(size - offset) < need) {
    *error = "file is truncated (" + std::to_string(size - offset) + " bytes of pixels, the header needs " +
             std::to_string(need) + ")";
    return nullptr;
  }
  return std::make_unique<PnmReader>(path, pfm, int(w), int(h), channels, third, offset);
}

class BuiltinModule final : public Module {
 public:
  bool can_write(const std::string& name) override { return lowercase_extension(name) == "ppm"; }
  bool in_memory(const std::string&) override { return true; }
  std::string encode(const std::string& name, const std::string&, int width, int height, PixelType type,
                     const void* data, const Attributes&, std::string* bytes) override {
    if (!can_write(name)) return std::string(kLeanBuildNote) + ": writes .ppm and .pfm only";
    if (type != PixelType::UInt8) return "PPM holds 8-bit colour";
    // The header's comments (metadata) are inserted by image_file.cpp.
    *bytes = "P6\n" + std::to_string(width) + " " + std::to_string(height) + "\n255\n";
    const size_t n = size_t(width) * size_t(height) * 3;
    bytes->append(static_cast<const char*>(data), n);
    return "";
  }
  std::string encode_channels(const std::string&, const std::string&, int, int, const std::vector<std::string>&,
                              const float*, const Attributes&, std::string*) override {
    return std::string(kLeanBuildNote) + ": no multi-layer EXR (OpenImageIO)";
  }
  std::unique_ptr<Reader> open(const std::string& path, std::string* error) override { return open_pnm(path, error); }
  TextBox text_size(const std::string&, int, const std::string&) override {
    throw UserError(std::string(kLeanBuildNote) + ": no text rendering (OpenImageIO)");
  }
  std::unique_ptr<Canvas> canvas(int, int, const Rgb&) override {
    throw UserError(std::string(kLeanBuildNote) + ": no canvas (OpenImageIO)");
  }
};

}  // namespace

Module& module() {
  static BuiltinModule m;
  return m;
}

void check_module_present() {}

bool module_loaded() {
  return false;  // (there is no module to load: OpenImageIO is never loaded)
}

std::vector<std::string> module_candidates() {
  return {};
}

void set_library_location(const std::string&, const std::string&) {}  // (nothing is looked for)

}  // namespace imageio
}  // namespace clrt
