// image_file.cpp - image files through the imaging module (OpenImageIO,
// loaded on first use: image_io.hpp): checked before the work, written
// atomically, read as untrusted input.
#include "image/image_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "image/image_io.hpp"
#include "image/pnm_header.hpp"
#include "util/build_features.hpp"
#include "util/error.hpp"
#include "util/output_file.hpp"

namespace clrt {

namespace {

std::string lower(std::string s) {
  for (auto& ch : s) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return s;
}

// --format's value: "exr", "EXR" and ".exr" name the same format.
std::string format_arg(const std::string& format) {
  return lower(!format.empty() && format[0] == '.' ? format.substr(1) : format);
}

std::string extension_of(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  return ext.empty() ? ext : ext.substr(1);
}

}  // namespace

std::string lowercase_extension(const std::string& path) {
  return lower(extension_of(path));
}

namespace {

// The name whose extension picks the encoder: "out.FORMAT" for --format,
// OUT itself, or "out.png" ("out.ppm" in a lean build) for standard output
// and devices named without an extension (/dev/stdout).
std::string format_name(const std::string& path, OutputKind kind, const std::string& format) {
  if (!format.empty()) return "out." + format;
  const char* unnamed = kLeanBuild ? "out.ppm" : "out.png";
  return extension_of(path).empty() && kind != OutputKind::File ? std::string(unnamed) : path;
}

std::string format_ext(const std::string& path, OutputKind kind, const std::string& format) {
  return lowercase_extension(format_name(path, kind, format));
}

bool is_float_ext(const std::string& ext) {
  return ext == "exr" || ext == "hdr" || ext == "pfm";
}

// Formats whose header clrt writes its metadata into as comment lines
// ("# key=value" after the first line): OpenImageIO's writers keep none.
bool comment_header_ext(const std::string& ext) {
  return ext == "ppm" || ext == "pnm" || ext == "hdr";
}

// The formats to suggest: a lean build writes PPM and PFM only.
constexpr const char* kFormatHint = kLeanBuild ? "use .ppm or .pfm" : "use .png, .ppm, .exr, .pfm, ...";

[[noreturn]] void unknown_format(const std::string& path, const std::string& ext) {
  if (kLeanBuild)
    throw UserError(path + ": unknown image format \"." + ext + "\": " + kLeanBuildNote +
                    ", without OpenImageIO (no PNG, EXR, ...); write .ppm or .pfm");
  throw UserError(path + ": unknown image format \"." + ext + "\" (" + kFormatHint + ")");
}

// UserError unless there is an encoder for OUT (of this kind). The formats
// of written_without_asking() are known without loading the imaging module
// (only its file must be there), PFM is clrt's own; any other extension is
// asked of OpenImageIO, which loads it. (A lean build's module is built in:
// it writes PPM only.)
void check_image_format(const std::string& path, OutputKind kind, const std::string& format) {
  if (format.empty() && extension_of(path).empty() && kind == OutputKind::File)
    throw UserError(path + ": output has no file extension (" + kFormatHint + " or --format)");
  const std::string name = format_name(path, kind, format);
  const std::string ext = lowercase_extension(name);
  if (ext == "pfm") return;
  const auto& known = written_without_asking();
  if (std::find(known.begin(), known.end(), ext) != known.end()) {
    imageio::check_module_present();
    return;
  }
  if (!imageio::module().can_write(name)) unknown_format(path, format.empty() ? extension_of(path) : format);
}

[[noreturn]] void encode_failed(const std::string& path, std::string err) {
  for (auto& c : err)
    if (c == '\n') c = ' ';
  throw UserError(path + ": cannot write output: " + (err.empty() ? std::string("unknown error") : err));
}

// One line, whatever the value held (a scene path may hold a newline).
std::string one_line(std::string s) {
  for (auto& c : s)
    if (c == '\n' || c == '\r' || c == '\0') c = ' ';
  return s;
}

// `metadata` as "# key=value" lines inserted after the header's first line
// (PPM: "P6", HDR: "#?RADIANCE"), where both formats allow comments.
std::string with_header_comments(std::string bytes, const ImageMetadata& metadata) {
  const size_t eol = bytes.find('\n');
  if (eol == std::string::npos || metadata.empty()) return bytes;
  std::string lines;
  for (const auto& [key, value] : metadata) lines += "# " + one_line(key) + "=" + one_line(value) + "\n";
  return bytes.insert(eol + 1, lines);
}

// PFM (OpenImageIO 2.4 reads it but cannot write it): "PF", width height,
// -1 (little-endian floats), then rows bottom to top, RGB float32.
std::string encode_pfm(int w, int h, const std::vector<float>& rgb) {
  static_assert(sizeof(float) == 4, "PFM holds IEEE float32");
  std::string bytes = "PF\n" + std::to_string(w) + " " + std::to_string(h) + "\n-1.0\n";
  const size_t row = size_t(w) * 3 * sizeof(float), header = bytes.size();
  bytes.resize(header + row * size_t(h));
  for (int y = 0; y < h; ++y)  // (this host is little-endian: x86-64, aarch64)
    std::memcpy(&bytes[header + row * size_t(h - 1 - y)], rgb.data() + size_t(y) * w * 3, row);
  return bytes;
}

// Encodes `pixels` (float or uint8 RGB) in memory - or, for the few encoders
// that can only write to a path, in a private scratch file - and returns the
// file's bytes. Nothing is written to OUT here: write_output() does that.
std::string encode(const std::string& path, const std::string& name, int w, int h, imageio::PixelType type,
                   const void* data, const ImageMetadata& metadata) {
  imageio::Module& io = imageio::module();
  std::string bytes;
  if (io.in_memory(name)) {
    const std::string err = io.encode(name, "", w, h, type, data, metadata, &bytes);
    if (!err.empty()) encode_failed(path, err);
    return bytes;
  }
  ScratchFile scratch("out" + std::filesystem::path(name).extension().string());
  const std::string err = io.encode(name, scratch.path(), w, h, type, data, metadata, nullptr);
  if (!err.empty()) encode_failed(path, err);
  return scratch.read();
}

// The bytes of the file `path` (of `kind`) in `format` holding `pixels`.
std::string encode_pixels(const std::string& path, OutputKind kind, const std::string& format, int w, int h,
                          imageio::PixelType type, const void* data, const ImageMetadata& metadata) {
  check_image_format(path, kind, format);
  const std::string name = format_name(path, kind, format);
  const std::string ext = lowercase_extension(name);
  if (ext == "pfm") {
    const size_t n = size_t(w) * h * 3;
    std::vector<float> f(n);
    for (size_t i = 0; i < n; ++i)  // (8-bit data, a --diff image: 255 = 1.0)
      f[i] = type == imageio::PixelType::Float ? static_cast<const float*>(data)[i]
                                               : float(static_cast<const uint8_t*>(data)[i] / 255.0);
    return encode_pfm(w, h, f);
  }
  std::string bytes = encode(path, name, w, h, type, data, metadata);
  if (comment_header_ext(ext)) bytes = with_header_comments(std::move(bytes), metadata);
  return bytes;
}

// (Callers checked OUT before the work with check_output_format();
// write_output() meets any change since.)
void write_pixels(const std::string& path, const std::string& format, int w, int h, imageio::PixelType type,
                  const void* data, const ImageMetadata& metadata) {
  write_output(path, encode_pixels(path, resolve_output(path).kind, format, w, h, type, data, metadata));
}

// What a file of a float format (or not) holds of `img`: the colour tags,
// then the caller's metadata, and the pixels, float (to_unit()) or 8-bit.
struct FilePixels {
  ImageMetadata metadata;
  imageio::PixelType type = imageio::PixelType::UInt8;
  std::vector<float> unit;
  std::vector<uint8_t> u8;
  const void* data() const {
    return type == imageio::PixelType::Float ? static_cast<const void*>(unit.data()) : u8.data();
  }
};

FilePixels file_pixels(const Image& img, bool floating, const ImageMetadata& metadata, const std::string& path) {
  FilePixels px;
  // The colour tags come first; the caller's metadata cannot replace them.
  px.metadata = {{"oiio:ColorSpace", "sRGB"}, {kWhiteKey, floating ? "1" : "255"}};
  for (const auto& kv : metadata)
    if (kv.first != "oiio:ColorSpace" && kv.first != kWhiteKey) px.metadata.push_back({kv.first, one_line(kv.second)});
  if (floating) {
    static_assert(kFloatWhite == 1.0, "to_unit() stores 255 as 1.0");
    px.type = imageio::PixelType::Float;
    if (img.contents.pixels == PixelFormat::Unit) {
      px.unit = img.unit;
    } else {
      if (img.contents.pixels != PixelFormat::Float)
        throw std::logic_error("write_image: " + path + " needs float colour, the frame holds 8-bit");
      px.unit.resize(img.rgb.size());
      for (size_t i = 0; i < px.unit.size(); ++i) px.unit[i] = to_unit(img.rgb[i]);
    }
  } else {
    px.u8 = to_u8(img);
  }
  return px;
}

// The "# key=value" comment lines of a PPM or HDR header (read_metadata).
ImageMetadata header_comments(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string head(65536, '\0');
  in.read(&head[0], std::streamsize(head.size()));
  head.resize(size_t(in.gcount()));
  ImageMetadata out;
  size_t pos = head.find('\n');  // after the magic line
  while (pos != std::string::npos && pos + 1 < head.size()) {
    const size_t eol = head.find('\n', pos + 1);
    if (eol == std::string::npos) break;
    const std::string line = head.substr(pos + 1, eol - pos - 1);
    pos = eol;
    if (line.rfind("# ", 0) != 0) {
      if (line.empty() || std::isdigit(static_cast<unsigned char>(line[0]))) break;  // end of the header
      continue;                                                                      // HDR's FORMAT=..., EXPOSURE=...
    }
    const size_t eq = line.find('=');
    if (eq != std::string::npos) out.emplace_back(line.substr(2, eq - 2), line.substr(eq + 1));
  }
  return out;
}

}  // namespace

const std::vector<std::string>& written_without_asking() {
  static const std::vector<std::string> known =
      kLeanBuild
          ? std::vector<std::string>{"ppm"}
          : std::vector<std::string>{"png", "ppm", "pnm", "exr", "hdr", "jpg", "jpeg", "tif", "tiff", "bmp", "tga"};
  return known;
}

OutputTarget check_output_format(const std::string& path, const std::string& format) {
  const OutputTarget target = check_output(path);
  check_image_format(path, target.kind, format_arg(format));
  return target;
}

PixelFormat output_pixel_format(const std::string& path, const std::string& format) {
  const OutputKind kind = path == "-" ? OutputKind::Stdout : OutputKind::File;
  return is_float_ext(format_ext(path, kind, format_arg(format))) ? PixelFormat::Float : PixelFormat::Rgba8;
}

void check_layers_output(const std::string& path, const std::string& format_in) {
  const OutputKind kind = path == "-" ? OutputKind::Stdout : OutputKind::File;
  const std::string ext = format_ext(path, kind, format_arg(format_in));
  if (ext == "exr") return;
  if (kLeanBuild)
    throw UserError(path + ": --aov writes a multi-layer EXR file, through OpenImageIO, which this build lacks (" +
                    kLeanBuildNote + ")");
  const std::string holds = is_float_ext(ext) ? "float RGB only" : "8-bit colour only";
  throw UserError(path + ": --aov writes its layers into one multi-layer EXR file; ." + ext + " holds " + holds +
                  " (use .exr)");
}

namespace {

// The bytes of a multi-layer EXR of `img`: R, G, B (value / 255, as every
// float file), A = 1 (the background is part of the picture), then the
// layers' channels (layers.hpp), all float32.
std::string layer_file_bytes(const Image& img, const FrameLayers& frame, const std::string& path, OutputKind kind,
                             const ImageMetadata& metadata, const std::string& format) {
  check_layers_output(path, format);
  check_image_format(path, kind, format);
  if (!frame.holds(img.width, img.height, frame.layers))
    throw std::logic_error("write_image: " + path + ": layers of another frame");
  const FilePixels px = file_pixels(img, /*floating=*/true, metadata, path);
  const unsigned layers = frame.layers;
  std::vector<std::string> channels{"R", "G", "B", "A"};
  for (const std::string& name : layer_channels(layers)) channels.push_back(name);
  const size_t stride = channels.size(), n = img.pixels();
  std::vector<float> data(n * stride);
  for (size_t p = 0; p < n; ++p) {
    float* d = &data[p * stride];
    for (int c = 0; c < 3; ++c) d[c] = px.unit[p * 3 + c];
    d[3] = 1.0f;
    size_t k = 4;
    if (layers & kLayerDepth) d[k++] = frame.depth[p];
    if (layers & kLayerNormal)
      for (int c = 0; c < 3; ++c) d[k++] = frame.normal[p * 3 + c];
    if (layers & kLayerAlbedo)
      for (int c = 0; c < 3; ++c) d[k++] = frame.albedo[p * 3 + c];
    if (layers & kLayerId) d[k++] = float(frame.id[p]);  // (exact: ids < kMaxLayerIds)
  }
  const std::string name = format_name(path, kind, format);
  imageio::Module& io = imageio::module();
  std::string bytes;
  std::string err;
  if (io.in_memory(name)) {
    err = io.encode_channels(name, "", img.width, img.height, channels, data.data(), px.metadata, &bytes);
  } else {
    ScratchFile scratch("out.exr");
    err = io.encode_channels(name, scratch.path(), img.width, img.height, channels, data.data(), px.metadata, nullptr);
    if (err.empty()) bytes = scratch.read();
  }
  if (!err.empty()) encode_failed(path, err);
  return bytes;
}

}  // namespace

// An image's file bytes, for write_image() (a file at `path`, of `kind`) and
// encode_image() (a regular file's bytes, in memory).
std::string file_bytes(const Image& img, const FrameLayers* layers, const std::string& path, OutputKind kind,
                       const ImageMetadata& metadata, const std::string& format_in) {
  const std::string format = format_arg(format_in);
  if (layers && layers->layers) return layer_file_bytes(img, *layers, path, kind, metadata, format);
  const bool floating = output_pixel_format(path, format) == PixelFormat::Float;
  const FilePixels px = file_pixels(img, floating, metadata, path);
  return encode_pixels(path, kind, format, img.width, img.height, px.type, px.data(), px.metadata);
}

void write_image(const Image& img, const std::string& path, const ImageMetadata& metadata, const std::string& format) {
  write_output(path, file_bytes(img, nullptr, path, resolve_output(path).kind, metadata, format));
}

void write_image(const Image& img, const FrameLayers& layers, const std::string& path, const ImageMetadata& metadata,
                 const std::string& format) {
  write_output(path, file_bytes(img, &layers, path, resolve_output(path).kind, metadata, format));
}

std::string encode_image(const Image& img, const std::string& path, const ImageMetadata& metadata,
                         const std::string& format) {
  return file_bytes(img, nullptr, path, OutputKind::File, metadata, format);
}

std::string encode_image(const Image& img, const FrameLayers& layers, const std::string& path,
                         const ImageMetadata& metadata, const std::string& format) {
  return file_bytes(img, &layers, path, OutputKind::File, metadata, format);
}

ImageMetadata read_metadata(const std::string& path, const std::vector<std::string>& keys) {
  ImageMetadata out;
  const std::string ext = lowercase_extension(path);
  if (comment_header_ext(ext)) {
    const ImageMetadata all = header_comments(path);
    for (const auto& k : keys)
      for (const auto& kv : all)
        if (kv.first == k) {
          out.push_back(kv);
          break;
        }
    return out;
  }
  std::string err;
  auto in = imageio::module().open(path, &err);
  if (!in) throw UserError(path + ": cannot read image: " + err);
  for (const auto& k : keys) {
    std::string v = in->attribute(k);
    if (!v.empty()) out.emplace_back(k, std::move(v));
  }
  return out;
}

Image read_image(const std::string& path, int max_edge, long long max_pixels) {
  std::string err;
  {
    // PPM and PFM headers are checked here, in both builds (pnm_header.hpp):
    // OpenImageIO reads a maxval of 0 as white and a PFM scale of NaN as is.
    // Only a regular file: opening a FIFO must not block (O_NONBLOCK), and
    // what is not one is the imaging module's to refuse.
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
    struct stat st {};
    std::string head;
    if (fd >= 0 && ::fstat(fd, &st) == 0 && S_ISREG(st.st_mode)) {
      head.resize(64 << 10);  // a header with its comments
      ssize_t n = 0;
      do n = ::read(fd, &head[0], head.size());
      while (n < 0 && errno == EINTR);
      head.resize(n > 0 ? size_t(n) : 0);
    }
    if (fd >= 0) ::close(fd);
    if (head.size() >= 2 && has_pnm_magic(head.data())) {
      std::istringstream file(head);
      PnmHeader header;
      if (!parse_pnm_header(file, header, err)) throw UserError(path + ": cannot read image: " + err);
    }
  }
  auto in = imageio::module().open(path, &err);
  if (!in) throw UserError(path + ": cannot read image: " + err);
  const int w = in->width(), h = in->height(), nch = in->channels();
  if (nch < 3) throw UserError(path + ": cannot read image: " + std::to_string(nch) + " channel(s), need RGB");
  if (w <= 0 || h <= 0 || w > max_edge || h > max_edge || (long long)w * h > max_pixels)
    throw UserError(path + ": image " + std::to_string(w) + "x" + std::to_string(h) + " is too large or empty");
  const bool floating = in->floating();
  // Float files: how much 255 (white) is stored as. The file says so (EXR's
  // clrt:white, clrt's HDR comment); every PFM is clrt's 1.0 = white (no
  // older clrt wrote one); other float files are as stored (older clrt
  // EXR/HDR files hold the 0..255 scale).
  double scale = 1;
  if (floating) {
    const std::string ext = lowercase_extension(path);
    std::string white = in->attribute(kWhiteKey);
    if (white.empty() && comment_header_ext(ext)) {
      const ImageMetadata m = read_metadata(path, {kWhiteKey});
      if (!m.empty()) white = m.front().second;
    }
    char* end = nullptr;
    const double white_value = white.empty() ? 0 : std::strtod(white.c_str(), &end);
    if (!white.empty() && end && *end == '\0' && std::isfinite(white_value) && white_value > 0)
      scale = 255.0 / white_value;
    else if (ext == "pfm")
      scale = 255.0 / kFloatWhite;
  }
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
  for (size_t i = 0; i < img.rgb.size(); ++i) img.rgb[i] = floating ? double(f[i]) * scale : double(u8[i]);
  return img;
}

FrameLayers read_layers(const std::string& path, int width, int height) {
  std::string err;
  auto in = imageio::module().open(path, &err);
  if (!in) throw UserError(path + ": cannot read image: " + err);
  if (in->width() != width || in->height() != height)
    throw UserError(path + ": cannot read layers: the image is " + std::to_string(in->width()) + "x" +
                    std::to_string(in->height()) + ", not " + std::to_string(width) + "x" + std::to_string(height));
  const std::vector<std::string> names = in->channel_names();
  const auto index_of = [&](const std::string& name) {
    const auto it = std::find(names.begin(), names.end(), name);
    return it == names.end() ? -1 : int(it - names.begin());
  };
  unsigned layers = 0;
  for (const std::string& layer : layer_names()) {
    const unsigned bit = layer_bit(layer);
    size_t found = 0;
    const std::vector<std::string> channels = layer_channels(bit);
    for (const std::string& channel : channels) found += index_of(channel) >= 0;
    if (found == channels.size()) layers |= bit;
    else if (found > 0) throw UserError(path + ": layer " + layer + " has only some of its channels");
  }
  FrameLayers out(width, height, layers);
  if (!layers) return out;
  const size_t n = out.pixels(), stride = names.size();
  std::vector<float> all(n * stride);
  err = in->read_channels(0, int(stride), all.data());
  if (!err.empty()) throw UserError(path + ": cannot read layers: " + err);
  // each channel's place among the file's (-1: a layer it lacks)
  const int z = index_of("Z"), id_channel = index_of("id");
  const int xyz[3] = {index_of("N.X"), index_of("N.Y"), index_of("N.Z")};
  const int rgb[3] = {index_of("albedo.R"), index_of("albedo.G"), index_of("albedo.B")};
  for (size_t p = 0; p < n; ++p) {
    const float* pixel = &all[p * stride];
    if (layers & kLayerDepth) out.depth[p] = pixel[z];
    for (int c = 0; c < 3; ++c) {
      if (layers & kLayerNormal) out.normal[p * 3 + c] = pixel[xyz[c]];
      if (layers & kLayerAlbedo) out.albedo[p * 3 + c] = pixel[rgb[c]];
    }
    if (layers & kLayerId) {
      const float id = pixel[id_channel];
      if (!(id >= -1 && id < float(kMaxLayerIds) && id == std::floor(id)))
        throw UserError(path + ": cannot read layers: the id channel holds " + std::to_string(id) +
                        ", not a primitive id");
      out.id[p] = int32_t(id);
    }
  }
  return out;
}

void write_rgb8(const std::vector<uint8_t>& rgb, int width, int height, const std::string& path,
                const ImageMetadata& metadata) {
  ImageMetadata meta{{"oiio:ColorSpace", "sRGB"}};
  for (const auto& kv : metadata) meta.push_back({kv.first, one_line(kv.second)});
  write_pixels(path, "", width, height, imageio::PixelType::UInt8, rgb.data(), meta);
}

}  // namespace clrt
