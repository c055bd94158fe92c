// image_io_oiio.cpp - the imaging module (clrt_imageio.so): image_io.hpp's
// interface on OpenImageIO. Built as a shared module of its own, not into
// clrt_core; it links OpenImageIO and nothing of clrt.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include "image/image_io.hpp"

namespace clrt {
namespace imageio {
namespace {

namespace OIA = OIIO::ImageBufAlgo;

OIIO::TypeDesc oiio_type(PixelType t) {
  return t == PixelType::Float ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8;
}

OIA::TextAlignX oiio_align(AlignX a) {
  return a == AlignX::Right    ? OIA::TextAlignX::Right
         : a == AlignX::Center ? OIA::TextAlignX::Center
                               : OIA::TextAlignX::Left;
}

OIA::TextAlignY oiio_align(AlignY a) {
  switch (a) {
    case AlignY::Top:
      return OIA::TextAlignY::Top;
    case AlignY::Bottom:
      return OIA::TextAlignY::Bottom;
    case AlignY::Center:
      return OIA::TextAlignY::Center;
    default:
      return OIA::TextAlignY::Baseline;
  }
}

std::string or_unknown(std::string err) {
  return err.empty() ? std::string("unknown error") : err;
}

class OiioReader final : public Reader {
 public:
  explicit OiioReader(std::unique_ptr<OIIO::ImageInput> in) : in_(std::move(in)) {}
  int width() const override { return in_->spec().width; }
  int height() const override { return in_->spec().height; }
  int channels() const override { return in_->spec().nchannels; }
  bool floating() const override { return in_->spec().format.is_floating_point(); }
  std::string attribute(const std::string& name) const override {
    const OIIO::ParamValue* p = in_->spec().find_attribute(name, OIIO::TypeDesc::STRING);
    return p ? std::string(p->get_string()) : std::string();
  }
  std::string read_rgb(PixelType type, void* data) override {
    if (in_->read_image(0, 0, 0, 3, oiio_type(type), data)) return "";
    return or_unknown(in_->geterror());
  }
  std::vector<std::string> channel_names() const override {
    const auto& names = in_->spec().channelnames;
    return std::vector<std::string>(names.begin(), names.end());
  }
  std::string read_channels(int begin, int end, float* data) override {
    if (begin < 0 || end > channels() || begin >= end) return "no channels " + std::to_string(begin) + ".." + std::to_string(end);
    if (in_->read_image(0, 0, begin, end, OIIO::TypeDesc::FLOAT, data)) return "";
    return or_unknown(in_->geterror());
  }

 private:
  std::unique_ptr<OIIO::ImageInput> in_;
};

class OiioCanvas final : public Canvas {
 public:
  OiioCanvas(int w, int h, const Rgb& background) : img_(OIIO::ImageSpec(w, h, 3, OIIO::TypeDesc::FLOAT)) {
    OIA::fill(img_, background);
  }
  void line(int x0, int y0, int x1, int y1, const Rgb& c) override { OIA::render_line(img_, x0, y0, x1, y1, c); }
  void box(int x0, int y0, int x1, int y1, const Rgb& c, bool fill) override {
    OIA::render_box(img_, x0, y0, x1, y1, c, fill);
  }
  void text(int x, int y, const std::string& s, int size, const std::string& font, const Rgb& c, AlignX ax,
            AlignY ay) override {
    OIA::render_text(img_, x, y, s, size, font, c, oiio_align(ax), oiio_align(ay));
  }
  void vertical_text(int cx, int cy, const std::string& s, int size, const std::string& font, const Rgb& c) override {
    OIIO::ROI r = OIA::text_size(s, size, font);
    if (!r.defined()) return;
    OIIO::ImageBuf tmp(OIIO::ImageSpec(r.width() + 4, r.height() + 4, 3, OIIO::TypeDesc::FLOAT));
    OIA::fill(tmp, Rgb{1, 1, 1});
    OIA::render_text(tmp, 2 - r.xbegin, 2 - r.ybegin, s, size, font, c);
    OIIO::ImageBuf rot = OIA::rotate270(tmp);
    OIIO::ROI rr = rot.roi();
    OIA::paste(img_, cx - rr.width() / 2, cy - rr.height() / 2, 0, 0, rot);
  }
  std::vector<uint8_t> rgb8() const override {
    const OIIO::ROI roi = img_.roi();
    std::vector<uint8_t> out(size_t(roi.width()) * roi.height() * 3);
    img_.get_pixels(roi, OIIO::TypeDesc::UINT8, out.data());
    return out;
  }

