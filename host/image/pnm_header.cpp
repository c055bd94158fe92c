// pnm_header.cpp - PPM (P6) and PFM headers, parsed and checked
// (pnm_header.hpp).
#include "image/pnm_header.hpp"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <istream>
#include <limits>

namespace clrt {
namespace {

// The header's tokens: whitespace-separated, '#' comments to the end of a
// line skipped (PPM; PFM files have none, a '#' there is refused as a number).
class HeaderTokens {
 public:
  explicit HeaderTokens(std::istream& in) : in_(in) {}
  // The next token; "" at the end of the file or for one over 64 characters.
  std::string next() {
    int c = in_.get();
    while (c != EOF && (std::isspace(c) || c == '#')) {
      if (c == '#')
        while (c != EOF && c != '\n') c = in_.get();
      c = in_.get();
    }
    std::string t;
    while (c != EOF && !std::isspace(c)) {
      if (t.size() == 64) return "";
      t += char(c);
      c = in_.get();
    }
    // The one whitespace character after a token is consumed with it (after
    // the header's last token, the pixels begin); a token the file ends in
    // is no header.
    return c == EOF ? std::string() : t;
  }

 private:
  std::istream& in_;
};

bool parse_int(const std::string& t, long lo, long hi, long* out) {
  if (t.empty() || t.size() > 10 || t.find_first_not_of("0123456789") != std::string::npos) return false;
  const long v = std::stol(t);
  if (v < lo || v > hi) return false;
  *out = v;
  return true;
}

}  // namespace

bool has_pnm_magic(const char magic[2]) {
  return magic[0] == 'P' && (magic[1] == '2' || magic[1] == '3' || magic[1] == '5' || magic[1] == '6' ||
                             magic[1] == 'F' || magic[1] == 'f');
}

bool parse_pnm_header(std::istream& in, PnmHeader& header, std::string& error) {
  char magic[2] = {0, 0};
  in.read(magic, 2);
  if (!in || !has_pnm_magic(magic)) {
    error = "not a PPM or PFM file";
    return false;
  }
  header.kind = magic[1];
  header.pfm = magic[1] == 'F' || magic[1] == 'f';
  const bool ppm = !header.pfm;
  HeaderTokens tokens(in);
  long w = 0, h = 0;
  constexpr long kMaxEdge = std::numeric_limits<int>::max() / 16;
  if (!parse_int(tokens.next(), 1, kMaxEdge, &w) || !parse_int(tokens.next(), 1, kMaxEdge, &h)) {
    error = "bad width or height in the header";
    return false;
  }
  header.width = int(w), header.height = int(h);
  header.channels = magic[1] == '3' || magic[1] == '6' || magic[1] == 'F' ? 3 : 1;
  if (ppm) {
    if (!parse_int(tokens.next(), 1, 65535, &header.maxval)) {
      error = "bad maxval in the header (1 to 65535)";
      return false;
    }
    header.sample = header.maxval > 255 ? 2 : 1;
  } else {
    const std::string t = tokens.next();
    char* end = nullptr;
    header.scale = t.empty() ? 0 : std::strtod(t.c_str(), &end);
    if (t.empty() || !end || *end != '\0' || !std::isfinite(header.scale) || header.scale == 0) {
      error = "bad scale in the header (a finite number other than 0)";
      return false;
    }
    header.sample = 4;
  }
  header.pixels = in.tellg();
  if (!in || header.pixels < 0) {
    error = "truncated header";
    return false;
  }
  return true;
}

}  // namespace clrt
