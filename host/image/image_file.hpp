// image_file.hpp - image files (png, ppm, exr, ... through OpenImageIO, in
// the imaging module loaded on first use: image_io.hpp): the output checked
// before the work, written atomically, and read back.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "image/image.hpp"
#include "util/output_file.hpp"

namespace clrt {

// Checks, before rendering, that OUT can be written: a non-empty path whose
// extension OpenImageIO can write, in an existing directory that accepts new
// files, and not itself a directory (output_file.hpp: check_output). Throws
// UserError naming OUT otherwise; returns what OUT is (file, device, stdout).
// The extensions of written_without_asking() load nothing (the imaging
// module need only be present); any other asks OpenImageIO, loading it.
OutputTarget check_output_format(const std::string& path);
// The extensions, lower case, that check_output_format() accepts without
// loading OpenImageIO (a test checks that it writes each).
const std::vector<std::string>& written_without_asking();
// The colour OUT needs: Float for float formats (exr, hdr, pfm), else
// Rgba8 (render asks the kernel for exactly this).
PixelFormat output_pixel_format(const std::string& path);
// Writes via a temporary file in the same directory and an atomic rename, so
// a failed write never leaves a half-written OUT. EXR (and other float
// formats) get the unclamped float colour (an Rgba8 frame is a logic_error
// there); the rest get 8-bit values (Rgba8 frames as they are).
void write_image(const Image& img, const std::string& path);
// Reads the first three channels of an image file (untrusted input): float
// formats as stored, integer formats as 8-bit values 0..255. hit/shadowed are
// unknown (-1 / 0). UserError naming the file when it cannot be read, has
// fewer than 3 channels, or is larger than max_edge per edge or max_pixels.
Image read_image(const std::string& path, int max_edge, long long max_pixels);
// Writes an 8-bit RGB buffer the same way.
void write_rgb8(const std::vector<uint8_t>& rgb, int width, int height, const std::string& path);

}  // namespace clrt
