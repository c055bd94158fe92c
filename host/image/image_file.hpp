// image_file.hpp - image files (png, ppm, exr, ... through OpenImageIO, in
// the imaging module loaded on first use: image_io.hpp): the output checked
// before the work, written atomically, and read back.
#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "image/image.hpp"
#include "image/layers.hpp"
#include "util/output_file.hpp"

namespace clrt {

// What an image file says about itself: (key, value) string attributes,
// e.g. {"clrt:scene", "scenes/cgfs-demo.json"}. write_image() stores them
// where the format has a place for them (docs/guide/images.md).
using ImageMetadata = std::vector<std::pair<std::string, std::string>>;

// The colour convention of the files clrt writes (docs/guide/images.md):
// the book's colours are display values (sRGB-encoded, as a canvas shows
// them), never linear light. 8-bit formats hold them as they are (canvas
// rule); float formats hold value / 255, so 1.0 is white, tagged sRGB
// (oiio:ColorSpace) and with kWhiteKey = "1" (8-bit: "255").
constexpr const char* kWhiteKey = "clrt:white";
constexpr double kFloatWhite = 1.0;

// `format` below: an extension ("png", "exr", "pfm", ...) that picks the
// encoder instead of OUT's own (render --format); "" = OUT's extension, or
// PNG for standard output and devices named without one (PPM in a lean
// build, CLRT_LEAN=ON, which writes and reads PPM and PFM only: its imaging
// module is image_io_builtin.cpp, and any other format is a UserError).

// Checks, before rendering, that OUT can be written: a non-empty path whose
// extension (or `format`) clrt can write, in an existing directory that
// accepts new files, and not itself a directory (output_file.hpp:
// check_output). Throws UserError naming OUT otherwise; returns what OUT is
// (file, device, stdout). The extensions of written_without_asking() (and
// pfm, which clrt writes itself) load nothing (the imaging module need only
// be present); any other asks OpenImageIO, loading it.
OutputTarget check_output_format(const std::string& path, const std::string& format = "");
// The extensions, lower case, that check_output_format() accepts without
// loading OpenImageIO (a test checks that it writes each).
const std::vector<std::string>& written_without_asking();
// The colour OUT needs: Float for float formats (exr, hdr, pfm), else
// Rgba8 (render asks the kernel for exactly this).
PixelFormat output_pixel_format(const std::string& path, const std::string& format = "");
// UserError unless OUT (or `format`) is an EXR file, the one format that
// holds AOV layers (image/layers.hpp): 8-bit formats, HDR and PFM hold
// colour only, and a lean build writes no EXR. render --aov checks this
// before rendering.
void check_layers_output(const std::string& path, const std::string& format = "");
// Writes via a temporary file in the same directory and an atomic rename, so
// a failed write never leaves a half-written OUT. Float formats get the
// unclamped float colour / 255 (an Rgba8 frame is a logic_error there); the
// rest get 8-bit values (Rgba8 frames as they are). `metadata` goes into the
// file with the colour tags above: as attributes (PNG text chunks, EXR
// header; TIFF, JPEG and TGA keep Software and ImageDescription), as header
// comments in PPM and HDR (`# key=value`); BMP and PFM have no place for it.
void write_image(const Image& img, const std::string& path, const ImageMetadata& metadata = {},
                 const std::string& format = "");
// The same with the frame's AOV layers (layers.layers not 0): one
// multi-layer EXR, R, G, B, A (1), then the layers' channels
// (layer_channels()), all float32; any other format is
// check_layers_output()'s UserError.
void write_image(const Image& img, const FrameLayers& layers, const std::string& path,
                 const ImageMetadata& metadata = {}, const std::string& format = "");
// The bytes write_image() would write to the regular file `path`, made
// without touching the file system (`path` picks the format unless `format`
// does, and names the file in messages): for a rank of an MPI job that
// encodes the frames it renders, which rank 0 then writes with
// write_output(), and the Python module's images as a notebook shows them
// (PNG). UserError for a format clrt cannot write.
std::string encode_image(const Image& img, const std::string& path, const ImageMetadata& metadata = {},
                         const std::string& format = "");
std::string encode_image(const Image& img, const FrameLayers& layers, const std::string& path,
                         const ImageMetadata& metadata = {}, const std::string& format = "");
// Reads the first three channels of an image file (untrusted input) on the
// book's 0..255 scale: integer formats as 8-bit values; float formats x 255
// where the file says 1.0 is white (clrt:white in EXR, clrt's comment in
// HDR, and every PFM), else as stored (EXR and HDR written by clrt before
// 1.0 meant white, on the 0..255 scale). hit/shadowed are unknown (-1 / 0).
// UserError naming the file when it cannot be read, has fewer than 3
// channels, or is larger than max_edge per edge or max_pixels.
Image read_image(const std::string& path, int max_edge, long long max_pixels);
// The AOV layers of an image file that clrt render --aov wrote (untrusted
// input): the layers whose channels (layer_channels()) it has, every one of
// a layer's channels or none; a layers.layers of 0 when it has none. The
// id channel must hold integers >= -1. UserError naming the file otherwise,
// and for a size other than width x height.
FrameLayers read_layers(const std::string& path, int width, int height);
// The extension of `path`'s file name, lowercase, without the dot ("" for
// none): what picks an image's or a plot's format.
std::string lowercase_extension(const std::string& path);

// A file's metadata as read_image() sees it: the string attributes `keys`
// that it has (PPM and HDR comments included), in that order.
ImageMetadata read_metadata(const std::string& path, const std::vector<std::string>& keys);
// Writes an 8-bit RGB buffer the same way.
void write_rgb8(const std::vector<uint8_t>& rgb, int width, int height, const std::string& path,
                const ImageMetadata& metadata = {});

}  // namespace clrt