 private:
  OIIO::ImageBuf img_;
};

class OiioModule final : public Module {
 public:
  bool can_write(const std::string& name) override {
    if (OIIO::ImageOutput::create(name)) return true;
    (void)OIIO::geterror();
    return false;
  }

  bool in_memory(const std::string& name) override {
    auto out = OIIO::ImageOutput::create(name);
    if (!out) (void)OIIO::geterror();
    return out && out->supports("ioproxy");
  }

  std::string encode(const std::string& name, const std::string& file, int w, int h, PixelType type, const void* data,
                     const Attributes& attributes, std::string* bytes) override {
    OIIO::ImageSpec spec(w, h, 3, oiio_type(type));
    for (const auto& [key, value] : attributes) spec.attribute(key, value);
    return write(name, file, spec, oiio_type(type), data, bytes);
  }

  std::string encode_channels(const std::string& name, const std::string& file, int w, int h,
                              const std::vector<std::string>& channels, const float* data,
                              const Attributes& attributes, std::string* bytes) override {
    OIIO::ImageSpec spec(w, h, int(channels.size()), OIIO::TypeDesc::FLOAT);
    spec.channelnames.assign(channels.begin(), channels.end());
    spec.alpha_channel = spec.z_channel = -1;  // (named below where the file has one)
    for (size_t c = 0; c < channels.size(); ++c) {
      if (channels[c] == "A") spec.alpha_channel = int(c);
      if (channels[c] == "Z") spec.z_channel = int(c);
    }
    for (const auto& [key, value] : attributes) spec.attribute(key, value);
    return write(name, file, spec, OIIO::TypeDesc::FLOAT, data, bytes);
  }

  // Writes `data` as `spec` says into *bytes (file empty) or `file`.
  static std::string write(const std::string& name, const std::string& file, const OIIO::ImageSpec& spec,
                           OIIO::TypeDesc type, const void* data, std::string* bytes) {
    std::vector<unsigned char> buf;
    OIIO::Filesystem::IOVecOutput memory(buf);
    auto out = file.empty() ? OIIO::ImageOutput::create(name, &memory) : OIIO::ImageOutput::create(name);
    if (!out) return or_unknown(OIIO::geterror());
    const std::string& target = file.empty() ? name : file;
    if (!(out->open(target, spec) && out->write_image(type, data) && out->close()))
      return or_unknown(out->geterror());
    if (file.empty()) bytes->assign(buf.begin(), buf.end());
    return "";
  }

  std::unique_ptr<Reader> open(const std::string& path, std::string* error) override {
    auto in = OIIO::ImageInput::open(path);
    if (!in) {
      *error = or_unknown(OIIO::geterror());
      return nullptr;
    }
    return std::make_unique<OiioReader>(std::move(in));
  }

  TextBox text_size(const std::string& s, int size, const std::string& font) override {
    const OIIO::ROI r = OIA::text_size(s, size, font);
    if (!r.defined()) {
      (void)OIIO::geterror();
      return {};
    }
    return {true, r.xbegin, r.ybegin, r.width(), r.height()};
  }

  std::unique_ptr<Canvas> canvas(int w, int h, const Rgb& background) override {
    return std::make_unique<OiioCanvas>(w, h, background);
  }
};

}  // namespace
}  // namespace imageio
}  // namespace clrt

extern "C" __attribute__((visibility("default"))) clrt::imageio::Module* clrt_imageio(int abi) {
  static clrt::imageio::OiioModule m;
  return abi == clrt::imageio::kImageIoAbi ? &m : nullptr;
}
