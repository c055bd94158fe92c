// pnm_header.hpp - the header of a PPM (P6) or PFM (PF, Pf) file, parsed and
// checked: the one place both builds validate these headers (the lean
// build's own reader reads the pixels after it; the full build checks the
// header before OpenImageIO reads the file, which accepts a maxval of 0 - a
// white image - and a PFM scale of NaN or 0).
#pragma once
#include <cstdint>
#include <iosfwd>
#include <string>

namespace clrt {

struct PnmHeader {
  char kind = 0;  // the magic's second character: '2', '3', '5', '6' (PNM with a maxval), 'F', 'f' (PFM)
  bool pfm = false;
  int width = 0, height = 0, channels = 0;
  long maxval = 0;      // PPM: 1 to 65535
  double scale = 0;     // PFM: finite and not 0 (its sign: < 0 little-endian)
  size_t sample = 0;    // bytes per sample: 1 or 2 (PPM), 4 (PFM)
  std::streamoff pixels = 0;  // where the pixels begin
};

// Whether the file's first bytes are the magic of a PNM with a maxval
// ("P2", "P3", "P5", "P6") or of a PFM ("PF", "Pf"): then parse_pnm_header()
// must accept it before it is read.
bool has_pnm_magic(const char magic[2]);

// Parses the header from the start of `in`; false with `error` set ("bad
// maxval in the header (1 to 65535)", ...) for anything but such a header
// with sizes in range. Never reads past the header.
bool parse_pnm_header(std::istream& in, PnmHeader& header, std::string& error);

}  // namespace clrt
