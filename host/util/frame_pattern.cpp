// frame_pattern.cpp - frame_####.png -> frame_0000.png, ...
#include "util/frame_pattern.hpp"

#include "util/error.hpp"

namespace clrt {

FramePattern parse_frame_pattern(const std::string& out) {
  const size_t slash = out.rfind('/');
  const size_t name = slash == std::string::npos ? 0 : slash + 1;
  FramePattern p;
  size_t begin = std::string::npos, end = 0;
  int runs = 0;
  for (size_t i = name; i < out.size(); ++i) {
    if (out[i] != '#') continue;
    if (i == name || out[i - 1] != '#') ++runs, begin = i;
    end = i + 1;
    if (runs > 1)
      throw UserError(out + ": the file name has more than one run of '#' (a frame pattern has one: frame_####.png)");
  }
  if (runs == 0) {
    p.prefix = out;
    return p;
  }
  p.prefix = out.substr(0, begin);
  p.suffix = out.substr(end);
  p.digits = int(end - begin);
  return p;
}

std::string frame_path(const FramePattern& p, int index) {
  if (!p.has_run()) return p.prefix;
  std::string digits = std::to_string(index);
  if (int(digits.size()) < p.digits) digits.insert(0, size_t(p.digits) - digits.size(), '0');
  return p.prefix + digits + p.suffix;
}

std::vector<std::string> frame_paths(const std::string& out, int frames) {
  const FramePattern p = parse_frame_pattern(out);
  if (!p.has_run() && frames > 1)
    throw UserError(out + ": " + std::to_string(frames) +
                    " scenes need an output pattern with a run of '#' in its file name for the frame number "
                    "(frame_####.png)");
  std::vector<std::string> paths;
  paths.reserve(size_t(frames > 0 ? frames : 0));
  for (int i = 0; i < frames; ++i) paths.push_back(frame_path(p, i));
  return paths;
}

}  // namespace clrt
