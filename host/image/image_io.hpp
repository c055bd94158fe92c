// image_io.hpp - the imaging module: every call into OpenImageIO goes through
// this narrow interface to a shared module (clrt_imageio.so, built beside the
// clrt binary from image_io_oiio.cpp) that is loaded with dlopen on first use.
// OpenImageIO brings some 250 shared libraries (OpenCV, FFmpeg, Boost, ...);
// a command that writes no image never maps one of them.
//
// Only image_file.cpp and plot.cpp (and tests) use this header; everything
// else calls their functions. The interface is C++ (virtual classes, std
// types): the module is built by the same build as the binary that loads
// it, and kImageIoAbi, checked when the module is loaded, changes with any
// change here.
#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace clrt {
namespace imageio {

// Bump on every change to the classes below: a module of another version
// then refuses to load ("not a clrt imaging module of this build") instead
// of crashing.
constexpr int kImageIoAbi = 3;
// The module's one exported function, `extern "C" Module* clrt_imageio(int
// abi)`: its module, or null when `abi` is not the module's kImageIoAbi.
constexpr const char* kImageIoEntry = "clrt_imageio";

enum class PixelType { UInt8, Float };
enum class AlignX { Left, Right, Center };
enum class AlignY { Baseline, Top, Bottom, Center };
using Rgb = std::array<float, 3>;
// String attributes written into a file (OpenImageIO ImageSpec attributes:
// PNG text chunks, EXR header attributes, TIFF/JPEG tags where the format
// has them; a format without a place for one drops it).
using Attributes = std::vector<std::pair<std::string, std::string>>;

// The box a text would cover, relative to its origin; defined=false when
// the font cannot render it.
struct TextBox {
  bool defined = false;
  int xbegin = 0, ybegin = 0, width = 0, height = 0;
};

// An open image file being read.
class Reader {
 public:
  virtual ~Reader() = default;
  virtual int width() const = 0;
  virtual int height() const = 0;
  virtual int channels() const = 0;
  virtual bool floating() const = 0;  // stored as floating point
  // The string attribute `name` of the file ("" when it has none).
  virtual std::string attribute(const std::string& name) const = 0;
  // Reads the first three channels, width*height*3 values of `type`, into
  // `data`. Returns "" or the error.
  virtual std::string read_rgb(PixelType type, void* data) = 0;
  // The channels' names, in the file's order ("R", "G", "B", "Z", ...).
  virtual std::vector<std::string> channel_names() const = 0;
  // Reads channels [begin, end) as float, width*height*(end - begin) values
  // interleaved, into `data`. Returns "" or the error.
  virtual std::string read_channels(int begin, int end, float* data) = 0;
};

// An RGB float picture being drawn (charts), row 0 at the top.
class Canvas {
 public:
  virtual ~Canvas() = default;
  virtual void line(int x0, int y0, int x1, int y1, const Rgb& c) = 0;
  virtual void box(int x0, int y0, int x1, int y1, const Rgb& c, bool fill) = 0;
  virtual void text(int x, int y, const std::string& s, int size, const std::string& font, const Rgb& c, AlignX ax,
                    AlignY ay) = 0;
  // Text turned 90 degrees counter-clockwise on a white box, centred on (cx, cy).
  virtual void vertical_text(int cx, int cy, const std::string& s, int size, const std::string& font, const Rgb& c) = 0;
  // The picture as 8-bit RGB, width*height*3.
  virtual std::vector<uint8_t> rgb8() const = 0;
};

class Module {
 public:
  // Whether there is an encoder for a file named `name` (by its extension).
  virtual bool can_write(const std::string& name) = 0;
  // Encodes width x height RGB `data` of `type` as the format of `name`,
  // with `attributes`: into *bytes when `file` is empty, else into `file`
  // (for the encoders that can only write to a path: in_memory() is false).
  // Returns "" or the error.
  virtual bool in_memory(const std::string& name) = 0;
  virtual std::string encode(const std::string& name, const std::string& file, int width, int height, PixelType type,
                             const void* data, const Attributes& attributes, std::string* bytes) = 0;
  // The same for float pixels of any number of channels, named `channels`
  // (data: width*height*channels.size() floats, interleaved): a multi-layer
  // EXR, whose readers group "albedo.R", "albedo.G", ... into a layer.
  virtual std::string encode_channels(const std::string& name, const std::string& file, int width, int height,
                                      const std::vector<std::string>& channels, const float* data,
                                      const Attributes& attributes, std::string* bytes) = 0;
  // Opens an image file; null with *error set when it cannot be read.
  virtual std::unique_ptr<Reader> open(const std::string& path, std::string* error) = 0;
  virtual TextBox text_size(const std::string& s, int size, const std::string& font) = 0;
  virtual std::unique_ptr<Canvas> canvas(int width, int height, const Rgb& background) = 0;

 protected:
  ~Module() = default;  // the module's own, never deleted by a caller
};

// The module, loaded on the first call (thread-safe). Throws UserError
// ("clrt: error: ... imaging module ...") when it cannot be found or loaded;
// every later call throws the same.
Module& module();
// Throws that UserError now, without loading anything, when the module
// cannot be found (a missing file): commands check it before their work.
void check_module_present();
// Whether module() has loaded the module in this process.
bool module_loaded();
// Where the module is looked for, in order: $CLRT_IMAGEIO_MODULE (a path;
// when set, the only place), beside the running executable
// (/proc/self/exe), where `cmake --install` puts it relative to the
// executable (CLRT_IMAGEIO_FROM_BIN, e.g. ../lib/clrt), and the build
// directory this binary was built in (only for a binary inside it). In a
// shared library that set_library_location() named, the library's places
// instead of the executable's.
std::vector<std::string> module_candidates();
// Code of clrt's that runs in a shared library of another program (the
// Python module, python/: the executable is python3) names the library's
// folder (absolute, as the library found it) and where `cmake --install`
// puts the module relative to that folder (CLRT_IMAGEIO_FROM_PYTHON, e.g.
// ../../../clrt). The module is then looked for at that relative place and,
// for a library inside the build directory, in the build directory, never
// beside the executable (another program's folder). Call it before the
// first image is read or written.
void set_library_location(const std::string& library_dir, const std::string& module_from_library);

}  // namespace imageio
}  // namespace clrt
